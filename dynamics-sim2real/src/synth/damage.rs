//! What real logs carry, made on purpose: a jittered controller clock, a
//! late position channel and a late effort channel (in the experiment
//! itself, `run.rs`), and, on the recorded rows, repeated samples, holes
//! and glitches.

use nalgebra::SVector;

use super::Rng;
use crate::data::Measured;

/// Damage to apply to a synthetic log (all off by default).
///
/// ```
/// use dynamics_sim2real::synth::{Damage, SynthOptions};
/// let opts = SynthOptions::<2> {
///     rate: 100.0,
///     damage: Damage { jitter: 0.3, repeats: 0.05, holes: 2, glitches: 3, ..Damage::default() },
///     ..Default::default()
/// };
/// assert!(opts.damage.any());
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Damage {
    /// Controller clock jitter: each interval is the nominal one times a
    /// factor uniform in `1 +- jitter` (0.3: +-30 %); the timestamps are
    /// the true sampling times.
    pub jitter: f64,
    /// Fraction of rows on which the logger writes a quantity's previous
    /// values again (the whole row, only the positions or only the
    /// efforts, in turn).
    pub repeats: f64,
    /// Holes: stretches of rows missing.
    pub holes: usize,
    /// Length of each hole, s.
    pub hole_length: f64,
    /// Glitches: one cell each, in turn 1e300, a spike of 50 effort-noise
    /// deviations, the value's sign flipped (on a position column).
    pub glitches: usize,
    /// How late the position channel is against velocity and effort, s.
    pub q_late: f64,
    /// How late the effort channel is against position and velocity, s:
    /// each recorded effort is the applied one `tau_late` earlier
    /// (interpolated linearly between the controller's samples; the
    /// controller itself is not delayed).
    pub tau_late: f64,
}

impl Default for Damage {
    fn default() -> Self {
        Damage {
            jitter: 0.0,
            repeats: 0.0,
            holes: 0,
            hole_length: 0.1,
            glitches: 0,
            q_late: 0.0,
            tau_late: 0.0,
        }
    }
}

impl Damage {
    /// Whether any damage is asked for.
    pub fn any(&self) -> bool {
        self.jitter > 0.0
            || self.repeats > 0.0
            || self.holes > 0
            || self.glitches > 0
            || self.q_late > 0.0
            || self.tau_late > 0.0
    }

    /// Applies the row damage (repeats, holes, glitches) to `m`, drawing
    /// from `seed`; `tau_noise` is each joint's effort noise.
    pub(super) fn apply_rows<const N: usize>(
        &self,
        m: &mut Measured<N>,
        tau_noise: &SVector<f64, N>,
        seed: u64,
    ) {
        let mut rng = Rng::new(seed ^ 0xDA_4A6E);
        let n = m.len();
        if n < 10 {
            return;
        }
        let repeats = (self.repeats * n as f64).round() as usize;
        // In time order, so that a row repeats the row before as written.
        let mut rows: Vec<(usize, usize)> =
            (0..repeats).map(|i| (1 + rng.below(n - 1), i)).collect();
        rows.sort_unstable();
        for (k, i) in rows {
            match i % 3 {
                0 => {
                    m.q[k] = m.q[k - 1];
                    m.qd[k] = m.qd[k - 1];
                    m.tau[k] = m.tau[k - 1];
                }
                1 => m.q[k] = m.q[k - 1],
                _ => m.tau[k] = m.tau[k - 1],
            }
        }
        for i in 0..self.glitches {
            // Away from the edges, where a fit has no window anyway.
            let k = n / 20 + rng.below(n - n / 10);
            let j = rng.below(N);
            match i % 3 {
                0 => m.tau[k][j] = 1e300,
                1 => {
                    m.tau[k][j] +=
                        50.0 * tau_noise[j].max(1e-6) * if rng.below(2) == 0 { 1.0 } else { -1.0 }
                }
                _ => {
                    m.q[k][j] = if m.q[k][j].abs() > 1e-3 {
                        -m.q[k][j]
                    } else {
                        m.q[k][j] + 0.1
                    }
                }
            }
        }
        if self.holes > 0 && self.hole_length > 0.0 {
            let t0 = m.t[0];
            let span = m.duration();
            let mut cut = vec![false; n];
            for i in 0..self.holes {
                // Spread over the record: hole i in the i-th of `holes` stretches.
                let part = span / self.holes as f64;
                let start = t0 + part * (i as f64 + rng.uniform(0.2, 0.8));
                for (k, c) in cut.iter_mut().enumerate() {
                    if m.t[k] >= start && m.t[k] < start + self.hole_length {
                        *c = true;
                    }
                }
            }
            let keep = |v: &mut Vec<_>| {
                let mut k = 0;
                v.retain(|_| {
                    k += 1;
                    !cut[k - 1]
                });
            };
            let mut t = std::mem::take(&mut m.t);
            let mut k = 0;
            t.retain(|_| {
                k += 1;
                !cut[k - 1]
            });
            m.t = t;
            keep(&mut m.q);
            keep(&mut m.qd);
            keep(&mut m.tau);
        }
    }
}
