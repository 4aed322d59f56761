//! The diagnosis of data files, and the time series behind its readable
//! report.

use std::path::Path;

use dynamics_runtime::Robot;
use dynamics_sim2real::data::Measured;
use dynamics_sim2real::diagnose::traces::{traces, Traces};
use dynamics_sim2real::diagnose::{diagnose, Options, Report};
use dynamics_sim2real::effects::{undo_sensors, Effect};
use dynamics_sim2real::explained;

use super::{DataFile, GapError};

/// Diagnoses `train` against `holdout` (CSV files) for `robot`; the
/// report's warnings (reading and preparing the files, what the data
/// cannot show) come back beside it as the sentences to print (a row's
/// glitches as one: [`crate::warnings::lines`]).
pub fn diagnose_files<R: Robot<N> + Clone + Sync, const N: usize>(
    robot: &R,
    train: &Path,
    holdout: &Path,
    options: &Options,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<(Report, Vec<String>), GapError> {
    diagnose_data(
        robot,
        &DataFile::csv(train),
        &DataFile::csv(holdout),
        options,
        progress,
    )
}

/// [`diagnose_files`] on data files of any layout ([`DataFile`]).
pub fn diagnose_data<R: Robot<N> + Clone + Sync, const N: usize>(
    robot: &R,
    train: &DataFile,
    holdout: &DataFile,
    options: &Options,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<(Report, Vec<String>), GapError> {
    diagnose_data_described(robot, train, holdout, options, progress).map(|(r, w, _)| (r, w))
}

/// [`diagnose_data`], and what was read of each file that says more than
/// its samples (a bag's topic, message count and time range: the lines of
/// the report's header).
pub fn diagnose_data_described<R: Robot<N> + Clone + Sync, const N: usize>(
    robot: &R,
    train: &DataFile,
    holdout: &DataFile,
    options: &Options,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<(Report, Vec<String>, Vec<String>), GapError> {
    diagnose_calibrated(robot, &[], train, holdout, options, progress)
}

/// [`diagnose_data_described`] against a calibrated baseline: `robot` with
/// the baseline's model effects folded in
/// ([`dynamics_sim2real::effects::Calibrated`]), and `sensors`, the
/// baseline's effects on the sensors, undone on both records before the
/// diagnosis ([`dynamics_sim2real::effects::undo_sensors`]).
pub fn diagnose_calibrated<R: Robot<N> + Clone + Sync, const N: usize>(
    robot: &R,
    sensors: &[Effect],
    train: &DataFile,
    holdout: &DataFile,
    options: &Options,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<(Report, Vec<String>, Vec<String>), GapError> {
    let (a, about_a) = train.read_described(&R::JOINT_NAMES)?;
    let (b, about_b) = holdout.read_described(&R::JOINT_NAMES)?;
    // The records as read are dropped once the sensors' effects are undone
    // (a long log is not held twice).
    let undo = |m: Measured<N>| {
        if sensors.is_empty() {
            m
        } else {
            undo_sensors(&m, sensors)
        }
    };
    let (a, b) = (undo(a), undo(b));
    let report = diagnose(robot, &a, &b, options, progress)?;
    let warnings = crate::warnings::lines(&report.warnings);
    let about = [
        about_a.map(|s| format!("training data: {s}")),
        about_b.map(|s| format!("held-out data: {s}")),
    ]
    .into_iter()
    .flatten()
    .collect();
    Ok((report, warnings, about))
}

/// The time series behind `report` (the readable report's plots), from the
/// same CSV files: the model with the whole explanation
/// ([`dynamics_sim2real::explained::traces`]); where the explanation names
/// nothing, the chosen single effect (none when the verdict is `none`)
/// refitted on `train` and applied to `holdout`. Example: with
/// [`crate::report::write`].
pub fn traces_files<R: Robot<N> + Clone, const N: usize>(
    robot: &R,
    train: &Path,
    holdout: &Path,
    report: &Report,
    options: &Options,
) -> Result<Traces, GapError> {
    traces_data(
        robot,
        &DataFile::csv(train),
        &DataFile::csv(holdout),
        report,
        options,
    )
}

/// [`traces_files`] on data files of any layout ([`DataFile`]).
pub fn traces_data<R: Robot<N> + Clone, const N: usize>(
    robot: &R,
    train: &DataFile,
    holdout: &DataFile,
    report: &Report,
    options: &Options,
) -> Result<Traces, GapError> {
    if !report.which.effects.is_empty() {
        let a = train.read(&R::JOINT_NAMES)?;
        let b = holdout.read(&R::JOINT_NAMES)?;
        return Ok(explained::traces(robot, &a, &b, report, options)?);
    }
    let chosen = report
        .which
        .verdict
        .names_effect()
        .then(|| report.which.ranked.first())
        .flatten();
    traces_for(robot, train, holdout, chosen, options)
}

fn traces_for<R: Robot<N> + Clone, const N: usize>(
    robot: &R,
    train: &DataFile,
    holdout: &DataFile,
    chosen: Option<&dynamics_sim2real::diagnose::Ranked>,
    options: &Options,
) -> Result<Traces, GapError> {
    let a = train.read(&R::JOINT_NAMES)?;
    let b = holdout.read(&R::JOINT_NAMES)?;
    Ok(traces(robot, &a, &b, chosen, options)?)
}
