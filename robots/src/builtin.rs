//! The generic sim-to-real commands of `dynamics_cli::gap` over the
//! built-in robots by name, with each robot's home pose and amplitudes.

use std::path::Path;

use dynamics_cli::gap::{self, GapError, Motion, SynthOutput, SynthRequest};
use dynamics_sim2real::diagnose::traces::Traces;
use dynamics_sim2real::diagnose::{Options, Report};

use crate::registry::{AnyRobot, RegistryError, ROBOTS};

/// Home pose and reference amplitude of a built-in robot's motion (inside
/// the joint limits of the URDF arms); others move by 0.4 about zero.
///
/// ```
/// assert_eq!(robots::builtin::motion("ur5").home.len(), 6);
/// assert!(robots::builtin::motion("r2d2").home.is_empty());
/// ```
pub fn motion(name: &str) -> Motion {
    let (home, amplitude) = match name {
        "arm3r" | "arm3r-urdf" => (vec![0.0, 0.4, -0.4], vec![0.6, 0.6, 0.6]),
        "rrp" | "rrp-rigid" | "rrp-urdf" => (vec![0.0, 0.3, 0.05], vec![0.5, 0.5, 0.04]),
        "mar" | "mar-drives" | "mar-urdf" => (vec![0.0, 0.3, 0.05], vec![0.4, 0.5, 0.04]),
        "ur5" => (vec![0.0, -1.2, 1.2, -1.5, -1.5, 0.0], vec![0.4; 6]),
        "panda" | "panda-damped" => (vec![0.0, -0.4, 0.0, -2.0, 0.0, 1.7, 0.8], vec![0.35; 7]),
        _ => (Vec::new(), Vec::new()),
    };
    Motion { home, amplitude }
}

fn robot(name: &str) -> Result<AnyRobot, GapError> {
    AnyRobot::by_name(name).map_err(|e| match e {
        RegistryError::UnknownRobot(name) => GapError::UnknownRobot {
            name,
            known: ROBOTS.iter().map(|r| r.0).collect::<Vec<_>>().join(", "),
        },
        other => GapError::Request(other.to_string()),
    })
}

/// [`gap::synth`] for the built-in robot `req.robot`.
///
/// ```
/// use dynamics_sim2real::effects::EffectKind;
/// use dynamics_cli::gap::SynthRequest;
/// let out = robots::builtin::synth(&SynthRequest {
///     robot: "arm3r".into(), kind: Some(EffectKind::ViscousFriction), joint: Some("j2".into()),
///     magnitude: Some(0.5), seed: 3, excitation: "sines".parse().unwrap(), duration: 0.5,
///     noise: Default::default(),
/// }).unwrap();
/// assert!(out.train.starts_with("t,q_j1,q_j2,q_j3,qd_j1"));
/// assert_eq!(out.truth.kind, "viscous_friction");
/// ```
pub fn synth(req: &SynthRequest) -> Result<SynthOutput, GapError> {
    let motion = motion(&req.robot);
    crate::each_robot!(&robot(&req.robot)?, r => gap::synth(r, &motion, req))
}

/// [`gap::synth_recorded`] for the built-in robot `req.robot`.
pub fn synth_recorded(req: &SynthRequest, rec: &gap::Recording) -> Result<SynthOutput, GapError> {
    let motion = motion(&req.robot);
    crate::each_robot!(&robot(&req.robot)?, r => gap::synth_recorded(r, &motion, req, rec))
}

/// [`gap::diagnose_files`] for the built-in robot `name`.
pub fn diagnose_files(
    name: &str,
    train: &Path,
    holdout: &Path,
    options: &Options,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<(Report, Vec<String>), GapError> {
    crate::each_robot!(&robot(name)?, r => gap::diagnose_files(r, train, holdout, options, progress))
}

/// [`gap::traces_files`] for the built-in robot `name`.
pub fn traces_files(
    name: &str,
    train: &Path,
    holdout: &Path,
    report: &Report,
    options: &Options,
) -> Result<Traces, GapError> {
    crate::each_robot!(&robot(name)?, r => gap::traces_files(r, train, holdout, report, options))
}

/// The built-in robots as a [`dynamics_cli::RobotSet`]: what the
/// `dynamics` program runs on (`dynamics_cli::run_set(&Builtin)`), with the
/// scenarios of the source works as an extra subcommand and the built-in diagnosis case
/// as what it does without one.
#[derive(Debug, Clone, Copy, Default)]
pub struct Builtin;

/// The robots whose shipped reference values are of that very model.
const REFERENCE_VALUES: &[&str] = &[
    "arm3r",
    "rrp-rigid",
    "mar",
    "ur5",
    "panda",
    "arm3r-urdf",
    "rrp-urdf",
    "mar-urdf",
];

impl dynamics_cli::RobotSet for Builtin {
    fn robots(&self) -> Vec<(String, String)> {
        ROBOTS
            .iter()
            .map(|(n, d)| (n.to_string(), d.to_string()))
            .collect()
    }

    fn visit<V: dynamics_cli::RobotVisitor>(&self, name: &str, visitor: V) -> Option<V::Output> {
        let robot = AnyRobot::by_name(name).ok()?;
        let (file, text) = robot.reference();
        let info = dynamics_cli::RobotInfo {
            name: name.to_string(),
            states: Some((file.to_string(), text.to_string())),
            reference_values: REFERENCE_VALUES.contains(&name),
            motion: motion(name),
            limits: robot.limits(),
        };
        Some(crate::each_robot!(robot, r => visitor.visit(r, &info)))
    }

    fn default_robot(&self) -> Option<String> {
        Some("arm3r".into())
    }

    fn commands(&self) -> Vec<clap::Command> {
        vec![clap::Command::new("scenario")
            .about("Run a scenario of the source works by name, writing CSV and SVG plots")
            .arg(clap::Arg::new("name").help("Scenario name; omit to list them"))
            .arg(
                clap::Arg::new("out")
                    .long("out")
                    .value_parser(clap::value_parser!(std::path::PathBuf))
                    .help("Output folder (default `out/NAME`)"),
            )]
    }

    fn run_command(&self, name: &str, m: &clap::ArgMatches) -> dynamics_cli::Res {
        if name != "scenario" {
            return Err(format!("no subcommand `{name}`").into());
        }
        let Some(scenario) = m.get_one::<String>("name") else {
            for (n, what) in crate::scenarios::SCENARIOS {
                println!("{n:14} {what}");
            }
            return Ok(());
        };
        let dir = m
            .get_one::<std::path::PathBuf>("out")
            .cloned()
            .unwrap_or_else(|| std::path::PathBuf::from("out").join(scenario));
        let lines = crate::scenarios::run(scenario, &dir)?;
        println!("{scenario}: outputs in {}", dir.display());
        for l in lines {
            println!("  {l}");
        }
        Ok(())
    }

    /// The built-in case: Coulomb friction withheld at arm3r's j2,
    /// generated in memory and diagnosed; the truth is printed after the
    /// verdict.
    fn demo(&self, args: &dynamics_cli::program::args::DiagnoseArgs) -> dynamics_cli::Res {
        let dir = std::env::temp_dir().join(format!("dynamics-demo-{}", std::process::id()));
        std::fs::create_dir_all(&dir)?;
        let req = SynthRequest {
            robot: "arm3r".into(),
            kind: Some("coulomb_friction".parse()?),
            joint: Some("j2".into()),
            magnitude: Some(0.3),
            seed: 7,
            excitation: "sines".parse()?,
            duration: 8.0,
            noise: Default::default(),
        };
        eprintln!("built-in case: arm3r following sines, 8 s at 1 kHz, with a withheld effect (not told to the diagnoser)");
        let data = synth(&req)?;
        let (a, b) = (dir.join("train.csv"), dir.join("holdout.csv"));
        std::fs::write(&a, &data.train)?;
        std::fs::write(&b, &data.holdout)?;
        let robot = dynamics_sim2real::effects::Calibrated::new(crate::Arm3r::default(), vec![])?;
        let result = dynamics_cli::diagnose::diagnose_cmd(
            &robot,
            dynamics_cli::gap::DataFile::csv(a),
            dynamics_cli::gap::DataFile::csv(b),
            args.json.clone(),
            args.report.clone(),
            args.options(),
        );
        let _ = std::fs::remove_dir_all(&dir);
        result?;
        println!(
            "truth of the built-in case (read after the verdict): {} at {}",
            data.truth.kind,
            data.truth.joint.unwrap_or_default()
        );
        Ok(())
    }
}
