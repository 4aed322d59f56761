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
//! `positions` channel offered as a candidate, in place of channel `all`
//! (which keeps positions and velocities consistent); its column is what
//! the model misses when evaluated at `q - d qd`: `d K qd`.
//!
//! The effort late against position and velocity (channel `effort`) is the
//! motion early against the effort: the effort recorded `d` later is the
//! one that goes with the motion now. Only the delay of the motion against
//! the effort shows in the data (every channel late together shows
//! nothing); of its two signs, the motion late is channel `all`, the
//! effort late channel `effort`. The `effort` column is the secant of the
//! smoothed measured effort over `d` (`shift.rs`), `d` found by least
//! squares on the secant at the previous estimate until it settles
//! ([`effort_secant`]); the fit then gives the delay (>= 0) and its
//! standard deviation. The `all` column is likewise the secant of the
//! measured effort over the motion's delay, found the same way
//! ([`motion_secant`]), where that delay is two samples or more. When the
//! velocities are derived from the positions no kinematic consistency can
//! be checked: positions late alone and positions and velocities late
//! together are the same data, and a delay of channel `all` is then warned
//! as such ([`warn`]), not guessed.

use crate::data::Measured;
use crate::diagnose::candidates::candidate::Candidate;
use crate::diagnose::candidates::shift::{late_effort_column, late_motion_column};
use crate::diagnose::candidates::Prepared;
use crate::diagnose::signals::Signals;
use crate::Warning;
use nalgebra::SVector;

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
            let (e, x) = (rate[k] - sig.motion.qd_at(k, j), sig.motion.qdd_at(k, j));
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

/// The `effort` candidate added to `candidates` whenever delays are asked
/// for, and the `positions` candidate when the positions of `m` are late
/// by their kinematic consistency, with a warning saying by how much.
pub fn offer_delays<const N: usize>(
    candidates: &mut Vec<Candidate>,
    m: &Measured<N>,
    p: &Prepared<N>,
    warnings: &mut Vec<Warning>,
) {
    let Some(all) = candidates
        .iter()
        .position(|c| matches!(c, Candidate::TimeDelay(_)))
    else {
        return;
    };
    candidates[all] = Candidate::TimeDelay(motion_secant(p));
    candidates.push(Candidate::LateEffort(effort_secant(p)));
    if let Some(k) = kinematic(m, p).filter(|k| k.late(p.sig.dt)) {
        // Positions and velocities late together stay consistent with each
        // other: the inconsistency found rules that channel out, though
        // its first-order column may fit a long delay better (a position
        // stream 23.8 ms late at 100 Hz: `all` 53 AICc ahead, at 17 ms).
        candidates.retain(|c| !matches!(c, Candidate::TimeDelay(_)));
        candidates.push(Candidate::LatePositions);
        warnings.push(Warning::LatePositions {
            delay: k.delay,
            std: k.std,
        });
    }
}

/// Longest delay searched, s.
const LONGEST: f64 = 0.25;

/// The delay over which the `effort` candidate takes the secant of the
/// measured effort: the delay found by least squares on the column of the
/// secant at the previous estimate, from one sample on, until it settles
/// (a first-order column alone reads a delay `d` of content at `w` rad/s
/// as `sin(w d) / w`: 8 % short at 10 ms and 11 Hz); 0 when the effort
/// does not lag the model's.
pub fn effort_secant<const N: usize>(p: &Prepared<N>) -> f64 {
    settle(p, late_effort_column, f64::MIN_POSITIVE).unwrap_or_else(|last| last)
}

/// The delay over which the `all` candidate (the motion late) takes the
/// secant of the measured effort, found as [`effort_secant`]'s from the
/// tangent on; 0 (the tangent) when the motion is not late, or by less
/// than two samples.
pub fn motion_secant<const N: usize>(p: &Prepared<N>) -> f64 {
    settle(p, late_motion_column, 2.0 * p.sig.dt).unwrap_or(0.0)
}

/// The delay `column` (taken over the previous estimate, from 0) fits
/// to the residual by least squares, again until it settles; the last
/// estimate as `Err` once one falls below `least` (or is not finite).
fn settle<const N: usize>(
    p: &Prepared<N>,
    column: impl Fn(&Signals<N>, usize, f64) -> SVector<f64, N>,
    least: f64,
) -> Result<f64, f64> {
    let sig = &p.sig;
    let mut d0 = 0.0;
    for _ in 0..6 {
        let (mut xy, mut xx) = (0.0, 0.0);
        for &k in &p.rows {
            let c = column(sig, k, d0);
            for j in 0..N {
                let (x, y) = (c[j] / sig.floor[j], sig.residual[k][j] / sig.floor[j]);
                if x.is_finite() && y.is_finite() {
                    xy += x * y;
                    xx += x * x;
                }
            }
        }
        let d = xy / xx;
        if !(d.is_finite() && d >= least) {
            return Err(d0);
        }
        let d = d.min(LONGEST);
        let settled = (d - d0).abs() < 1e-3 * sig.dt;
        d0 = d;
        if settled {
            break;
        }
    }
    Ok(d0)
}
