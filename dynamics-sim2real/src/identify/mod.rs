//! The plain least-squares identification baseline: per joint Coulomb
//! friction, viscous friction, a constant offset and rotor inertia, plus
//! corrections to every link's ten inertial parameters (the emitted
//! regressor `Robot::inertial_regressor`), fitted to the torque the
//! nominal model misses on training data, reduced to the base parameters
//! the data determine, and judged by the held-out torque it leaves.
//!
//! Signals are prepared as the diagnosis prepares them
//! (`diagnose::Signals`: one Savitzky-Golay smoothing of 40 ms half-width,
//! accelerations from its derivative); every column is smoothed once more
//! by the same filter, as the measured efforts are. Rows are whitened per
//! joint in two passes (first by the residual's RMS, then by what the first
//! fit leaves). Base parameters: columns taken in order (joints' columns
//! first, then each link's), a column kept when more than
//! [`Options::rank_tolerance`] of it (unit norm) lies outside the span of
//! those kept before it; each dropped column is reported as the
//! combination of kept ones it equals.

mod columns;
mod solve;

pub use crate::regressor::Column;

use nalgebra::{DVector, SVector};
use thiserror::Error;

use crate::data::Measured;
use crate::diagnose::Signals;
use dynamics_runtime::Robot;

/// Options of [`identify`].
#[derive(Debug, Clone, PartialEq)]
pub struct Options {
    /// Velocity scale of the smooth sign `tanh(qd / zone)` of the Coulomb
    /// columns, rad/s or m/s.
    pub sign_zone: f64,
    /// A column is kept when more than this fraction of it (unit norm,
    /// whitened rows) lies outside the span of the columns kept before it.
    pub rank_tolerance: f64,
    /// Rows every this many seconds (at least one sample).
    pub row_interval: f64,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            sign_zone: crate::effects::SIGN_SMOOTHING,
            rank_tolerance: 1e-4,
            row_interval: 0.01,
        }
    }
}

/// Why an identification could not be made.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum IdentifyError {
    /// Too few samples with a full smoothing window.
    #[error("{which} data: {rows} usable rows for {columns} parameters; record longer")]
    TooShort {
        /// `training` or `held-out`.
        which: &'static str,
        /// Rows available.
        rows: usize,
        /// Parameters to fit.
        columns: usize,
    },
    /// The least-squares problem has no solution (nothing excited, or
    /// values that are not finite).
    #[error("the least-squares fit could not be made: {reason}")]
    NoFit {
        /// Why.
        reason: String,
    },
}

/// A fitted value and its standard deviation (`None` when the data do not
/// determine it on its own: a dropped column, whose effect is in the kept
/// ones it is a combination of).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Estimate {
    /// Value (SI units).
    pub value: f64,
    /// Standard deviation.
    pub std: Option<f64>,
}

/// One joint's fitted terms.
#[derive(Debug, Clone, PartialEq)]
pub struct JointTerms {
    /// Joint name.
    pub joint: &'static str,
    /// Coulomb level (N m or N; positive opposes the motion).
    pub coulomb: Estimate,
    /// Viscous coefficient (positive opposes the motion).
    pub viscous: Estimate,
    /// Constant effort offset (measured minus model).
    pub offset: Estimate,
    /// Rotor inertia (kg m^2 or kg).
    pub armature: Estimate,
    /// Held-out torque residual RMS before (nominal model).
    pub holdout_before: f64,
    /// Held-out torque residual RMS after (model plus the fit).
    pub holdout_after: f64,
}

/// One link's fitted parameter corrections (Pinocchio's order, see
/// [`crate::inertial`]).
#[derive(Debug, Clone, PartialEq)]
pub struct LinkTerms {
    /// Link name (`Robot::LINK_NAMES`).
    pub link: &'static str,
    /// Nominal parameters.
    pub nominal: SVector<f64, 10>,
    /// Fitted corrections (base-parameter values: dropped ones are 0).
    pub delta: [Estimate; 10],
}

/// A column the data do not determine on its own.
#[derive(Debug, Clone, PartialEq)]
pub struct Dropped {
    /// Its name, e.g. `panda_link1 m c_z`.
    pub column: String,
    /// The kept columns it equals a combination of, with coefficients
    /// (empty: the column is zero on these data).
    pub combination: Vec<(String, f64)>,
}

/// The identification and how far it shrinks the held-out gap.
#[derive(Debug, Clone, PartialEq)]
pub struct Identification {
    /// Per joint: friction, offset, rotor inertia, held-out RMS.
    pub joints: Vec<JointTerms>,
    /// Per link of `Robot::LINK_NAMES`.
    pub links: Vec<LinkTerms>,
    /// Columns offered and kept (the number of base parameters).
    pub columns: usize,
    /// Base parameters fitted.
    pub rank: usize,
    /// What was dropped, and what it is a combination of.
    pub dropped: Vec<Dropped>,
    /// Training rows (samples x joints).
    pub train_rows: usize,
    /// `1 - ||after|| / ||before||` of the held-out torque residual over
    /// all joints and rows (noise included).
    pub shrink: f64,
}

/// Fits the baseline on `train` and judges it on `holdout`.
///
/// ```
/// use dynamics_sim2real::effects::Effect;
/// use dynamics_sim2real::identify::{identify, Options};
/// use dynamics_sim2real::synth::{synthesize, SynthOptions};
/// dynamics_macros::robot! {
///     pub robot Pendulum;
///     gravity = [0.0, -9.81, 0.0];
///     link base;
///     link rod { mass = 1.0; com = [0.5, 0.0, 0.0]; inertia = [1e-4, 0.02, 0.02]; }
///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
/// }
/// let robot = Pendulum::default();
/// let truth = [Effect::ViscousFriction { joint: 0, fv: 0.3 }];
/// let opts = |seed| SynthOptions::<1> { duration: 4.0, seed, ..Default::default() };
/// let train = synthesize(&robot, &truth, &opts(1)).unwrap();
/// let holdout = synthesize(&robot, &truth, &opts(2)).unwrap();
/// let id = identify(&robot, &train, &holdout, &Options::default()).unwrap();
/// let fv = id.joints[0].viscous;
/// assert!((fv.value - 0.3).abs() < 0.02, "{fv:?}");
/// assert!(id.shrink > 0.5);
/// ```
pub fn identify<R: Robot<N>, const N: usize>(
    robot: &R,
    train: &Measured<N>,
    holdout: &Measured<N>,
    options: &Options,
) -> Result<Identification, IdentifyError> {
    let cols = crate::regressor::all::<R, N>();
    let prepare = |m: &Measured<N>, which| {
        let sig = Signals::unfloored(robot, m);
        let stride = (options.row_interval / sig.dt.max(1e-12)).round().max(1.0) as usize;
        let rows = columns::rows(&sig, stride);
        if rows.len() * N <= cols.len() && which == "training" {
            return Err(IdentifyError::TooShort {
                which,
                rows: rows.len() * N,
                columns: cols.len(),
            });
        }
        if rows.is_empty() {
            return Err(IdentifyError::TooShort {
                which,
                rows: 0,
                columns: cols.len(),
            });
        }
        let (x, y) = columns::design(robot, &sig, &rows, &cols, options.sign_zone);
        Ok((x, y, stride, sig.sg.half()))
    };
    let (x, y, stride, half) = prepare(train, "training")?;
    let (xh, yh, ..) = prepare(holdout, "held-out")?;
    if x.iter().chain(y.iter()).any(|v| !v.is_finite()) {
        return Err(IdentifyError::NoFit {
            reason: "the training rows hold values that are not finite".into(),
        });
    }

    // Two passes of per-joint whitening.
    let per_joint_rms = |r: &DVector<f64>| -> [f64; N] {
        std::array::from_fn(|j| {
            let v: Vec<f64> = r.iter().skip(j).step_by(N).copied().collect();
            (v.iter().map(|a| a * a).sum::<f64>() / v.len().max(1) as f64).sqrt()
        })
    };
    let weights = |s: [f64; N]| {
        let top = s.iter().copied().fold(0.0, f64::max).max(1e-300);
        DVector::from_fn(y.len(), |r, _| 1.0 / s[r % N].max(1e-9 * top))
    };
    let tol = options.rank_tolerance;
    let no_fit = || IdentifyError::NoFit {
        reason: "no column is excited on the training data".into(),
    };
    let first = solve::solve(&x, &y, &weights(per_joint_rms(&y)), tol, 1.0).ok_or_else(no_fit)?;
    let resid = &y - &x * DVector::from_vec(first.theta.clone());
    let w = weights(per_joint_rms(&resid));
    let lags = (2 * half).div_ceil(stride);
    let vif = solve::variance_inflation(&resid.component_mul(&w), N, lags);
    let sol = solve::solve(&x, &y, &w, tol, vif).ok_or_else(no_fit)?;

    let theta = DVector::from_vec(sol.theta.clone());
    let after = &yh - &xh * &theta;
    let (before_j, after_j) = (per_joint_rms(&yh), per_joint_rms(&after));
    let shrink = if yh.norm() > 0.0 {
        1.0 - after.norm() / yh.norm()
    } else {
        0.0
    };
    let est = |c: usize| Estimate {
        value: sol.theta[c],
        std: sol.std[c],
    };
    let index = |col: Column| cols.iter().position(|c| *c == col).unwrap_or(0);
    let joints = (0..N)
        .map(|j| JointTerms {
            joint: R::JOINT_NAMES[j],
            coulomb: est(index(Column::Coulomb(j))),
            viscous: est(index(Column::Viscous(j))),
            offset: est(index(Column::Offset(j))),
            armature: est(index(Column::Armature(j))),
            holdout_before: before_j[j],
            holdout_after: after_j[j],
        })
        .collect();
    let mut nominal = vec![SVector::<f64, 10>::zeros(); R::LINK_NAMES.len()];
    robot
        .inertial_parameters(&mut nominal)
        .map_err(|e| IdentifyError::NoFit {
            reason: e.to_string(),
        })?;
    let links = (0..R::LINK_NAMES.len())
        .map(|l| LinkTerms {
            link: R::LINK_NAMES[l],
            nominal: nominal[l],
            delta: std::array::from_fn(|k| est(index(Column::Link(l, k)))),
        })
        .collect();
    let dropped = sol
        .dropped
        .iter()
        .map(|(d, combo)| Dropped {
            column: cols[*d].name::<R, N>(),
            combination: combo
                .iter()
                .map(|&(c, v)| (cols[c].name::<R, N>(), v))
                .collect(),
        })
        .collect();
    Ok(Identification {
        joints,
        links,
        columns: cols.len(),
        rank: sol.kept.len(),
        dropped,
        train_rows: y.len(),
        shrink,
    })
}
