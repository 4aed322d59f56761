//! Where the residual concentrates: per joint, the samples are labelled by
//! motion phase (hold, velocity reversal, peak acceleration, high speed,
//! cruise); contiguous runs of one phase are windows, scored by residual
//! RMS over the noise floor.

use serde::Serialize;

use crate::diagnose::candidates::Prepared;

/// A time window where the gap concentrates.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GapWindow {
    /// Start, s.
    pub start: f64,
    /// End, s.
    pub end: f64,
    /// Motion phase there.
    pub phase: &'static str,
    /// Residual RMS in the window over the noise floor.
    pub ratio: f64,
}

/// Windows of joint `j` with residual `r`, ranked by ratio, those above
/// `threshold` times the noise floor (at most `max`).
pub fn gap_windows<const N: usize>(
    p: &Prepared<N>,
    r: &[nalgebra::SVector<f64, N>],
    j: usize,
    threshold: f64,
    max: usize,
) -> Vec<GapWindow> {
    let sig = &p.sig;
    let (a, z) = sig.range;
    let h = sig.sg.half();
    let (a, z) = (a + h, z.saturating_sub(h));
    if z <= a {
        return vec![];
    }
    let (qd, qdd) = (|k| sig.motion.qd_at(k, j), |k| sig.motion.qdd_at(k, j));
    let peak_v = (a..z).map(|k| qd(k).abs()).fold(0.0, f64::max).max(1e-9);
    let peak_a = (a..z).map(|k| qdd(k).abs()).fold(0.0, f64::max).max(1e-9);
    let reversal_span = (0.03 / sig.dt).round() as usize;
    let mut near_reversal = vec![false; sig.t.len()];
    let mut before = qd(a);
    for k in a + 1..z {
        let now = qd(k);
        let reversed = now.signum() != before.signum();
        before = now;
        if reversed && peak_v > 1e-6 {
            for m in k.saturating_sub(reversal_span)..(k + reversal_span).min(z) {
                near_reversal[m] = true;
            }
        }
    }
    let phase = |k: usize| -> &'static str {
        let (v, acc) = (qd(k).abs(), qdd(k).abs());
        if v < 0.02 * peak_v && acc < 0.05 * peak_a {
            "hold"
        } else if near_reversal[k] {
            "velocity reversal"
        } else if acc > 0.7 * peak_a {
            "peak acceleration"
        } else if v > 0.7 * peak_v {
            "high speed"
        } else {
            "cruise"
        }
    };
    let floor = sig.floor[j];
    let mut out = Vec::new();
    let mut start = a;
    while start < z {
        let ph = phase(start);
        let mut end = start + 1;
        while end < z && phase(end) == ph {
            end += 1;
        }
        let ms: f64 = (start..end).map(|k| r[k][j].powi(2)).sum::<f64>() / (end - start) as f64;
        let ratio = ms.sqrt() / floor;
        if ratio > threshold && (end - start) as f64 * sig.dt >= 0.01 {
            out.push(GapWindow {
                start: sig.t[start],
                end: sig.t[end - 1],
                phase: ph,
                ratio,
            });
        }
        start = end;
    }
    out.sort_by(|x, y| y.ratio.total_cmp(&x.ratio));
    out.truncate(max);
    out
}
