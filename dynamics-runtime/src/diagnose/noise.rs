//! Sensor noise the user knows (from the data sheet or a still recording):
//! the torque residual's noise floor then comes from it, by pushing one
//! draw of that noise through the same smoothing and inverse dynamics as
//! the data, instead of being estimated from the data (where an effect
//! with fast content could pass for noise).

use nalgebra::SVector;

use super::signals::Signals;
use super::DiagnoseError;
use crate::data::Measured;
use crate::synth::Rng;
use crate::Robot;

/// Per-sample standard deviations of the sensors, each either one value
/// for every joint or one per joint (in joint order).
///
/// ```
/// use dynamics_runtime::diagnose::{Options, SensorNoise};
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
    pub(super) fn per_joint<const N: usize>(&self) -> Result<[SVector<f64, N>; 3], DiagnoseError> {
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
pub(super) fn known_floor<R: Robot<N>, const N: usize>(
    robot: &R,
    m: &Measured<N>,
    sig: &Signals<N>,
    levels: &[SVector<f64, N>; 3],
) -> SVector<f64, N> {
    let mut rng = Rng::new(0x5e_0015e);
    let mut noisy = m.clone();
    let mut draw = |sigma: &SVector<f64, N>| -> SVector<f64, N> {
        SVector::from_fn(|j, _| sigma[j] * rng.normal())
    };
    for k in 0..noisy.len() {
        noisy.q[k] += draw(&levels[0]);
        noisy.qd[k] += draw(&levels[1]);
        noisy.tau[k] += draw(&levels[2]);
    }
    let shaken = Signals::new(robot, &noisy);
    let (a, z) = sig.range;
    let mut sum = SVector::<f64, N>::zeros();
    for k in a..z {
        let d = shaken.residual[k] - sig.residual[k];
        sum += d.component_mul(&d);
    }
    (sum / (z - a).max(1) as f64).map(|s| s.sqrt().max(1e-12))
}
