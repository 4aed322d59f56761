//! Fitting every candidate to one data set's torque residual and scoring
//! it against the rigid model alone.

use nalgebra::{DMatrix, DVector, SVector};

use super::basis::Basis;
use super::candidate::Candidate;
use super::fit::{aicc, constrained_least_squares};
use super::motor::{motor_transmitted, MotorGuess};
use super::motor_fit;
use super::noise::{known_floor, sensor_levels};
use super::prior::EFFORT_SCALE_LIMIT;
use super::signals::Signals;
use crate::data::Measured;
use crate::effects::Effect;
use dynamics_runtime::Robot;

/// A data set ready for fitting: signals, shared model quantities, and the
/// (decimated) sample rows the fit uses.
#[derive(Debug, Clone)]
pub struct Prepared<const N: usize> {
    /// Signals.
    pub sig: Signals<N>,
    /// Shared quantities.
    pub basis: Basis<N>,
    /// Sample indices used as rows (every half-window, away from the edges).
    pub rows: Vec<usize>,
    /// Sensor noise levels per joint (q, qd, tau; stated, or estimated
    /// from the data) behind the noise floor and the prediction yardstick.
    pub levels: [SVector<f64, N>; 3],
}

impl<const N: usize> Prepared<N> {
    /// Prepares `m` for `robot`.
    pub fn new<R: Robot<N>>(robot: &R, m: &Measured<N>) -> Self {
        Self::with_noise(robot, m, None)
    }

    /// Prepares `m` for `robot`; the torque residual's noise floor is what
    /// sensor noise of `levels` (q, qd, tau per joint) makes of it, the
    /// levels estimated from the data when not known (`noise.rs`).
    pub fn with_noise<R: Robot<N>>(
        robot: &R,
        m: &Measured<N>,
        levels: Option<&[SVector<f64, N>; 3]>,
    ) -> Self {
        let mut sig = Signals::new(robot, m);
        let levels = match levels {
            Some(l) => *l,
            None => sensor_levels(m, &sig),
        };
        sig.floor = known_floor(robot, m, &sig, &levels);
        let basis = Basis::new(robot, &sig);
        let h = sig.sg.half();
        let (a, z) = sig.range;
        let rows = (a + h..z.saturating_sub(h))
            .step_by(h.max(1))
            .filter_map(|k| row_near(&sig, k, h))
            .collect();
        Prepared {
            sig,
            basis,
            rows,
            levels,
        }
    }

    /// Whitened residual sum of squares of `r` over the rows.
    pub fn sse(&self, r: &[SVector<f64, N>]) -> f64 {
        self.rows
            .iter()
            .map(|&k| {
                (0..N)
                    .map(|j| (r[k][j] / self.sig.floor[j]).powi(2))
                    .sum::<f64>()
            })
            .sum()
    }

    /// Number of scalar rows.
    pub fn n(&self) -> usize {
        self.rows.len() * N
    }
}

/// The usable sample nearest after `k` within a row spacing, if any (a
/// row skips a filled sample but not a whole stretch of them).
fn row_near<const N: usize>(sig: &Signals<N>, k: usize, h: usize) -> Option<usize> {
    (k..k + h.max(1)).find(|&i| sig.mask.usable(i))
}

/// A fitted candidate.
#[derive(Debug, Clone)]
pub struct Fit {
    /// The candidate.
    pub candidate: Candidate,
    /// Linear parameters (empty for motor-side candidates).
    pub theta: Vec<f64>,
    /// Their standard deviations.
    pub std: Vec<f64>,
    /// Motor-side parameters of elasticity and backlash.
    pub motor: Option<MotorGuess>,
    /// Their standard deviations (elasticity and backlash).
    pub motor_std: Option<MotorGuess>,
    /// Whitened residual sum of squares on the training rows.
    pub sse: f64,
    /// Number of parameters.
    pub k: usize,
}

impl Fit {
    /// The fitted effect.
    pub fn effect(&self) -> Option<Effect> {
        match (self.candidate, self.motor) {
            (Candidate::Elasticity(j), Some(g)) => Some(g.effect(false, j)),
            (Candidate::Backlash(j), Some(g)) => Some(g.effect(true, j)),
            (c, _) => c.effect(&self.theta),
        }
    }

    /// The smoothed residual of `p` once this effect is added to the model.
    pub fn corrected<const N: usize>(&self, p: &Prepared<N>) -> Vec<SVector<f64, N>> {
        let mut r = p.sig.residual.clone();
        let (a, z) = p.sig.range;
        match (self.candidate, self.motor) {
            (Candidate::Elasticity(j), Some(g))
            | (Candidate::Backlash(j), Some(g))
            | (Candidate::Armature(j), Some(g)) => {
                let backlash = matches!(self.candidate, Candidate::Backlash(_));
                let t = motor_transmitted(&p.sig, j, &g, backlash, &p.basis.compliance);
                for k in a..z {
                    if t[k].is_finite() {
                        r[k][j] = t[k] - p.sig.model[k][j];
                    }
                }
            }
            (c, _) => {
                for (k, rk) in r.iter_mut().enumerate().take(z).skip(a) {
                    let cols = c.columns(&p.sig, &p.basis, k);
                    for (i, th) in self.theta.iter().enumerate() {
                        *rk -= cols[i] * *th;
                    }
                }
            }
        }
        r
    }

    /// AICc on `n` rows.
    pub fn aicc(&self, n: usize) -> f64 {
        aicc(self.sse, n, self.k)
    }
}

/// Fits `c` to the residual of `p`.
pub fn fit<R: Robot<N>, const N: usize>(c: Candidate, p: &Prepared<N>) -> Fit {
    let params = c.linear_parameters();
    if params.is_empty() {
        return motor_fit::fit_motor::<R, N>(c, p);
    }
    let m = params.len();
    let n = p.n();
    let mut x = DMatrix::zeros(n, m);
    let mut y = DVector::zeros(n);
    for (r, &k) in p.rows.iter().enumerate() {
        let cols = c.columns(&p.sig, &p.basis, k);
        for j in 0..N {
            let w = 1.0 / p.sig.floor[j];
            y[r * N + j] = p.sig.residual[k][j] * w;
            for i in 0..m {
                x[(r * N + j, i)] = cols[i][j] * w;
            }
        }
    }
    let nonneg: Vec<bool> = params.iter().map(|p| p.1).collect();
    let mut f = constrained_least_squares(&x, &y, &nonneg);
    // An effort scale beyond its limit is held there, as in the compound
    // explanation (`prior::EFFORT_SCALE_LIMIT`).
    if let (Candidate::EffortScale(_), [s]) = (c, f.theta.as_slice()) {
        if s.abs() > EFFORT_SCALE_LIMIT {
            let held = EFFORT_SCALE_LIMIT.copysign(*s);
            f.sse = (&y - x.column(0) * held).norm_squared();
            f.theta = vec![held];
            f.std = vec![0.0];
        }
    }
    let linear = Fit {
        candidate: c,
        theta: f.theta,
        std: f.std,
        motor: None,
        motor_std: None,
        sse: f.sse,
        k: m,
    };
    match c {
        Candidate::Armature(j) => motor_fit::stiff_rotor(linear, j, p),
        _ => linear,
    }
}

/// Joint `j`'s whitening weight, the nominal model's whitened SSE over all
/// joints, and joint `j`'s share of it: what a model changing only joint
/// `j`'s effort starts from.
pub(super) fn whitened_nominal<const N: usize>(p: &Prepared<N>, j: usize) -> (f64, f64, f64) {
    let w = 1.0 / p.sig.floor[j];
    let own = p
        .rows
        .iter()
        .map(|&k| (p.sig.residual[k][j] * w).powi(2))
        .sum();
    (w, p.sse(&p.sig.residual), own)
}
