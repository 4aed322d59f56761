//! `dynamics`: the command-line program.
//!
//! ```text
//! dynamics                      # diagnose a built-in case (arm3r with a withheld effect)
//! dynamics check                # every seed robot against the shipped Pinocchio values
//! dynamics synth --robot NAME --effect KIND --joint J --out FILE.csv
//! dynamics diagnose --robot NAME --train A.csv --holdout B.csv [--json OUT.json] [--report DIR]
//! dynamics diagnose --robot NAME --columns t=times,q=positions,tau=torques --train A.npz --holdout B.npz
//! dynamics identify --robot NAME --train A.csv --holdout B.csv [--json OUT.json]
//! dynamics list                 # the robots it knows
//! dynamics eval --robot NAME [--states FILE.json] [--out FILE.json] [--set NAME=VALUE]...
//! ```

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use dynamics_cli::commands::{eval, synth_cmd};
use dynamics_cli::diagnose::diagnose_cmd;
use dynamics_cli::gap::{parse_window, DataFile};
use dynamics_cli::identify::identify_cmd;
use dynamics_cli::Res;
use robots::each_robot;
use robots::registry::{AnyRobot, ROBOTS};

#[derive(Parser)]
#[command(
    name = "dynamics",
    version,
    about = "Equations of motion generated at compile time: evaluate, compare, simulate."
)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Subcommand)]
enum Command {
    /// Compare every seed robot with the Pinocchio reference values shipped with it.
    Check,
    /// List the robots.
    List,
    /// Run a scenario of the seeds by name, writing CSV and SVG plots.
    Scenario {
        /// Scenario name; omit to list them.
        name: Option<String>,
        /// Output folder (default `out/NAME`).
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Generate measured data (CSV) of a robot with a withheld effect under a tracking controller.
    Synth {
        /// Robot name (see `dynamics list`).
        #[arg(long)]
        robot: String,
        /// Effect kind (coulomb_friction, viscous_friction, stribeck_friction, armature, payload_mass,
        /// joint_elasticity, backlash, environment_resistance, encoder_offset, time_delay, none);
        /// omit to draw one at random.
        #[arg(long)]
        effect: Option<String>,
        /// Joint name; omit to draw one.
        #[arg(long)]
        joint: Option<String>,
        /// Main parameter in SI units (Fc, Fv, Fc, rotor inertia, kg, resonance Hz, half-width,
        /// mu, offset, delay s); omit to draw from the realistic range.
        #[arg(long)]
        magnitude: Option<f64>,
        /// Random seed.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Reference motion: sines, chirp or pick-place.
        #[arg(long, default_value = "sines")]
        excitation: String,
        /// Duration, s.
        #[arg(long, default_value_t = 8.0)]
        duration: f64,
        /// Position noise (rad or m).
        #[arg(long, default_value_t = 2e-5)]
        noise_q: f64,
        /// Velocity noise.
        #[arg(long, default_value_t = 2e-3)]
        noise_qd: f64,
        /// Effort noise as a fraction of each joint's peak effort.
        #[arg(long, default_value_t = 2e-3)]
        noise_tau: f64,
        /// Training CSV to write (the held-out set goes beside it as `<stem>-holdout.csv`).
        #[arg(long)]
        out: PathBuf,
        /// Where to write the truth (JSON); default: none written.
        #[arg(long)]
        truth: Option<PathBuf>,
        /// Sample rate, Hz.
        #[arg(long, default_value_t = 1000.0)]
        rate: f64,
        /// Clock jitter: each interval times a factor in 1 +- this (0.3: +-30 %).
        #[arg(long, default_value_t = 0.0)]
        jitter: f64,
        /// Fraction of rows whose values (whole row, positions or efforts) repeat the previous row's.
        #[arg(long, default_value_t = 0.0)]
        repeats: f64,
        /// Holes of 0.1 s (rows missing).
        #[arg(long, default_value_t = 0)]
        holes: usize,
        /// Glitches (1e300, a 50-sigma spike, a sign flipped).
        #[arg(long, default_value_t = 0)]
        glitches: usize,
        /// How late the position channel is against velocity and effort, s.
        #[arg(long, default_value_t = 0.0)]
        q_late: f64,
    },
    /// Diagnose the gap between a robot's model and measured data: where, which effect, how far it shrinks.
    /// Without files: a built-in case (arm3r with a withheld effect, generated in memory).
    Diagnose {
        /// Robot name.
        #[arg(long, default_value = "arm3r")]
        robot: String,
        /// Training data (CSV or CSV.gz; with --columns: a text matrix, a .npz or .npy, or a
        /// directory of one file per quantity).
        #[arg(long, requires = "holdout")]
        train: Option<PathBuf>,
        /// Held-out data (may be the training file with another window).
        #[arg(long, requires = "train")]
        holdout: Option<PathBuf>,
        /// Read recorded files in their own layout: where the time, positions, velocities
        /// (optional) and efforts are, in the robot's joint order, as
        /// `t=SRC,q=SRC[,qd=SRC],tau=SRC` with SRC = `[ENTRY][:COLUMNS][*SCALE]`: ENTRY a file of
        /// the directory or an array of the .npz, COLUMNS 1-based (`2-8`), SCALE a factor
        /// (`*1e-3` for milliseconds, `*-1` for the opposite sign).
        #[arg(long, value_name = "MAP", requires = "train")]
        columns: Option<String>,
        /// Use only this part of the training data: START:END, seconds from its first sample.
        #[arg(long, value_name = "START:END", requires = "train")]
        train_window: Option<String>,
        /// Use only this part of the held-out data: START:END, seconds from its first sample.
        #[arg(long, value_name = "START:END", requires = "train")]
        holdout_window: Option<String>,
        /// Write the JSON report here.
        #[arg(long)]
        json: Option<PathBuf>,
        /// Write a readable report here: report.md with SVG plots (residual per joint with the gap
        /// windows, measured vs nominal vs corrected, the ranking) and report.json.
        #[arg(long, value_name = "DIR")]
        report: Option<PathBuf>,
        /// Known effort noise, per-sample standard deviation (N m or N): one value, or one per
        /// joint separated by commas. Given, the noise floor comes from the stated noise
        /// (with --noise-q and --noise-qd, default 0) instead of noise levels estimated from the data.
        #[arg(long, value_delimiter = ',', value_name = "SIGMA[,..]")]
        noise_tau: Option<Vec<f64>>,
        /// Known position noise (rad or m), one value or one per joint; needs --noise-tau.
        #[arg(
            long,
            value_delimiter = ',',
            value_name = "SIGMA[,..]",
            requires = "noise_tau"
        )]
        noise_q: Option<Vec<f64>>,
        /// Known velocity noise (rad/s or m/s), one value or one per joint; needs --noise-tau.
        #[arg(
            long,
            value_delimiter = ',',
            value_name = "SIGMA[,..]",
            requires = "noise_tau"
        )]
        noise_qd: Option<Vec<f64>>,
    },
    /// Plain least-squares identification (the baseline): per-joint Coulomb, viscous, offset and
    /// rotor inertia plus every link's inertial parameters, fitted on training data, judged on
    /// held-out data.
    Identify {
        /// Robot name.
        #[arg(long)]
        robot: String,
        /// Training data (CSV or CSV.gz).
        #[arg(long)]
        train: PathBuf,
        /// Held-out data.
        #[arg(long)]
        holdout: PathBuf,
        /// Write the result as JSON here.
        #[arg(long)]
        json: Option<PathBuf>,
    },
    /// Evaluate tau, M, g, C, nle, ddq, the energies and the derivatives (dtau_dq, dtau_dv, ddq_dq, ddq_dv) at given states.
    Eval {
        /// Robot name (see `dynamics list`).
        #[arg(long)]
        robot: String,
        /// States file (JSON with `states: [{q, v, a}]`); default: the shipped reference states.
        #[arg(long)]
        states: Option<PathBuf>,
        /// Where to write the JSON; default: standard output.
        #[arg(long)]
        out: Option<PathBuf>,
        /// Set a run-time parameter, e.g. `--set m=3.5` (repeatable).
        #[arg(long = "set", value_name = "NAME=VALUE")]
        set: Vec<String>,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command.unwrap_or(Command::Diagnose {
        robot: "arm3r".into(),
        train: None,
        holdout: None,
        columns: None,
        train_window: None,
        holdout_window: None,
        json: None,
        report: None,
        noise_tau: None,
        noise_q: None,
        noise_qd: None,
    }) {
        Command::Check => check(),
        Command::List => {
            for (name, what) in ROBOTS {
                println!("{name:12} {what}");
            }
            Ok(())
        }
        Command::Scenario { name, out } => scenario(name, out),
        Command::Synth {
            robot,
            effect,
            joint,
            magnitude,
            seed,
            excitation,
            duration,
            noise_q,
            noise_qd,
            noise_tau,
            out,
            truth,
            rate,
            jitter,
            repeats,
            holes,
            glitches,
            q_late,
        } => AnyRobot::by_name(&robot).map_err(Into::into).and_then(|r| {
            let recording = dynamics_cli::gap::Recording {
                rate,
                damage: dynamics_sim2real::synth::Damage {
                    jitter,
                    repeats,
                    holes,
                    glitches,
                    q_late,
                    ..Default::default()
                },
            };
            each_robot!(&r, r => synth_cmd(
                r,
                &robots::builtin::motion(&robot),
                &robot,
                effect,
                joint,
                magnitude,
                seed,
                &excitation,
                duration,
                [noise_q, noise_qd, noise_tau],
                &out,
                truth,
                &recording,
            ))
        }),
        Command::Diagnose {
            robot,
            train,
            holdout,
            columns,
            train_window,
            holdout_window,
            json,
            report,
            noise_tau,
            noise_q,
            noise_qd,
        } => {
            let noise = noise_tau.map(|tau| dynamics_sim2real::diagnose::SensorNoise {
                q: noise_q.unwrap_or_else(|| vec![0.0]),
                qd: noise_qd.unwrap_or_else(|| vec![0.0]),
                tau,
            });
            match (train, holdout) {
                (Some(train), Some(holdout)) => {
                    data_files(train, holdout, columns, train_window, holdout_window).and_then(
                        |(train, holdout)| {
                            AnyRobot::by_name(&robot).map_err(Into::into).and_then(|r| {
                                each_robot!(&r, r => diagnose_cmd(r, train.clone(), holdout.clone(), json.clone(), report.clone(), noise.clone()))
                            })
                        },
                    )
                }
                _ => built_in_case(json, report, noise),
            }
        }
        Command::Identify {
            robot,
            train,
            holdout,
            json,
        } => AnyRobot::by_name(&robot)
            .map_err(Into::into)
            .and_then(|r| each_robot!(&r, r => identify_cmd(r, train, holdout, json))),
        Command::Eval {
            robot,
            states,
            out,
            set,
        } => AnyRobot::by_name(&robot).map_err(Into::into).and_then(|r| {
            let reference = r.reference();
            each_robot!(r, r => eval(&robot, r, Some(reference), states, out, &set))
        }),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

/// `dynamics check`: every model against the shipped Pinocchio values.
fn check() -> Res {
    println!("Our models against Pinocchio 4.1.0 (shipped reference states; worst relative error per field)");
    let mut failed = false;
    for name in [
        "arm3r",
        "rrp-rigid",
        "mar",
        "ur5",
        "panda",
        "arm3r-urdf",
        "rrp-urdf",
        "mar-urdf",
    ] {
        let robot = AnyRobot::by_name(name)?;
        let (file, text) = robot.reference();
        failed |= !each_robot!(&robot, r => dynamics_cli::commands::check(name, r, file, text))?;
    }
    if failed {
        Err("some values differ from Pinocchio by more than 1e-10".into())
    } else {
        println!("\nall within 1e-10");
        Ok(())
    }
}

/// `dynamics scenario [NAME]`: runs a seed scenario, or lists them.
fn scenario(name: Option<String>, out: Option<PathBuf>) -> Res {
    let Some(name) = name else {
        for (n, what) in robots::scenarios::SCENARIOS {
            println!("{n:14} {what}");
        }
        return Ok(());
    };
    let dir = out.unwrap_or_else(|| PathBuf::from("out").join(&name));
    let lines = robots::scenarios::run(&name, &dir)?;
    println!("{name}: outputs in {}", dir.display());
    for l in lines {
        println!("  {l}");
    }
    Ok(())
}

/// The training and held-out files as `diagnose --columns/--train-window/--holdout-window` say.
fn data_files(
    train: PathBuf,
    holdout: PathBuf,
    columns: Option<String>,
    train_window: Option<String>,
    holdout_window: Option<String>,
) -> Result<(DataFile, DataFile), Box<dyn std::error::Error>> {
    let columns = columns
        .map(|c| c.parse::<dynamics_sim2real::data::import::ColumnMap>())
        .transpose()?;
    let window = |w: Option<String>| w.as_deref().map(parse_window).transpose();
    Ok((
        DataFile {
            path: train,
            columns: columns.clone(),
            window: window(train_window)?,
        },
        DataFile {
            path: holdout,
            columns,
            window: window(holdout_window)?,
        },
    ))
}

/// `dynamics` without a subcommand: the built-in case, Coulomb friction
/// withheld at arm3r's j2, generated in memory and diagnosed; the truth is
/// printed after the verdict.
fn built_in_case(
    json: Option<PathBuf>,
    report: Option<PathBuf>,
    noise: Option<dynamics_sim2real::diagnose::SensorNoise>,
) -> Res {
    let dir = std::env::temp_dir().join(format!("dynamics-demo-{}", std::process::id()));
    std::fs::create_dir_all(&dir)?;
    let req = dynamics_cli::gap::SynthRequest {
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
    let data = robots::builtin::synth(&req)?;
    let (a, b) = (dir.join("train.csv"), dir.join("holdout.csv"));
    std::fs::write(&a, &data.train)?;
    std::fs::write(&b, &data.holdout)?;
    let (a, b) = (DataFile::csv(a), DataFile::csv(b));
    diagnose_cmd(&robots::Arm3r::default(), a, b, json, report, noise)?;
    println!(
        "truth of the built-in case (read after the verdict): {} at {}",
        data.truth.kind,
        data.truth.joint.unwrap_or_default()
    );
    let _ = std::fs::remove_dir_all(dir);
    Ok(())
}
