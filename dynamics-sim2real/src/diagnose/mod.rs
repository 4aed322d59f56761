//! Sim-to-real gap diagnosis: given a model and measured data, say WHERE
//! the model and the robot disagree (joint, time windows, motion phase),
//! WHICH unmodelled effect explains it (every candidate of the vocabulary
//! fitted and ranked by a corrected information criterion), and HOW FAR
//! the gap shrinks on held-out data once that effect is added.
//!
//! Method: the torque residual `tau - ID(q, qd, qdd)` along the measured
//! motion, every signal smoothed by one Savitzky-Golay filter (40 ms
//! half-width; accelerations from its derivative, never from double
//! differencing), rows whitened by the residual's noise floor: one draw of
//! the sensor noise (levels stated by the user, or estimated from the
//! data) pushed through the same smoothing and inverse dynamics.
//! Effects linear in their parameters (friction, rotor inertia, payload,
//! resistance, encoder offset through the emitted perturbation Jacobian K,
//! delay through the measured effort's rate) are fitted by sign-constrained
//! least squares on columns filtered like the efforts: friction laws are
//! evaluated on a lightly smoothed velocity and then filtered as the
//! residual shows a force the motion takes (`force_filter.rs`: the
//! acceleration estimate's filter on the force's integral; the sign of a
//! smoothed velocity switches sharply where the residual does not);
//! columns built from the acceleration estimate are smoothed once
//! more, so that they do not add its noise a second time (rotor inertia
//! was otherwise taken for a stiff elastic joint). Elasticity and backlash
//! are fitted by a grid search on a motor-side simulation driven by the
//! measured effort (its link following the measured motion plus the
//! effect of the transmitted effort's departure from the model), refined by a compass search on the logarithms of their
//! parameters; their standard deviations come from the objective's
//! curvature there (`spread`). Rotor inertia is fitted both ways (its acceleration column,
//! and a rotor on a very stiff coupling simulated like the motor-side
//! models, which see the effort's fast content the same way) and keeps the
//! better. Candidates are ranked by AICc; a richer model nesting a
//! simpler one at the same joint (Stribeck over Coulomb, elasticity or
//! backlash over rotor inertia) must win by [`Options::nesting_margin`].

//!
//! # Stages
//!
//! One diagnosis runs six stages, each a folder whose imports go one way
//! (each uses only the stages listed after it, `numeric.rs`, and
//! `along.rs`, the one place the model is evaluated at every sample):
//!
//! 1. `explain/`: the report in the user's words (the only stage that
//!    knows the report's schema);
//! 2. `evaluate/`: where the gap is, the explanation on the held-out
//!    record, the shrink;
//! 3. `select/`: the single-effect ranking and the compound explanation;
//! 4. `fit/`: every candidate fitted on its own;
//! 5. `candidates/`: the vocabulary at every place, a record made ready
//!    for fitting, what the data can identify;
//! 6. `signals/`: smoothed signals, the noise floor, usable samples.
//!
//! [`diagnose`] runs them in the order of the data: signals and candidates,
//! fit, select, evaluate, explain.

mod along;
mod candidates;
mod error;
mod evaluate;
mod explain;
mod fit;
mod numeric;
mod options;
mod select;
mod signals;
pub mod traces;

pub use crate::smoothing::SavitzkyGolay;
pub use candidates::MotorGuess;
pub use candidates::{payload_com, Candidate, Channel, Prepared, Unnamed};
pub use error::DiagnoseError;
pub use evaluate::GapWindow;
pub use explain::report::*;
pub(crate) use fit::motor_transmitted_raw;
pub use fit::Fit;
pub use numeric::aicc;
pub use options::{CalibrationSpread, Options};
pub use select::{breakaway_data_needed, HeldLinks};
pub use signals::SensorNoise;
pub(crate) use signals::Signals;

use crate::data::Measured;
use candidates::{Record, Records};
use dynamics_runtime::Robot;
use std::sync::Arc;

/// Diagnoses the gap between `robot` and the measured `train` data, and
/// checks the chosen effect on `holdout`; `progress(done, total)` is called
/// as candidates are fitted. The work runs on [`Options::threads`] threads
/// (0: all cores); the result does not depend on how many.
///
/// ```
/// use dynamics_sim2real::diagnose::{diagnose, Options, Report};
/// use dynamics_runtime::Robot;
/// use dynamics_sim2real::data::Measured;
/// fn run<R: Robot<3> + Clone + Send + Sync + 'static>(robot: &R, train: &Measured<3>, holdout: &Measured<3>) -> Report {
///     diagnose(robot, train, holdout, &Options::default(), &|_, _| {}).expect("enough data")
/// }
/// ```
pub fn diagnose<R: Robot<N> + Clone + Send + Sync + 'static, const N: usize>(
    robot: &R,
    train: &Measured<N>,
    holdout: &Measured<N>,
    options: &Options,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<Report, DiagnoseError> {
    let (train, holdout) = (Record::Lent(train), Record::Lent(holdout));
    in_pool(options, || stages(robot, train, holdout, options, progress))
}

/// [`diagnose`] on records handed over rather than lent: the diagnosis
/// reads their times, raw efforts and velocities where they are instead
/// of copying them (some 120 bytes a sample of a 7-joint arm less held
/// through the diagnosis); the report is the same.
///
/// ```
/// use dynamics_sim2real::diagnose::{diagnose_owned, Options, Report};
/// use dynamics_runtime::Robot;
/// use dynamics_sim2real::data::Measured;
/// fn run<R: Robot<3> + Clone + Send + Sync + 'static>(robot: &R, train: Measured<3>, holdout: Measured<3>) -> Report {
///     diagnose_owned(robot, train, holdout, &Options::default(), &|_, _| {}).expect("enough data")
/// }
/// ```
pub fn diagnose_owned<R: Robot<N> + Clone + Send + Sync + 'static, const N: usize>(
    robot: &R,
    train: Measured<N>,
    holdout: Measured<N>,
    options: &Options,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<Report, DiagnoseError> {
    let train = Record::Shared(Arc::new(train));
    let holdout = Record::Shared(Arc::new(holdout));
    in_pool(options, || stages(robot, train, holdout, options, progress))
}

/// `run` on a thread pool of `options.threads` threads.
fn in_pool<T: Send>(
    options: &Options,
    run: impl FnOnce() -> Result<T, DiagnoseError> + Send,
) -> Result<T, DiagnoseError> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(options.threads)
        .build()
        .map_err(|e| DiagnoseError::Threads(e.to_string()))?
        .install(run)
}

/// The stages of [`diagnose`], in the order of the data.
fn stages<R: Robot<N> + Clone + Send + Sync + 'static, const N: usize>(
    robot: &R,
    train: Record<'_, N>,
    holdout: Record<'_, N>,
    options: &Options,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<Report, DiagnoseError> {
    // Both records prepared: signals, noise floors, what they can show.
    let mut records = Records::new(robot, train, holdout, options)?;
    // Every candidate the data can identify, fitted on its own.
    let candidates = candidates::offer(&mut records, options);
    let fitted = fit::fit_candidates::<R, N>(&candidates, &records.p, options, progress);
    // The single-effect ranking and the compound explanation.
    let selection = select::select(robot, &records.p, &records.h, fitted, options);
    // Where the gap is; the explanation on the held-out record.
    let evaluation = evaluate::evaluate(robot, &records, &selection, options);
    // The report.
    Ok(explain::report::<R, N>(
        robot,
        &records,
        &selection,
        &evaluation,
        options,
    ))
}
