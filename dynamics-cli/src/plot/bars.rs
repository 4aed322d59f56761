//! Horizontal bar charts (the diagnosis ranking).

use std::fmt::Write as _;

use super::{esc, num, COLORS};

/// A horizontal bar chart: one bar per `(label, value)` from zero (negative
/// values to the left), the value written at the bar's end, and a dashed
/// vertical line at `marker` (value, label) if given.
///
/// ```
/// use dynamics_cli::plot::bars;
/// let s = bars("ranking", "delta AICc", &[("coulomb j2".into(), 3800.0), ("offset j1".into(), -2.0)], Some((100.0, "threshold")));
/// assert_eq!(s.matches("<rect").count(), 1 + 2);
/// assert!(s.contains(">coulomb j2</text>") && s.contains("stroke-dasharray"));
/// ```
pub fn bars(
    title: &str,
    xlabel: &str,
    bars: &[(String, f64)],
    marker: Option<(f64, &str)>,
) -> String {
    // Label column as wide as the longest label (about 7 px a character).
    let longest = bars.iter().map(|b| b.0.chars().count()).max().unwrap_or(0);
    let left = (7.0 * longest as f64 + 16.0).max(120.0);
    let (right, top, row) = (70.0, 50.0, 22.0);
    let w = left + 450.0 + right;
    let h = top + row * bars.len().max(1) as f64 + 50.0;
    let values = bars
        .iter()
        .map(|b| b.1)
        .chain(marker.map(|m| m.0))
        .filter(|v| v.is_finite());
    let (mut lo, mut hi) = (0.0f64, 0.0f64);
    for v in values {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if hi - lo < 1e-12 {
        hi = lo + 1.0;
    }
    let pw = w - left - right;
    let px = |v: f64| left + (v.clamp(lo, hi) - lo) / (hi - lo) * pw;
    let mut out = String::new();
    let _ = write!(out, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" font-family=\"sans-serif\" font-size=\"12\">");
    let _ = write!(out, "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>");
    let _ = write!(
        out,
        "<text x=\"{}\" y=\"24\" text-anchor=\"middle\" font-size=\"15\">{}</text>",
        w / 2.0,
        esc(title)
    );
    for (i, (label, v)) in bars.iter().enumerate() {
        let y = top + row * i as f64;
        let v = if v.is_finite() { *v } else { 0.0 };
        let (a, b) = (px(0.0), px(v));
        let color = if v >= 0.0 { COLORS[0] } else { COLORS[1] };
        let _ = write!(
            out,
            "<rect x=\"{:.2}\" y=\"{:.2}\" width=\"{:.2}\" height=\"{:.2}\" fill=\"{color}\"/>",
            a.min(b),
            y + 3.0,
            (b - a).abs().max(0.5),
            row - 6.0
        );
        let _ = write!(
            out,
            "<text x=\"{:.2}\" y=\"{:.2}\" text-anchor=\"end\">{}</text>",
            left - 8.0,
            y + row / 2.0 + 4.0,
            esc(label)
        );
        let _ = write!(
            out,
            "<text x=\"{:.2}\" y=\"{:.2}\" font-size=\"10\">{}</text>",
            a.max(b) + 4.0,
            y + row / 2.0 + 4.0,
            if v.abs() >= 1e4 {
                num(v)
            } else {
                format!("{v:.1}")
            }
        );
    }
    let bottom = top + row * bars.len().max(1) as f64;
    let _ = write!(
        out,
        "<line x1=\"{0:.2}\" y1=\"{top}\" x2=\"{0:.2}\" y2=\"{bottom}\" stroke=\"#444\"/>",
        px(0.0)
    );
    if let Some((v, label)) = marker.filter(|m| m.0.is_finite()) {
        let _ = write!(
            out,
            "<line x1=\"{0:.2}\" y1=\"{1}\" x2=\"{0:.2}\" y2=\"{bottom}\" stroke=\"#888\" stroke-dasharray=\"4 3\"/>",
            px(v),
            top - 8.0
        );
        let _ = write!(
            out,
            "<text x=\"{:.2}\" y=\"{:.2}\" font-size=\"10\" fill=\"#555\">{}</text>",
            px(v) + 3.0,
            top - 2.0,
            esc(label)
        );
    }
    for k in 0..=4 {
        let v = lo + (hi - lo) * k as f64 / 4.0;
        let _ = write!(
            out,
            "<text x=\"{:.2}\" y=\"{:.2}\" text-anchor=\"middle\">{}</text>",
            px(v),
            bottom + 16.0,
            num(v)
        );
    }
    let _ = write!(
        out,
        "<text x=\"{:.2}\" y=\"{:.2}\" text-anchor=\"middle\">{}</text>",
        left + pw / 2.0,
        bottom + 36.0,
        esc(xlabel)
    );
    out.push_str("</svg>\n");
    out
}
