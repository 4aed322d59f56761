//! Minimal SVG plots (time series and x-y paths with shaded bands, and
//! horizontal bar charts), written by hand: a plotting crate (plotters)
//! would bring fonts and backends for what is a few lines of text output
//! here.

use std::fmt::Write as _;

mod bars;
mod ticks;
pub use bars::bars;
use ticks::ticks;

/// One named line.
pub struct Series<'a> {
    /// Legend text.
    pub name: &'a str,
    /// Points (x, y).
    pub points: Vec<(f64, f64)>,
}

const COLORS: [&str; 6] = [
    "#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf",
];

/// An SVG document with the series drawn over common axes.
///
/// ```
/// use dynamics_cli::plot::{svg, Series};
/// let s = svg("sine", "t [s]", "y", &[Series { name: "y", points: (0..50).map(|i| (i as f64 * 0.1, (i as f64 * 0.1).sin())).collect() }], false);
/// assert!(s.starts_with("<svg") && s.contains("<polyline"));
/// ```
pub fn svg(title: &str, xlabel: &str, ylabel: &str, series: &[Series], equal_axes: bool) -> String {
    svg_shaded(title, xlabel, ylabel, series, &[], equal_axes)
}

/// A shaded band behind the lines: `x` and `y` ranges (`None`: the whole
/// plot along that axis), labelled at its top left.
pub struct Shade<'a> {
    /// From and to along x.
    pub x: Option<(f64, f64)>,
    /// From and to along y.
    pub y: Option<(f64, f64)>,
    /// Label (may be empty).
    pub label: &'a str,
}

/// [`svg`] with shaded bands behind the lines (time windows, a noise band);
/// the y range covers the bands' finite y limits.
///
/// ```
/// use dynamics_cli::plot::{svg_shaded, Series, Shade};
/// let line = Series { name: "r", points: vec![(0.0, 0.0), (1.0, 2.0)] };
/// let s = svg_shaded("r", "t [s]", "r", &[line], &[
///     Shade { x: Some((0.2, 0.4)), y: None, label: "hold" },
///     Shade { x: None, y: Some((-3.0, 3.0)), label: "noise" },
/// ], false);
/// assert_eq!(s.matches("<rect").count(), 2 + 2);
/// assert!(s.contains(">hold</text>"));
/// ```
pub fn svg_shaded(
    title: &str,
    xlabel: &str,
    ylabel: &str,
    series: &[Series],
    shades: &[Shade],
    equal_axes: bool,
) -> String {
    let (w, h, m) = (720.0, 420.0, 60.0);
    let shade_y = shades
        .iter()
        .filter_map(|s| s.y)
        .flat_map(|(a, b)| [a, b])
        .filter(|v| v.is_finite());
    let first_x = series
        .iter()
        .flat_map(|s| s.points.first())
        .map(|p| p.0)
        .find(|x| x.is_finite())
        .unwrap_or(0.0);
    let pts = series
        .iter()
        .flat_map(|s| s.points.iter().copied())
        .chain(shade_y.map(|y| (first_x, y)))
        .filter(|p| p.0.is_finite() && p.1.is_finite());
    let (mut x0, mut x1, mut y0, mut y1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for (x, y) in pts {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    if !x0.is_finite() {
        (x0, x1, y0, y1) = (0.0, 1.0, 0.0, 1.0);
    }
    if x1 - x0 < 1e-12 {
        x1 = x0 + 1.0;
    }
    if y1 - y0 < 1e-12 {
        (y0, y1) = (y0 - 0.5, y1 + 0.5);
    }
    let pad = 0.05 * (y1 - y0);
    (y0, y1) = (y0 - pad, y1 + pad);
    let (pw, ph) = (w - 2.0 * m, h - 2.0 * m);
    let (mut sx, mut sy) = (pw / (x1 - x0), ph / (y1 - y0));
    if equal_axes {
        // One scale for both axes, the data centred in the wider range.
        let s = sx.min(sy);
        let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
        (x0, x1) = (cx - 0.5 * pw / s, cx + 0.5 * pw / s);
        (y0, y1) = (cy - 0.5 * ph / s, cy + 0.5 * ph / s);
        (sx, sy) = (s, s);
    }
    let px = |x: f64| m + (x - x0) * sx;
    let py = |y: f64| h - m - (y - y0) * sy;
    let mut out = String::new();
    let _ = write!(out, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" font-family=\"sans-serif\" font-size=\"12\">");
    let _ = write!(out, "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>");
    let _ = write!(
        out,
        "<text x=\"{}\" y=\"24\" text-anchor=\"middle\" font-size=\"15\">{}</text>",
        w / 2.0,
        esc(title)
    );
    let _ = write!(
        out,
        "<rect x=\"{m}\" y=\"{m}\" width=\"{pw}\" height=\"{ph}\" fill=\"none\" stroke=\"#888\"/>"
    );
    // Labels go on the first row where they do not overlap another.
    let mut rows: Vec<f64> = Vec::new();
    for sh in shades {
        let (xa, xb) = sh.x.unwrap_or((x0, x1));
        let (ya, yb) = sh.y.unwrap_or((y0, y1));
        if ![xa, xb, ya, yb].iter().all(|v| v.is_finite()) {
            continue;
        }
        let (xa, xb) = (px(xa.clamp(x0, x1)), px(xb.clamp(x0, x1)));
        let (ya, yb) = (py(ya.clamp(y0, y1)), py(yb.clamp(y0, y1)));
        let fill = if sh.x.is_some() { "#ff7f0e" } else { "#888888" };
        let _ = write!(
            out,
            "<rect x=\"{:.2}\" y=\"{:.2}\" width=\"{:.2}\" height=\"{:.2}\" fill=\"{fill}\" fill-opacity=\"0.18\"/>",
            xa.min(xb),
            ya.min(yb),
            (xb - xa).abs(),
            (yb - ya).abs()
        );
        if !sh.label.is_empty() {
            let x = xa.min(xb) + 2.0;
            let row = rows.iter().position(|&end| end < x).unwrap_or(rows.len());
            let end = x + 6.0 * sh.label.chars().count() as f64;
            match rows.get_mut(row) {
                Some(r) => *r = end,
                None => rows.push(end),
            }
            let _ = write!(
                out,
                "<text x=\"{x:.2}\" y=\"{:.2}\" font-size=\"10\" fill=\"#555\">{}</text>",
                ya.min(yb) + 11.0 + 11.0 * row as f64,
                esc(sh.label)
            );
        }
    }
    // Round ticks with light grid lines across the plot.
    for (fx, text) in ticks(x0, x1) {
        let x = px(fx);
        let _ = write!(
            out,
            "<line x1=\"{x:.1}\" y1=\"{m}\" x2=\"{x:.1}\" y2=\"{}\" stroke=\"#ddd\"/><text x=\"{x:.1}\" y=\"{:.1}\" text-anchor=\"middle\">{text}</text>",
            h - m,
            h - m + 16.0,
        );
    }
    for (fy, text) in ticks(y0, y1) {
        let y = py(fy);
        let _ = write!(
            out,
            "<line x1=\"{m}\" y1=\"{y:.1}\" x2=\"{}\" y2=\"{y:.1}\" stroke=\"#ddd\"/><text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"end\">{text}</text>",
            w - m,
            m - 6.0,
            y + 4.0,
        );
    }
    let _ = write!(
        out,
        "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>",
        w / 2.0,
        h - 14.0,
        esc(xlabel)
    );
    let _ = write!(
        out,
        "<text x=\"16\" y=\"{}\" transform=\"rotate(-90 16 {})\" text-anchor=\"middle\">{}</text>",
        h / 2.0,
        h / 2.0,
        esc(ylabel)
    );
    for (i, s) in series.iter().enumerate() {
        let color = COLORS[i % COLORS.len()];
        let line: Vec<String> = s
            .points
            .iter()
            .filter(|p| p.0.is_finite() && p.1.is_finite())
            .map(|&(x, y)| format!("{:.2},{:.2}", px(x), py(y)))
            .collect();
        let _ = write!(
            out,
            "<polyline fill=\"none\" stroke=\"{color}\" stroke-width=\"1.5\" points=\"{}\"/>",
            line.join(" ")
        );
        let ly = m + 16.0 + 16.0 * i as f64;
        let _ = write!(out, "<line x1=\"{}\" y1=\"{ly}\" x2=\"{}\" y2=\"{ly}\" stroke=\"{color}\" stroke-width=\"2\"/>", w - m - 110.0, w - m - 90.0);
        let _ = write!(
            out,
            "<text x=\"{}\" y=\"{}\">{}</text>",
            w - m - 85.0,
            ly + 4.0,
            esc(s.name)
        );
    }
    out.push_str("</svg>\n");
    out
}

/// Plots (each a whole SVG document of [`svg`] or [`svg_shaded`], 720 x
/// 420) stacked one under the other in one SVG document.
///
/// ```
/// use dynamics_cli::plot::{stack, svg, Series};
/// let one = svg("a", "t", "y", &[Series { name: "y", points: vec![(0.0, 1.0), (1.0, 2.0)] }], false);
/// let s = stack(&[one.clone(), one]);
/// assert!(s.contains("height=\"840\"") && s.matches("<polyline").count() == 2);
/// ```
pub fn stack(plots: &[String]) -> String {
    let (w, h) = (720.0, 420.0);
    let mut out = String::new();
    let _ = write!(
        out,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{}\">",
        h * plots.len() as f64
    );
    for (k, p) in plots.iter().enumerate() {
        out.push_str(
            &p.trim_end()
                .replacen("<svg ", &format!("<svg y=\"{}\" ", h * k as f64), 1),
        );
    }
    out.push_str("</svg>\n");
    out
}

fn num(v: f64) -> String {
    if v.abs() >= 1e4 || (v != 0.0 && v.abs() < 1e-2) {
        format!("{v:.2e}")
    } else {
        format!("{v:.3}")
    }
}

fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}
