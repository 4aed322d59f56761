//! The diagnosis of data files, and the time series behind its readable
//! report.

use std::path::Path;

use dynamics_runtime::Robot;
use dynamics_sim2real::baseline::undo;
use dynamics_sim2real::data::Measured;
use dynamics_sim2real::diagnose::traces::{traces, Traces};
use dynamics_sim2real::diagnose::{diagnose_owned, Options, Report};
use dynamics_sim2real::effects::Calibrated;
use dynamics_sim2real::explained;

use super::{DataFile, GapError};

/// Diagnoses `train` against `holdout` (CSV files) for `robot`; the
/// report's warnings (reading and preparing the files, what the data
/// cannot show) come back beside it as the sentences to print (a row's
/// glitches as one: [`crate::warnings::lines`]).
pub fn diagnose_files<R: Robot<N> + Clone + Send + Sync + 'static, const N: usize>(
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
pub fn diagnose_data<R: Robot<N> + Clone + Send + Sync + 'static, const N: usize>(
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
pub fn diagnose_data_described<R: Robot<N> + Clone + Send + Sync + 'static, const N: usize>(
    robot: &R,
    train: &DataFile,
    holdout: &DataFile,
    options: &Options,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<(Report, Vec<String>, Vec<String>), GapError> {
    diagnose_read(robot, &Ok, train, holdout, options, progress)
}

/// [`diagnose_data_described`] against a calibrated baseline: `robot` with
/// the baseline's model effects folded in ([`Calibrated`]), and what it
/// keeps apart (the sensors' effects, motor sides, effects limited to a
/// window) undone on both records before the diagnosis
/// ([`dynamics_sim2real::baseline::undo`]).
pub fn diagnose_calibrated<R: Robot<N> + Clone + Send + Sync + 'static, const N: usize>(
    robot: &Calibrated<R, N>,
    train: &DataFile,
    holdout: &DataFile,
    options: &Options,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<(Report, Vec<String>, Vec<String>), GapError> {
    let fix = |m: Measured<N>| undone(robot, m);
    diagnose_read(robot, &fix, train, holdout, options, progress)
}

/// `m` with what `robot` keeps apart from its model undone (as it is when
/// the baseline is all model).
fn undone<R: Robot<N> + Clone + Send + Sync + 'static, const N: usize>(
    robot: &Calibrated<R, N>,
    m: Measured<N>,
) -> Result<Measured<N>, GapError> {
    if robot.model_only() {
        return Ok(m);
    }
    undo(robot, &m).map_err(|e| GapError::Request(format!("--baseline: {e}")))
}

/// Reads both files, each on a thread of its own, corrects each by `fix`
/// (the record as read is dropped once corrected: a long log is not held
/// twice) and diagnoses them, handing the records over (the diagnosis
/// shares them, not copies them). An error of the training file is told
/// before one of the held-out file.
fn diagnose_read<R: Robot<N> + Clone + Send + Sync + 'static, const N: usize>(
    robot: &R,
    fix: &(dyn Fn(Measured<N>) -> Result<Measured<N>, GapError> + Sync),
    train: &DataFile,
    holdout: &DataFile,
    options: &Options,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<(Report, Vec<String>, Vec<String>), GapError> {
    let read = |file: &DataFile| -> Result<(Measured<N>, Option<String>), GapError> {
        let (m, about) = file.read_described(&R::JOINT_NAMES)?;
        Ok((fix(m)?, about))
    };
    let (a, b) = std::thread::scope(|s| {
        let b = s.spawn(|| read(holdout));
        (read(train), b.join())
    });
    let (a, about_a) = a?;
    let (b, about_b) = b.unwrap_or_else(|panic| std::panic::resume_unwind(panic))?;
    let report = diagnose_owned(robot, a, b, options, progress)?;
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
pub fn traces_files<R: Robot<N> + Clone + Send + Sync + 'static, const N: usize>(
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
pub fn traces_data<R: Robot<N> + Clone + Send + Sync + 'static, const N: usize>(
    robot: &R,
    train: &DataFile,
    holdout: &DataFile,
    report: &Report,
    options: &Options,
) -> Result<Traces, GapError> {
    let a = train.read(&R::JOINT_NAMES)?;
    let b = holdout.read(&R::JOINT_NAMES)?;
    traces_of(robot, &a, &b, report, options)
}

/// [`traces_data`] against a calibrated baseline: the records corrected
/// as [`diagnose_calibrated`] corrects them, so that the figures show what
/// the diagnosis saw.
pub fn traces_calibrated<R: Robot<N> + Clone + Send + Sync + 'static, const N: usize>(
    robot: &Calibrated<R, N>,
    train: &DataFile,
    holdout: &DataFile,
    report: &Report,
    options: &Options,
) -> Result<Traces, GapError> {
    let a = undone(robot, train.read(&R::JOINT_NAMES)?)?;
    let b = undone(robot, holdout.read(&R::JOINT_NAMES)?)?;
    traces_of(robot, &a, &b, report, options)
}

fn traces_of<R: Robot<N> + Clone + Send + Sync + 'static, const N: usize>(
    robot: &R,
    a: &Measured<N>,
    b: &Measured<N>,
    report: &Report,
    options: &Options,
) -> Result<Traces, GapError> {
    if !report.which.effects.is_empty() {
        return Ok(explained::traces(robot, a, b, report, options)?);
    }
    let chosen = report
        .which
        .verdict
        .names_effect()
        .then(|| report.which.ranked.first())
        .flatten();
    Ok(traces(robot, a, b, chosen, options)?)
}
