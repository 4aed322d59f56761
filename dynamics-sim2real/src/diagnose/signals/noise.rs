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

use nalgebra::{DMatrix, DVector, SVector};

use crate::data::Measured;
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
pub fn known_floor<R: Robot<N>, const N: usize>(
    robot: &R,
    m: &Measured<N>,
    sig: &Signals<N>,
    levels: &[SVector<f64, N>; 3],
) -> SVector<f64, N> {
    let mut rng = Rng::new(0x5e_0015e);
    let mut noisy = m.clone();
    for k in 0..noisy.len() {
        noisy.q[k] += rng.normal_vec(&levels[0]);
        noisy.qd[k] += rng.normal_vec(&levels[1]);
        noisy.tau[k] += rng.normal_vec(&levels[2]);
    }
    let shaken = Signals::unfloored(robot, &noisy);
    let (a, z) = sig.range;
    let mut sum = SVector::<f64, N>::zeros();
    let mut count = 0usize;
    for k in (a..z).filter(|&k| sig.mask.usable(k)) {
        let d = shaken.residual[k] - sig.residual[k];
        sum += d.component_mul(&d);
        count += 1;
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
    let sigma_q: SVector<f64, N> =
        SVector::from_fn(|j, _| spread(used().map(|k| m.q[k][j] - sig.q[k][j]).collect()));
    let sigma_qd: SVector<f64, N> = SVector::from_fn(|j, _| {
        if m.qd_measured {
            spread(used().map(|k| m.qd[k][j] - sig.qd[k][j]).collect())
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
    let fast = |v: &[SVector<f64, N>]| -> Vec<SVector<f64, N>> {
        let mut out = vec![SVector::<f64, N>::zeros(); v.len()];
        for j in 0..N {
            let x: Vec<f64> = v.iter().map(|s| s[j]).collect();
            for (k, y) in sg.apply(&x, 0).iter().enumerate() {
                out[k][j] = x[k] - y;
            }
        }
        out
    };
    let (eq, eqd, et) = (fast(&m.q), fast(&m.qd), fast(&m.tau));
    let cols = if m.qd_measured { 2 * N } else { N };
    let mut left: Vec<Vec<f64>> = vec![Vec::new(); N];
    let mut k0 = a;
    while k0 + BLOCK <= z {
        if !sig.mask.clear(k0, k0 + BLOCK) {
            k0 += BLOCK;
            continue;
        }
        let x = DMatrix::from_fn(BLOCK, cols, |r, c| {
            if c < N {
                eq[k0 + r][c]
            } else {
                eqd[k0 + r][c - N]
            }
        });
        let svd = x.clone().svd(true, true);
        for (j, l) in left.iter_mut().enumerate() {
            let y = DVector::from_fn(BLOCK, |r, _| et[k0 + r][j]);
            match svd.solve(&y, 1e-12) {
                Ok(theta) => l.extend((&y - &x * theta).iter()),
                Err(_) => l.extend(y.iter()),
            }
        }
        k0 += BLOCK;
    }
    SVector::from_fn(|j, _| {
        if left[j].is_empty() {
            robust_std(
                &(a..z)
                    .filter(|&k| sig.mask.usable(k))
                    .map(|k| et[k][j])
                    .collect::<Vec<_>>(),
            )
        } else {
            robust_std(&left[j])
        }
    })
}
