//! The whole program: [`run`] over one robot (what a scaffolded crate's
//! `main` calls), [`run_set`] over a set of robots chosen by name (the
//! built-in `dynamics` is that over the robots of the crate `robots`).
//! Subcommands and flags are the same in both (`args.rs`); `dispatch.rs`
//! runs one on one robot.

pub mod args;
mod dispatch;

use std::process::ExitCode;

use clap::{ArgMatches, CommandFactory, FromArgMatches};
use dynamics_runtime::Robot;

pub use crate::info::RobotInfo;
use crate::Res;
use args::{DiagnoseArgs, RobotCommand, SetCli, SetCommand, SingleCli};

/// Something to do with one robot of a set, whatever its type.
pub trait RobotVisitor {
    /// What it returns.
    type Output;
    /// Does it with `robot`.
    fn visit<R: Robot<N> + Clone + Send + Sync + 'static, const N: usize>(
        self,
        robot: R,
        info: &RobotInfo,
    ) -> Self::Output;
}

/// A set of robots known by name: what [`run_set`] needs.
pub trait RobotSet {
    /// Names and a line of description each, in listing order.
    fn robots(&self) -> Vec<(String, String)>;
    /// Calls `visitor` with the robot called `name`; `None` when there is none.
    fn visit<V: RobotVisitor>(&self, name: &str, visitor: V) -> Option<V::Output>;
    /// The robot `diagnose` takes without `--robot`.
    fn default_robot(&self) -> Option<String> {
        None
    }
    /// Subcommands of this set's own (e.g. the scenarios of the source works).
    fn commands(&self) -> Vec<clap::Command> {
        Vec::new()
    }
    /// Runs one of [`RobotSet::commands`].
    fn run_command(&self, name: &str, _matches: &ArgMatches) -> Res {
        Err(format!("no subcommand `{name}`").into())
    }
    /// What `diagnose` does without data files, and the program without a
    /// subcommand (`args` of the latter: all defaults).
    fn demo(&self, _args: &DiagnoseArgs) -> Res {
        Err("give --train and --holdout (data files to diagnose)".into())
    }
}

/// The program's name for `--help`, alive as long as the process (one small
/// allocation per run; clap wants a static string).
fn leak(name: &str) -> &'static str {
    Box::leak(name.to_string().into_boxed_str())
}

fn finish(result: Res) -> ExitCode {
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

/// The whole program over `robot`, with the command line of this process.
/// The one call a user's own crate needs:
///
/// ```no_run
/// dynamics_macros::robot! {
///     pub robot Pendulum; gravity = [0.0, -9.81, 0.0];
///     link base; link rod { mass = 1.0; com = [1.0, 0.0, 0.0]; }
///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
/// }
/// fn main() -> std::process::ExitCode {
///     dynamics_cli::run(Pendulum::default())
/// }
/// ```
pub fn run<R: Robot<N> + Clone + Send + Sync + 'static, const N: usize>(robot: R) -> ExitCode {
    run_with(robot, RobotInfo::default())
}

/// [`run`] with what the program should know about the robot besides its
/// model (reference states, its motion for `synth` and `simulate`).
pub fn run_with<R: Robot<N> + Clone + Send + Sync + 'static, const N: usize>(
    robot: R,
    mut info: RobotInfo,
) -> ExitCode {
    if info.name.is_empty() {
        info.name = R::NAME.to_string();
    }
    let cli = SingleCli::command().name(leak(&info.name));
    let matches = cli.get_matches();
    let result = SingleCli::from_arg_matches(&matches)
        .map_err(|e| e.to_string().into())
        .and_then(|cli| match cli.command {
            Some(command) => dispatch::run_on(robot, &info, command),
            None => {
                let _ = SingleCli::command().name(leak(&info.name)).print_help();
                Ok(())
            }
        });
    finish(result)
}

/// The whole program over a set of robots, chosen with `--robot NAME`,
/// with the command line of this process.
pub fn run_set<S: RobotSet>(name: &str, set: &S) -> ExitCode {
    finish(run_set_on(name, set, std::env::args_os().collect()))
}

fn run_set_on<S: RobotSet>(name: &str, set: &S, argv: Vec<std::ffi::OsString>) -> Res {
    let known = set
        .robots()
        .iter()
        .map(|r| r.0.clone())
        .collect::<Vec<_>>()
        .join(", ");
    let mut cli = SetCli::command().name(leak(name));
    for sub in [
        "check",
        "eval",
        "simulate",
        "synth",
        "diagnose",
        "identify",
        "excite",
        "check-data",
    ] {
        let help = if sub == "check" {
            "Robot name (see `list`); default: every robot with reference values".to_string()
        } else {
            format!("Robot name (see `list`; known: {known})")
        };
        cli = cli.mut_subcommand(sub, |c| {
            c.arg(
                clap::Arg::new("robot")
                    .long("robot")
                    .value_name("NAME")
                    .help(help),
            )
        });
    }
    for extra in set.commands() {
        cli = cli.subcommand(extra);
    }
    let matches = cli.try_get_matches_from(argv).unwrap_or_else(|e| e.exit());
    if let Some((sub, m)) = matches.subcommand() {
        if set.commands().iter().any(|c| c.get_name() == sub) {
            return set.run_command(sub, m);
        }
    }
    let robot_name = matches
        .subcommand()
        .and_then(|(_, m)| m.try_get_one::<String>("robot").ok().flatten().cloned());
    let parsed = SetCli::from_arg_matches(&matches).map_err(|e| e.to_string())?;
    let command = match parsed.command {
        None => return set.demo(&DiagnoseArgs::default()),
        Some(SetCommand::List) => {
            for (n, what) in set.robots() {
                println!("{n:14} {what}");
            }
            return Ok(());
        }
        Some(SetCommand::New(args)) => return crate::scaffold::new(&args),
        Some(SetCommand::Robot(c)) => c,
    };
    let unknown = |n: &str| format!("unknown robot `{n}`; known robots: {known}");
    match (&command, robot_name) {
        (RobotCommand::Check(args), None) if args.reference.is_some() => {
            Err(format!("check --reference needs --robot NAME (known robots: {known})").into())
        }
        (RobotCommand::Check(args), None) => {
            let mut failed = false;
            let mut compared = 0;
            for (n, _) in set.robots() {
                let ok = set
                    .visit(&n, dispatch::CheckIfReference(args))
                    .ok_or_else(|| unknown(&n))??;
                if let Some(ok) = ok {
                    failed |= !ok;
                    compared += 1;
                }
            }
            if failed {
                Err("some values differ from the reference by more than 1e-10".into())
            } else {
                println!("\nall {compared} within 1e-10");
                Ok(())
            }
        }
        (RobotCommand::Diagnose(args), _) if args.train.is_none() => set.demo(args),
        (_, robot) => {
            let robot = robot
                .or_else(|| {
                    matches!(command, RobotCommand::Diagnose(_))
                        .then(|| set.default_robot())
                        .flatten()
                })
                .ok_or_else(|| {
                    format!(
                        "`{}` needs --robot NAME (known robots: {known})",
                        command.name()
                    )
                })?;
            set.visit(&robot, dispatch::Run(command))
                .ok_or_else(|| unknown(&robot))?
        }
    }
}
