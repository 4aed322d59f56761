//! The torque residual's noise floor: one draw of the sensors' noise
//! pushed through the same smoothing and inverse dynamics as the data, at
//! levels the user states (`SensorNoise`: from the data sheet or a still
//! recording) or estimated from the data (raw minus smoothed signals).
//! The noise reaches the residual through filters of very different
//! colour (the smoothed effort; the smoothing filter's derivative of the
//! velocity, times the inertia), which is why the floor is propagated
//! rather than read off the residual's fast part: that reading, scaled as
//! if the noise were white, came out 1.27-1.34 times the true floor on a
//! control (the propagated one: 0.93-0.99).

use std::collections::VecDeque;

use nalgebra::{DMatrix, DVector, SVector};

use crate::data::Measured;
use crate::diagnose::along::{chunks, inverse_dynamics};
use crate::diagnose::signals::{robust_std, Signals};
use crate::diagnose::DiagnoseError;
use crate::synth::Rng;
use dynamics_runtime::Robot;

/// Per-sample standard deviations of the sensors, each either one value
/// for every joint or one per joint (in joint order).
///
/// ```
/// use dynamics_sim2real::diagnose::{Options, SensorNoise};
/// let options = Options {
///     noise: Some(SensorNoise {
///         q: vec![2e-5],                // rad (or m), every joint
///         qd: vec![2e-3],               // rad/s
///         tau: vec![0.8, 0.5, 0.05],    // N m per joint
///     }),
///     ..Options::default()
/// };
/// assert!(options.noise.is_some());
/// ```
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SensorNoise {
    /// Position noise (rad or m).
    pub q: Vec<f64>,
    /// Velocity noise (rad/s or m/s); ignored when the data carry no
    /// measured velocity.
    pub qd: Vec<f64>,
    /// Effort noise (N m or N).
    pub tau: Vec<f64>,
}

impl SensorNoise {
    /// The three levels per joint, checked: one value or `N`, each finite
    /// and not negative.
    #[allow(clippy::type_complexity)]
    pub(crate) fn per_joint<const N: usize>(&self) -> Result<[SVector<f64, N>; 3], DiagnoseError> {
        let one = |name: &'static str, v: &[f64]| -> Result<SVector<f64, N>, DiagnoseError> {
            let bad = |reason: String| DiagnoseError::Noise {
                sensor: name,
                reason,
            };
            if v.len() != 1 && v.len() != N {
                return Err(bad(format!(
                    "{} values given; give one for every joint or one per joint ({N})",
                    v.len()
                )));
            }
            if let Some(x) = v.iter().find(|x| !(x.is_finite() && **x >= 0.0)) {
                return Err(bad(format!(
                    "{x} is not a standard deviation (finite, >= 0)"
                )));
            }
            Ok(SVector::from_fn(|j, _| v[if v.len() == 1 { 0 } else { j }]))
        };
        Ok([
            one("q", &self.q)?,
            one("qd", &self.qd)?,
            one("tau", &self.tau)?,
        ])
    }
}

/// The noise floor of the smoothed torque residual per joint that sensor
/// noise of `levels` (q, qd, tau) makes: the RMS, over the samples in use,
/// of how far one draw of it added to the data moves `sig`'s residual.
///
/// The noisy twin of the record is drawn sample by sample and its
/// residual made a chunk at a time (the smoothing's windows and the
/// inverse dynamics, as [`Signals::unfloored`] makes them over the whole
/// record), so that neither the twin nor its signals are held whole.
pub fn known_floor<R: Robot<N>, const N: usize>(
    robot: &R,
    m: &Measured<N>,
    sig: &Signals<N>,
    levels: &[SVector<f64, N>; 3],
) -> SVector<f64, N> {
    let mut rng = Rng::new(0x5e_0015e);
    let n = m.len();
    let sg = &sig.sg;
    let h = sg.half();
    let (a, z) = sig.range;
    // The twin's samples (q, qd, tau) drawn so far, from sample `from` on.
    let mut twin: VecDeque<[SVector<f64, N>; 3]> = VecDeque::new();
    let (mut from, mut drawn) = (0usize, 0usize);
    let mut sum = SVector::<f64, N>::zeros();
    let mut count = 0usize;
    for c in chunks(a..z, 0) {
        // The stretch the chunk's windows read (one more sample before it:
        // the held effort averages a sample with the previous one).
        let (lo, hi) = (c.start.saturating_sub(h + 1), (c.end + h).min(n));
        while drawn < hi {
            let q = m.q[drawn] + rng.normal_vec(&levels[0]);
            let qd = m.qd[drawn] + rng.normal_vec(&levels[1]);
            let tau = m.tau[drawn] + rng.normal_vec(&levels[2]);
            twin.push_back([q, qd, tau]);
            drawn += 1;
        }
        while from < lo {
            twin.pop_front();
            from += 1;
        }
        let len = c.len();
        let mut motion = [
            vec![SVector::<f64, N>::zeros(); len],
            vec![SVector::zeros(); len],
            vec![SVector::zeros(); len],
        ];
        let mut tau = vec![SVector::<f64, N>::zeros(); len];
        for j in 0..N {
            let col = |x: usize| -> Vec<f64> { (lo..hi).map(|i| twin[i - from][x][j]).collect() };
            let (qj, vj) = (col(0), col(1));
            let held: Vec<f64> = (lo..hi)
                .map(|i| {
                    let prev = i.saturating_sub(1).max(from);
                    0.5 * (twin[prev - from][2][j] + twin[i - from][2][j])
                })
                .collect();
            for (i, k) in c.clone().enumerate() {
                let at = |x: &[f64], d: usize| sg.at(x, d, k - lo);
                motion[0][i][j] = at(&qj, 0);
                (motion[1][i][j], motion[2][i][j]) = if m.qd_measured {
                    (at(&vj, 0), at(&vj, 1))
                } else {
                    (at(&qj, 1), at(&qj, 2))
                };
                tau[i][j] = at(&held, 0);
            }
        }
        let mut model = vec![SVector::<f64, N>::zeros(); len];
        let [q, qd, qdd] = &motion;
        inverse_dynamics(robot, [q, qd, qdd], 0..len, len, &mut model);
        for (i, k) in c.enumerate() {
            if sig.mask.usable(k) {
                let d = (tau[i] - model[i]) - sig.residual[k];
                sum += d.component_mul(&d);
                count += 1;
            }
        }
    }
    (sum / count.max(1) as f64).map(|s| s.sqrt().max(1e-12))
}

/// The sensors' per-sample noise levels (q, qd, tau per joint) estimated
/// from the data: raw minus smoothed positions and velocities (variance
/// sigma^2 (1 - w0) for white noise, w0 the smoother's centre weight), and
/// [`effort_sensor_noise`] for the efforts.
pub fn sensor_levels<const N: usize>(m: &Measured<N>, sig: &Signals<N>) -> [SVector<f64, N>; 3] {
    let sg = &sig.sg;
    let h = sg.half();
    let (a, z) = sig.range;
    let w0 = sg.weights(0)[h];
    // (The grid's interpolation, if any, lowered the noise's variance by
    // `noise_variance_factor` on average; its low frequencies, which the
    // smoothed residual keeps, it did not lower.)
    let gain = 1.0 / ((1.0 - w0).max(0.25) * m.noise_variance_factor()).sqrt();
    let spread = |d: Vec<f64>| (robust_std(&d) * gain).max(1e-15);
    let used = || (a..z).filter(|&k| sig.mask.usable(k));
    let sigma_q: SVector<f64, N> = SVector::from_fn(|j, _| {
        spread(used().map(|k| m.q[k][j] - sig.motion.q_at(k, j)).collect())
    });
    let sigma_qd: SVector<f64, N> = SVector::from_fn(|j, _| {
        if m.qd_measured {
            spread(
                used()
                    .map(|k| m.qd[k][j] - sig.motion.qd_at(k, j))
                    .collect(),
            )
        } else {
            0.0
        }
    });
    let sigma_tau = effort_sensor_noise(m, sig).map(|s| (s * gain).max(1e-15));
    [sigma_q, sigma_qd, sigma_tau]
}

/// Samples per block of the regression in [`effort_sensor_noise`].
const BLOCK: usize = 500;

/// Robust spread per joint of the recorded efforts' fast part (raw minus
/// smoothed) that the fast part of the measured positions and velocities
/// does not explain. A feedback controller turns the sensors' position and
/// velocity noise into real effort jitter that moves the robot and belongs
/// in the prediction; what is left is effort that was recorded but not
/// applied. Fitted by least squares in blocks of [`BLOCK`] samples (the
/// controller's gains through the inertia vary with the pose).
fn effort_sensor_noise<const N: usize>(m: &Measured<N>, sig: &Signals<N>) -> SVector<f64, N> {
    let sg = &sig.sg;
    let (a, z) = sig.range;
    // Joint `j`'s fast part of `v` (raw minus smoothed) at samples
    // `lo..hi`, the whole series' filter at each (`joint_run`, to the bit),
    // made a block at a time rather than for the whole record.
    let fast = |v: &[SVector<f64, N>], j: usize, lo: usize, hi: usize| -> Vec<f64> {
        let smooth = sg.joint_run(v, 0, j, (lo, hi));
        smooth
            .iter()
            .enumerate()
            .map(|(i, y)| v[lo + i][j] - y)
            .collect()
    };
    let cols = if m.qd_measured { 2 * N } else { N };
    let blocks: Vec<usize> = (a..z)
        .step_by(BLOCK)
        .filter(|&k0| k0 + BLOCK <= z && sig.mask.clear(k0, k0 + BLOCK))
        .collect();
    let mut left: Vec<Vec<f64>> = vec![Vec::with_capacity(blocks.len() * BLOCK); N];
    for &k0 in &blocks {
        let k1 = k0 + BLOCK;
        let eq: Vec<Vec<f64>> = (0..N).map(|j| fast(&m.q, j, k0, k1)).collect();
        let eqd: Vec<Vec<f64>> = if m.qd_measured {
            (0..N).map(|j| fast(&m.qd, j, k0, k1)).collect()
        } else {
            vec![]
        };
        let x = DMatrix::from_fn(
            BLOCK,
            cols,
            |r, c| {
                if c < N {
                    eq[c][r]
                } else {
                    eqd[c - N][r]
                }
            },
        );
        let svd = x.clone().svd(true, true);
        for (j, l) in left.iter_mut().enumerate() {
            let et = fast(&m.tau, j, k0, k1);
            let y = DVector::from_fn(BLOCK, |r, _| et[r]);
            match svd.solve(&y, 1e-12) {
                Ok(theta) => l.extend((&y - &x * theta).iter()),
                Err(_) => l.extend(y.iter()),
            }
        }
    }
    SVector::from_fn(|j, _| {
        if left[j].is_empty() {
            let et = fast(&m.tau, j, a, z);
            robust_std(
                &(a..z)
                    .filter(|&k| sig.mask.usable(k))
                    .map(|k| et[k - a])
                    .collect::<Vec<_>>(),
            )
        } else {
            robust_std(&left[j])
        }
    })
}

#[cfg(test)]
mod tests;
