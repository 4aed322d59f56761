//! The report's SVG figures: per joint the training residual with the gap
//! windows shaded, the held-out residual before and after the chosen
//! effect, measured vs nominal vs corrected effort; and the ranking.

use dynamics_sim2real::diagnose::traces::{DataTraces, JointTraces};
use dynamics_sim2real::diagnose::{JointGap, Ranked, Report};

use crate::plot::{bars, svg_shaded, Series, Shade};

/// Most points drawn per line (the smoothed series lose nothing visible).
const MAX_POINTS: usize = 1500;
/// Candidates in the ranking chart.
pub const RANKED_SHOWN: usize = 12;
/// Length of the zoomed effort plot, s.
const ZOOM: f64 = 1.0;

/// `(x, y)` points of `y` against `t` over samples `a..z`, thinned.
fn points(t: &[f64], y: &[f64], a: usize, z: usize) -> Vec<(f64, f64)> {
    let step = (z.saturating_sub(a)).div_ceil(MAX_POINTS).max(1);
    (a..z).step_by(step).map(|k| (t[k], y[k])).collect()
}

/// `kind at place`.
pub fn place(r: &Ranked) -> String {
    match r.joint.as_ref().or(r.point.as_ref()) {
        Some(p) => format!("{} at {p}", r.kind),
        None => r.kind.to_string(),
    }
}

/// Training residual of joint `j` with its windows and noise band.
pub fn residual(data: &DataTraces, jt: &JointTraces, gap: &JointGap, corrected: bool) -> String {
    let n = data.t.len();
    let mut series = vec![Series {
        name: "nominal model",
        points: points(&data.t, &jt.residual, 0, n),
    }];
    if corrected {
        series.push(Series {
            name: "corrected",
            points: points(&data.t, &jt.residual_after, 0, n),
        });
    }
    let mut shades: Vec<Shade> = gap
        .windows
        .iter()
        .map(|w| Shade {
            x: Some((w.start, w.end)),
            y: None,
            label: w.phase,
        })
        .collect();
    shades.push(Shade {
        x: None,
        y: Some((-3.0 * jt.floor, 3.0 * jt.floor)),
        label: "",
    });
    svg_shaded(
        &format!(
            "{}: torque residual, training data (bands: gap windows)",
            jt.joint
        ),
        "t [s]",
        &format!("measured - model [{}]", jt.unit),
        &series,
        &shades,
        false,
    )
}

/// Held-out residual of one joint before and after the chosen effect.
pub fn shrink(data: &DataTraces, jt: &JointTraces) -> String {
    let n = data.t.len();
    svg_shaded(
        &format!("{}: torque residual, held-out data", jt.joint),
        "t [s]",
        &format!("measured - model [{}]", jt.unit),
        &[
            Series {
                name: "nominal model",
                points: points(&data.t, &jt.residual, 0, n),
            },
            Series {
                name: "corrected",
                points: points(&data.t, &jt.residual_after, 0, n),
            },
        ],
        &[Shade {
            x: None,
            y: Some((-3.0 * jt.floor, 3.0 * jt.floor)),
            label: "",
        }],
        false,
    )
}

/// Measured vs nominal vs corrected effort of one joint on the held-out
/// data, over [`ZOOM`] seconds centred where the nominal residual peaks.
pub fn effort(data: &DataTraces, jt: &JointTraces) -> String {
    let n = data.t.len();
    let peak = (0..n)
        .max_by(|&a, &b| jt.residual[a].abs().total_cmp(&jt.residual[b].abs()))
        .unwrap_or(0);
    let dt = if n > 1 {
        (data.t[n - 1] - data.t[0]) / (n - 1) as f64
    } else {
        1.0
    };
    let half = ((0.5 * ZOOM / dt).round() as usize).max(1);
    let a = peak.saturating_sub(half).min(n.saturating_sub(2 * half));
    let z = (a + 2 * half).min(n);
    svg_shaded(
        &format!(
            "{}: effort, held-out data, around the largest residual",
            jt.joint
        ),
        "t [s]",
        &format!("effort [{}]", jt.unit),
        &[
            Series {
                name: "measured",
                points: points(&data.t, &jt.measured, a, z),
            },
            Series {
                name: "nominal model",
                points: points(&data.t, &jt.nominal, a, z),
            },
            Series {
                name: "corrected",
                points: points(&data.t, &jt.corrected, a, z),
            },
        ],
        &[],
        false,
    )
}

/// The ranking: delta AICc of the first candidates, the `none` threshold
/// marked.
pub fn ranking(report: &Report, none_margin: f64) -> String {
    let rows: Vec<(String, f64)> = report
        .which
        .ranked
        .iter()
        .take(RANKED_SHOWN)
        .map(|r| (place(r), r.delta_aicc))
        .collect();
    bars(
        "Candidates ranked: AICc improvement over the nominal model (training data)",
        "delta AICc (larger is better)",
        &rows,
        Some((none_margin, "verdict `none` below")),
    )
}
