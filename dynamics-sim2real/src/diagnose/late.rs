//! Delayed channels: which stream of a log is late. Positions and
//! velocities late together against the effort is the `time_delay`
//! candidate of the vocabulary (channel `all`); the position stream late
//! against velocity and effort (channel `positions`) is told from it by the
//! kinematic consistency of the positions with the independently measured
//! velocities: positions `d` late have the rate `qd(t - d) ~ qd - d qdd`,
//! so the smoothed rate of the measured positions minus the smoothed
//! measured velocity, regressed on the acceleration over every joint and
//! fit row, gives `-d`. Only when that delay is significant
//! ([`SIGNIFICANCE`] standard deviations, and at least half a sample) is the
//! `positions` channel offered as a candidate; its column is what the model
//! misses when evaluated at `q - d qd`: `d K qd`.

use super::analysis::Prepared;
use super::candidate::Candidate;
use crate::data::Measured;
use crate::Warning;

/// How many standard deviations the kinematic delay must stand from zero.
pub const SIGNIFICANCE: f64 = 10.0;

/// The delay of the positions against the velocities found from their
/// kinematic consistency, and its standard deviation (s).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Kinematic {
    /// Delay, s (positive: the positions are late).
    pub delay: f64,
    /// Its standard deviation, s.
    pub std: f64,
}

impl Kinematic {
    /// Whether the positions are late (significantly, and by at least half
    /// a sample interval `dt`).
    pub fn late(&self, dt: f64) -> bool {
        self.delay >= 0.5 * dt && self.delay >= SIGNIFICANCE * self.std
    }
}

/// The kinematic delay of the positions of `m` (prepared as `p`) against
/// its velocities; `None` when the velocities are not measured (then they
/// come from the positions, and share their delay) or nothing moves.
pub fn kinematic<const N: usize>(m: &Measured<N>, p: &Prepared<N>) -> Option<Kinematic> {
    if !m.qd_measured || m.len() != p.sig.t.len() {
        return None;
    }
    let sig = &p.sig;
    // Per joint: the rate of the smoothed positions minus the smoothed
    // velocity (e), against the acceleration (x), over the fit rows.
    let mut per_joint = Vec::with_capacity(N);
    for j in 0..N {
        let q: Vec<f64> = m.q.iter().map(|v| v[j]).collect();
        let rate = sig.sg.apply(&q, 1);
        let (mut ex, mut xx, mut ee, mut n) = (0.0, 0.0, 0.0, 0.0);
        for &k in &p.rows {
            let (e, x) = (rate[k] - sig.qd[k][j], sig.qdd[k][j]);
            if e.is_finite() && x.is_finite() {
                ex += e * x;
                xx += x * x;
                ee += e * e;
                n += 1.0;
            }
        }
        if xx > 0.0 && n > 2.0 {
            let d = -ex / xx;
            let var = ((ee - ex * ex / xx) / (n - 1.0)).max(1e-300);
            per_joint.push((d, var / xx));
        }
    }
    // Inverse-variance weighted over the joints.
    let w: f64 = per_joint.iter().map(|(_, v)| 1.0 / v).sum();
    if per_joint.is_empty() || !w.is_finite() || w <= 0.0 {
        return None;
    }
    let delay = per_joint.iter().map(|(d, v)| d / v).sum::<f64>() / w;
    Some(Kinematic {
        delay,
        std: (1.0 / w).sqrt(),
    })
}

/// The `positions` candidate added to `candidates` when the positions of
/// `m` are late by their kinematic consistency (and delays are asked
/// for), with a warning saying by how much.
pub fn offer<const N: usize>(
    candidates: &mut Vec<Candidate>,
    m: &Measured<N>,
    p: &Prepared<N>,
    warnings: &mut Vec<Warning>,
) {
    if !candidates.contains(&Candidate::TimeDelay) {
        return;
    }
    if let Some(k) = kinematic(m, p).filter(|k| k.late(p.sig.dt)) {
        candidates.push(Candidate::LatePositions);
        warnings.push(Warning::LatePositions {
            delay: k.delay,
            std: k.std,
        });
    }
}

/// The late channel a delay candidate names: `all` (positions and
/// velocities late together against the effort) or `positions`.
pub fn channel(c: Candidate) -> Option<String> {
    match c {
        Candidate::TimeDelay => Some("all".into()),
        Candidate::LatePositions => Some("positions".into()),
        _ => None,
    }
}
