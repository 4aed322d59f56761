//! The uniform grid (see the module's documentation): each channel
//! interpolated linearly at the true times between its valid samples;
//! filled samples and holes marked.

use nalgebra::SVector;

use super::clock::{Clock, HOLE_PERIODS};
use super::{channel, series};
use crate::data::{differentiate, Measured};
use crate::Warning;

/// Brings every channel onto the grid of `clock`, skipping the samples
/// marked in `bad`.
pub(super) fn grid<const N: usize>(
    m: &Measured<N>,
    bad: &[Vec<bool>],
    clock: &Clock,
    file: &str,
    mut warnings: Vec<Warning>,
) -> Measured<N> {
    let dt = clock.interval;
    let (t0, t1) = (m.t[0], m.t[m.len() - 1]);
    let len = ((t1 - t0) / dt + 1e-9).floor() as usize + 1;
    let t: Vec<f64> = (0..len).map(|k| t0 + k as f64 * dt).collect();
    let ordinary = clock.max.max(dt) * (1.0 + 1e-9);
    let hole_span = HOLE_PERIODS * dt;
    let mut missing = vec![false; len];
    // Sum of the interpolation's white-noise variance factor, and count.
    let (mut variance, mut counted) = (0.0, 0usize);
    let mut hole = vec![false; len];
    // Per grid point in a hole: the line of the first sample after it, and
    // the times of the samples either side.
    let mut hole_at = vec![(0usize, 0.0, 0.0); len];
    let mut out = Measured::<N> {
        t: t.clone(),
        q: vec![SVector::zeros(); len],
        qd: vec![SVector::zeros(); len],
        tau: vec![SVector::zeros(); len],
        qd_measured: m.qd_measured,
        joints: m.joints.clone(),
        ..Default::default()
    };
    for (c, flags) in bad.iter().enumerate() {
        let x = channel(m, c);
        let valid: Vec<usize> = (0..m.len()).filter(|&k| !flags[k]).collect();
        let mut i = 0; // valid[i] is the last valid sample at or before the grid time
        let mut values = vec![0.0; len];
        for (g, &tg) in t.iter().enumerate() {
            while i + 1 < valid.len() && m.t[valid[i + 1]] <= tg {
                i += 1;
            }
            let (a, b) = (valid[i], valid[(i + 1).min(valid.len() - 1)]);
            // A grid point on a valid sample (to rounding) is that sample.
            let on = [a, b]
                .into_iter()
                .find(|&s| (m.t[s] - tg).abs() <= 1e-6 * dt);
            let value = if let Some(s) = on {
                x[s]
            } else if m.t[a] > tg || a == b {
                // Before the first valid sample or after the last: the nearest.
                missing[g] = true;
                x[if m.t[a] > tg { a } else { b }]
            } else {
                let span = m.t[b] - m.t[a];
                if span >= hole_span {
                    hole[g] = true;
                    if b + 2 > hole_at[g].0 {
                        hole_at[g] = (b + 2, m.t[a], m.t[b]);
                    }
                } else if span > ordinary || b > a + 1 {
                    missing[g] = true;
                } else {
                    let f = (tg - m.t[a]) / span;
                    variance += (1.0 - f).powi(2) + f * f;
                    counted += 1;
                }
                x[a] + (x[b] - x[a]) * ((tg - m.t[a]) / span)
            };
            values[g] = value;
        }
        let (_, j) = series(m, c);
        let target = match (c / N, m.qd_measured) {
            (0, _) => &mut out.q,
            (1, true) => &mut out.qd,
            _ => &mut out.tau,
        };
        for (g, v) in values.into_iter().enumerate() {
            target[g][j] = v;
        }
    }
    let mut g = 0;
    while g < len {
        if !hole[g] {
            g += 1;
            continue;
        }
        let start = g;
        while g < len && hole[g] {
            g += 1;
        }
        out.holes.push((start, g));
        let (line, start, end) = hole_at[start..g]
            .iter()
            .copied()
            .fold((0, 0.0, 0.0), |best, h| if h.0 > best.0 { h } else { best });
        warnings.push(Warning::Hole {
            file: file.to_string(),
            line,
            start,
            end,
        });
    }
    for (mg, h) in missing.iter_mut().zip(&hole) {
        *mg |= *h;
    }
    out.missing = missing;
    out.prepared = true;
    out.interpolation_variance = if counted > 0 {
        variance / counted as f64
    } else {
        1.0
    };
    if !m.qd_measured {
        out.qd = differentiate(&out.t, &out.q);
    }
    out.warnings = warnings;
    out
}
