//! One subcommand on one robot: the nominal model made (`--set`,
//! `--baseline`), then the subcommand's module called.

use std::path::Path;

use dynamics_runtime::Robot;
use dynamics_sim2real::effects::Calibrated;

use super::args::{BaselineArgs, CheckArgs, ModelArgs, RobotCommand};
use super::{RobotInfo, RobotVisitor};
use crate::tune::{apply_set, left_out, read_baseline_timed, read_calibration};
use crate::Res;

/// The robot with `--set` applied and the `--baseline` effects folded in
/// (those it keeps apart, for the data, with them).
fn nominal<R: Robot<N>, const N: usize>(
    mut robot: R,
    model: &ModelArgs,
    baseline: Option<&BaselineArgs>,
) -> Result<Calibrated<R, N>, Box<dyn std::error::Error>> {
    apply_set(&mut robot, &model.set)?;
    let effects = match baseline.and_then(|b| b.baseline.as_deref()) {
        Some(path) => {
            let effects = read_baseline_timed::<R, N>(path)?;
            eprintln!(
                "baseline from {}: {}",
                path.display(),
                if effects.is_empty() {
                    "no effects (its verdict names none)".to_string()
                } else {
                    effects
                        .iter()
                        .map(|(e, w)| match w {
                            Some(w) => format!("{e:?} in [{}, {}) s", w.start, w.end),
                            None => format!("{e:?}"),
                        })
                        .collect::<Vec<_>>()
                        .join("; ")
                }
            );
            effects
        }
        None => Vec::new(),
    };
    Ok(Calibrated::timed(robot, effects).map_err(|e| format!("--baseline: {e}"))?)
}

/// [`nominal`] for a command that uses the model alone (no measured data
/// to undo the rest on): what the baseline keeps apart from the model is
/// said to be left out.
fn model_alone<R: Robot<N>, const N: usize>(
    robot: R,
    model: &ModelArgs,
    baseline: &BaselineArgs,
    command: &str,
) -> Result<Calibrated<R, N>, Box<dyn std::error::Error>> {
    let r = nominal(robot, model, Some(baseline))?;
    if let Some(warning) = left_out(&r, command) {
        eprintln!("warning: {warning}");
    }
    Ok(r)
}

/// Runs `command` on `robot`.
pub fn run_on<R: Robot<N> + Clone + Send + Sync + 'static, const N: usize>(
    robot: R,
    info: &RobotInfo,
    command: RobotCommand,
) -> Res {
    match command {
        RobotCommand::Check(args) => match check(robot, info, &args)? {
            Some(true) => Ok(()),
            Some(false) => Err("some values differ from the reference by more than 1e-10".into()),
            None => Err(format!(
                "no reference values for `{}`: give --reference FILE.json",
                info.name
            )
            .into()),
        },
        RobotCommand::Eval(args) => {
            let robot = model_alone(robot, &args.model, &args.baseline, "eval")?;
            let states = info.states.as_ref().map(|(f, t)| (f.as_str(), t.as_str()));
            crate::commands::eval(&info.name, robot, states, args.states, args.out)
        }
        RobotCommand::Simulate(args) => {
            let robot = model_alone(robot, &args.model, &args.baseline, "simulate")?;
            crate::simulate::simulate(&robot, info, &args)
        }
        RobotCommand::Synth(a) => {
            let robot = model_alone(robot, &a.model, &a.baseline, "synth")?;
            crate::commands::synth_cmd(
                &robot,
                &info.motion,
                &info.name,
                a.effect,
                a.joint,
                a.magnitude,
                a.seed,
                &crate::commands::Followed {
                    excitation: a.excitation.clone(),
                    motion: a.motion.clone(),
                    duration: a.duration,
                },
                [a.noise_q, a.noise_qd, a.noise_tau],
                &a.out,
                a.truth,
                &crate::gap::Recording {
                    rate: a.rate,
                    damage: dynamics_sim2real::synth::Damage {
                        jitter: a.jitter,
                        repeats: a.repeats,
                        holes: a.holes,
                        glitches: a.glitches,
                        q_late: a.q_late,
                        tau_late: a.tau_late,
                        ..Default::default()
                    },
                    window: a
                        .window
                        .as_deref()
                        .map(str::parse)
                        .transpose()
                        .map_err(|e| format!("--window: {e}"))?,
                },
            )
        }
        RobotCommand::Diagnose(a) => {
            let mut options = a.options();
            if let Some(path) = a.baseline.baseline.as_deref() {
                options.calibration = read_calibration::<R, N>(path)?;
            }
            let robot = nominal(robot, &a.model, Some(&a.baseline))?;
            let (Some(train), Some(holdout)) = (a.train.clone(), a.holdout.clone()) else {
                return Err("give --train and --holdout (data files to diagnose)".into());
            };
            let (train, holdout) = a.data_files(train, holdout)?;
            crate::diagnose::diagnose_cmd(&robot, train, holdout, a.json, a.report, options)
        }
        RobotCommand::Identify(a) => {
            let robot = nominal(robot, &a.model, None)?;
            let file = |path| crate::gap::DataFile {
                topic: a.topic.clone(),
                ..crate::gap::DataFile::csv(path)
            };
            crate::identify::identify_cmd(&robot, file(a.train), file(a.holdout), a.json)
        }
        RobotCommand::Excite(a) => {
            let robot = nominal(robot, &a.model, None)?;
            crate::excite::excite_cmd(&robot, info, &a)
        }
        RobotCommand::CheckData(a) => {
            let robot = nominal(robot, &a.model, None)?;
            crate::excite::check_data_cmd(&robot, info, &a)
        }
    }
}

/// `check` on one robot: `None` when there are no reference values.
fn check<R: Robot<N>, const N: usize>(
    robot: R,
    info: &RobotInfo,
    args: &CheckArgs,
) -> Result<Option<bool>, Box<dyn std::error::Error>> {
    let robot = nominal(robot, &args.model, None)?;
    let (file, text) = match &args.reference {
        Some(path) => (
            path.display().to_string(),
            std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?,
        ),
        None => match (&info.states, info.reference_values) {
            (Some((f, t)), true) => (f.clone(), t.clone()),
            _ => return Ok(None),
        },
    };
    let name = Path::new(&file)
        .file_name()
        .map(|f| f.to_string_lossy().to_string())
        .unwrap_or(file.clone());
    println!(
        "{} against {name} (worst relative error per field)",
        info.name
    );
    Ok(Some(crate::commands::check(
        &info.name, &robot, &file, &text,
    )?))
}

/// Runs a subcommand on the robot visited.
pub struct Run(pub RobotCommand);

impl RobotVisitor for Run {
    type Output = Res;
    fn visit<R: Robot<N> + Clone + Send + Sync + 'static, const N: usize>(
        self,
        robot: R,
        info: &RobotInfo,
    ) -> Res {
        run_on(robot, info, self.0)
    }
}

/// `check` on the robot visited if it has reference values: whether all
/// are within 1e-10, `None` when it has none.
pub struct CheckIfReference<'a>(pub &'a CheckArgs);

impl RobotVisitor for CheckIfReference<'_> {
    type Output = Result<Option<bool>, Box<dyn std::error::Error>>;
    fn visit<R: Robot<N> + Clone + Send + Sync + 'static, const N: usize>(
        self,
        robot: R,
        info: &RobotInfo,
    ) -> Self::Output {
        if !info.reference_values {
            return Ok(None);
        }
        check(robot, info, self.0)
    }
}
