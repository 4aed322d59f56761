//! From measured samples to what the diagnosis works on: smoothed positions,
//! velocities and accelerations (no double differencing of raw data), the
//! smoothed efforts, the nominal model's efforts along the measured motion,
//! their difference (the torque residual).

mod noise;
mod segments;

use std::sync::Arc;

use nalgebra::SVector;

use crate::data::Measured;
use crate::diagnose::along;
use crate::smoothing::SavitzkyGolay;
use dynamics_runtime::Robot;
pub use noise::SensorNoise;
use noise::{known_floor, sensor_levels};
pub use segments::Mask;

/// Half-width of the light smoother of velocities, s.
pub const LIGHT_HALF_WIDTH: f64 = 0.004;

/// One data set, prepared. The per-sample signals that do not change once
/// made are shared (`Arc`) by the copies of a record (the compound
/// explanation's, which change the model's efforts and the residual only).
#[derive(Debug, Clone)]
pub struct Signals<const N: usize> {
    /// Sample interval.
    pub dt: f64,
    /// First and one-past-last sample with a full filter window.
    pub range: (usize, usize),
    /// Times.
    pub t: Arc<[f64]>,
    /// Smoothed positions.
    pub q: Arc<[SVector<f64, N>]>,
    /// Smoothed velocities.
    pub qd: Arc<[SVector<f64, N>]>,
    /// Accelerations (derivative of the smoothing fit).
    pub qdd: Arc<[SVector<f64, N>]>,
    /// Whether the velocities were measured (the accelerations are then
    /// the first derivative of their smoothing fit; else the second of
    /// the positions').
    pub qd_measured: bool,
    /// Velocities smoothed only lightly (over [`LIGHT_HALF_WIDTH`]): the
    /// argument of effects that are nonlinear in the velocity, whose
    /// columns are then filtered as the residual shows them.
    pub qd_light: Arc<[SVector<f64, N>]>,
    /// Measured efforts, raw.
    pub tau_raw: Arc<[SVector<f64, N>]>,
    /// Measured efforts, smoothed.
    pub tau: Arc<[SVector<f64, N>]>,
    /// The nominal model's efforts along the smoothed motion.
    pub model: Vec<SVector<f64, N>>,
    /// Rate of the model efforts (derivative of their smoothing fit).
    pub model_rate: Arc<[SVector<f64, N>]>,
    /// `tau - model`.
    pub residual: Vec<SVector<f64, N>>,
    /// Noise floor of the smoothed residual per joint: what the sensors'
    /// noise makes of it (`noise.rs`; zero from [`Signals::unfloored`]).
    pub floor: SVector<f64, N>,
    /// The filter.
    pub sg: SavitzkyGolay,
    /// Which samples a fit may use (holes and filled samples excluded).
    pub mask: Mask,
}

fn column<const N: usize>(v: &[SVector<f64, N>], j: usize) -> Vec<f64> {
    v.iter().map(|x| x[j]).collect()
}

fn set_column<const N: usize>(v: &mut [SVector<f64, N>], j: usize, x: &[f64]) {
    for (a, b) in v.iter_mut().zip(x) {
        a[j] = *b;
    }
}

impl<const N: usize> Signals<N> {
    /// The signals of `m` for `robot` with the noise floor of the torque
    /// residual that sensor noise of `levels` (q, qd, tau per joint) makes
    /// of it, the levels estimated from the data when not known
    /// (`noise.rs`); and the levels used.
    pub fn new<R: Robot<N>>(
        robot: &R,
        m: &Measured<N>,
        levels: Option<&[SVector<f64, N>; 3]>,
        chunk: usize,
    ) -> (Self, [SVector<f64, N>; 3]) {
        let mut sig = Self::unfloored_chunked(robot, m, chunk);
        let levels = match levels {
            Some(l) => *l,
            None => sensor_levels(m, &sig),
        };
        sig.floor = known_floor(robot, m, &sig, &levels);
        (sig, levels)
    }

    /// The signals of `m` for `robot` without a noise floor (zero): what
    /// an identification by plain least squares, and the floor's own noisy
    /// twin, work on.
    pub fn unfloored<R: Robot<N>>(robot: &R, m: &Measured<N>) -> Self {
        Self::unfloored_chunked(robot, m, 0)
    }

    /// [`Signals::unfloored`], the model evaluated `chunk` samples at a
    /// time (`along.rs`; 0: the default).
    pub fn unfloored_chunked<R: Robot<N>>(robot: &R, m: &Measured<N>, chunk: usize) -> Self {
        let n = m.len();
        let dt = m.sample_interval();
        let sg = SavitzkyGolay::analysis(dt);
        let half = sg.half();
        let zero = vec![SVector::<f64, N>::zeros(); n];
        let (mut q, mut qd, mut qdd, mut tau) =
            (zero.clone(), zero.clone(), zero.clone(), zero.clone());
        let mut qd_light = zero.clone();
        let light = SavitzkyGolay::new(((LIGHT_HALF_WIDTH / dt).round() as usize).max(2), dt);
        for j in 0..N {
            let qj = column(&m.q, j);
            // Efforts are held from each sample to the next (zero-order
            // hold): centred on a sample, the held signal averages this
            // sample's value and the previous one's (half a sample late
            // otherwise, a delay the fit would read as an effect).
            let raw = column(&m.tau, j);
            let tj: Vec<f64> = (0..n)
                .map(|k| 0.5 * (raw[k.saturating_sub(1)] + raw[k]))
                .collect();
            set_column(&mut q, j, &sg.apply(&qj, 0));
            if m.qd_measured {
                let vj = column(&m.qd, j);
                set_column(&mut qd, j, &sg.apply(&vj, 0));
                set_column(&mut qdd, j, &sg.apply(&vj, 1));
                set_column(&mut qd_light, j, &light.apply(&vj, 0));
            } else {
                set_column(&mut qd_light, j, &light.apply(&qj, 1));
                set_column(&mut qd, j, &sg.apply(&qj, 1));
                set_column(&mut qdd, j, &sg.apply(&qj, 2));
            }
            set_column(&mut tau, j, &sg.apply(&tj, 0));
        }
        let range = (half, n.saturating_sub(half));
        let mut model = zero.clone();
        let mut residual = zero;
        along::inverse_dynamics(robot, [&q, &qd, &qdd], range.0..range.1, chunk, &mut model);
        for k in range.0..range.1 {
            residual[k] = tau[k] - model[k];
        }
        let mut model_rate = vec![SVector::<f64, N>::zeros(); n];
        for j in 0..N {
            let mj: Vec<f64> = (0..n)
                .map(|k| {
                    if k >= range.0 && k < range.1 {
                        model[k][j]
                    } else {
                        f64::NAN
                    }
                })
                .collect();
            set_column(&mut model_rate, j, &sg.apply(&mj, 1));
        }
        let mask = Mask::new(m, half, range);
        Signals {
            mask,
            model_rate: model_rate.into(),
            dt,
            range,
            t: m.t.as_slice().into(),
            q: q.into(),
            qd: qd.into(),
            qdd: qdd.into(),
            qd_measured: m.qd_measured,
            qd_light: qd_light.into(),
            tau_raw: m.tau.as_slice().into(),
            tau: tau.into(),
            model,
            residual,
            floor: SVector::zeros(),
            sg,
        }
    }

    /// Number of samples with a full window.
    pub fn valid(&self) -> usize {
        self.range.1.saturating_sub(self.range.0)
    }
}

/// 1.4826 x median absolute deviation from the median.
pub fn robust_std(x: &[f64]) -> f64 {
    if x.is_empty() {
        return 0.0;
    }
    let mut v = x.to_vec();
    v.sort_by(f64::total_cmp);
    let med = v[v.len() / 2];
    let mut dev: Vec<f64> = v.iter().map(|a| (a - med).abs()).collect();
    dev.sort_by(f64::total_cmp);
    1.4826 * dev[dev.len() / 2]
}
