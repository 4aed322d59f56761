//! `dynamics`: the command-line program.
//!
//! ```text
//! dynamics                      # diagnose a built-in case (arm3r with a withheld effect)
//! dynamics check                # every seed robot against the shipped Pinocchio values
//! dynamics synth --robot NAME --effect KIND --joint J --out FILE.csv
//! dynamics diagnose --robot NAME --train A.csv --holdout B.csv [--json OUT.json] [--report DIR]
//! dynamics list                 # the robots it knows
//! dynamics eval --robot NAME [--states FILE.json] [--out FILE.json] [--set NAME=VALUE]...
//! ```

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use robots::compare::compare;
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
    },
    /// Diagnose the gap between a robot's model and measured data: where, which effect, how far it shrinks.
    /// Without files: a built-in case (arm3r with a withheld effect, generated in memory).
    Diagnose {
        /// Robot name.
        #[arg(long, default_value = "arm3r")]
        robot: String,
        /// Training data (CSV or CSV.gz).
        #[arg(long, requires = "holdout")]
        train: Option<PathBuf>,
        /// Held-out data.
        #[arg(long, requires = "train")]
        holdout: Option<PathBuf>,
        /// Write the JSON report here.
        #[arg(long)]
        json: Option<PathBuf>,
        /// Write a readable report here: report.md with SVG plots (residual per joint with the gap
        /// windows, measured vs nominal vs corrected, the ranking) and report.json.
        #[arg(long, value_name = "DIR")]
        report: Option<PathBuf>,
    },
    /// Evaluate tau, M, g, C, nle, ddq and the energies at given states.
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
        json: None,
        report: None,
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
        } => synth_cmd(
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
        ),
        Command::Diagnose {
            robot,
            train,
            holdout,
            json,
            report,
        } => diagnose_cmd(&robot, train, holdout, json, report),
        Command::Eval {
            robot,
            states,
            out,
            set,
        } => eval(&robot, states, out, &set),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

type Res = Result<(), Box<dyn std::error::Error>>;

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
        let ours = robot.evaluate_json(text, file)?;
        let doc: serde_json::Value = serde_json::from_str(text)?;
        let cmp = compare(&ours, &doc);
        let worst = cmp.worst();
        let status = if worst <= 1e-10 { "ok" } else { "FAIL" };
        failed |= worst > 1e-10;
        println!("\n{name} ({} states): {status}", ours.len());
        for (field, err) in &cmp.fields {
            println!("  {field:18} {err:9.2e}");
        }
    }
    if failed {
        Err("some values differ from Pinocchio by more than 1e-10".into())
    } else {
        println!("\nall within 1e-10");
        Ok(())
    }
}

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

fn eval(name: &str, states: Option<PathBuf>, out: Option<PathBuf>, set: &[String]) -> Res {
    let mut robot = AnyRobot::by_name(name)?;
    for s in set {
        let (k, v) = s
            .split_once('=')
            .ok_or_else(|| format!("--set `{s}`: expected NAME=VALUE"))?;
        let v: f64 = v
            .trim()
            .parse()
            .map_err(|_| format!("--set `{s}`: `{v}` is not a number"))?;
        if !v.is_finite() {
            return Err(format!("--set `{s}`: the value must be finite").into());
        }
        robot.set_param(k.trim(), v)?;
    }
    let (file, text) = match &states {
        Some(path) => {
            let text =
                std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
            (path.display().to_string(), text)
        }
        None => {
            let (f, t) = robot.reference();
            (f.to_string(), t.to_string())
        }
    };
    let evaluated = robot.evaluate_json(&text, &file)?;
    let doc = serde_json::json!({
        "robot": name,
        "joint_names": robot.joint_names(),
        "states": evaluated,
    });
    let json = serde_json::to_string_pretty(&doc)?;
    match out {
        Some(path) => {
            std::fs::write(&path, json + "\n").map_err(|e| format!("{}: {e}", path.display()))?
        }
        None => println!("{json}"),
    }
    Ok(())
}

#[allow(clippy::too_many_arguments)]
fn synth_cmd(
    robot: &str,
    effect: Option<String>,
    joint: Option<String>,
    magnitude: Option<f64>,
    seed: u64,
    excitation: &str,
    duration: f64,
    noise: [f64; 3],
    out: &std::path::Path,
    truth: Option<PathBuf>,
) -> Res {
    use dynamics_runtime::synth::Noise;
    let kind = effect.map(|e| e.parse()).transpose()?;
    let req = robots::gap::SynthRequest {
        robot: robot.into(),
        kind,
        joint,
        magnitude,
        seed,
        excitation: excitation.parse()?,
        duration,
        noise: Noise {
            q: noise[0],
            qd: noise[1],
            tau_relative: noise[2],
        },
    };
    let data = robots::gap::synth(&req)?;
    let stem = out.file_stem().and_then(|s| s.to_str()).unwrap_or("data");
    let hold = out.with_file_name(format!("{stem}-holdout.csv"));
    std::fs::write(out, &data.train).map_err(|e| format!("{}: {e}", out.display()))?;
    std::fs::write(&hold, &data.holdout).map_err(|e| format!("{}: {e}", hold.display()))?;
    eprintln!("wrote {} and {}", out.display(), hold.display());
    if let Some(t) = truth {
        std::fs::write(&t, serde_json::to_string_pretty(&data.truth)?)
            .map_err(|e| format!("{}: {e}", t.display()))?;
        eprintln!("wrote the truth to {}", t.display());
    }
    Ok(())
}

fn diagnose_cmd(
    robot: &str,
    train: Option<PathBuf>,
    holdout: Option<PathBuf>,
    json: Option<PathBuf>,
    report_dir: Option<PathBuf>,
) -> Res {
    use dynamics_runtime::diagnose::Options;
    use indicatif::{ProgressBar, ProgressStyle};
    let (train, holdout, tmp) = match (train, holdout) {
        (Some(a), Some(b)) => (a, b, None),
        _ => {
            // The built-in case: Coulomb friction withheld at arm3r's j2.
            let dir = std::env::temp_dir().join(format!("dynamics-demo-{}", std::process::id()));
            std::fs::create_dir_all(&dir)?;
            let req = robots::gap::SynthRequest {
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
            let data = robots::gap::synth(&req)?;
            let (a, b) = (dir.join("train.csv"), dir.join("holdout.csv"));
            std::fs::write(&a, &data.train)?;
            std::fs::write(&b, &data.holdout)?;
            (a, b, Some((dir, data.truth)))
        }
    };
    let robot = if tmp.is_some() { "arm3r" } else { robot };
    let bar = ProgressBar::new(0);
    bar.set_style(
        ProgressStyle::with_template("fitting candidates {bar:30} {pos}/{len}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let progress = |done: usize, total: usize| {
        bar.set_length(total as u64);
        bar.set_position(done as u64);
    };
    let options = Options::default();
    let (report, warnings) =
        robots::gap::diagnose_files(robot, &train, &holdout, &options, &progress)?;
    bar.finish_and_clear();
    for w in warnings {
        eprintln!("warning: {w}");
    }
    println!("where (training data, nominal model):");
    for j in &report.where_.joints {
        println!(
            "  {:8} torque residual {:.4} = {:.1} x noise; 0.1 s prediction error {:.2e} = {:.1} x an exact model's",
            j.joint, j.torque_rms, j.torque_ratio, j.prediction_rms, j.prediction_ratio
        );
        for w in j.windows.iter().take(2) {
            println!(
                "           {:.2}-{:.2} s {} ({:.1} x noise)",
                w.start, w.end, w.phase, w.ratio
            );
        }
    }
    println!("which (best first):");
    for r in report.which.ranked.iter().take(5) {
        let place = r.joint.clone().or(r.point.clone()).unwrap_or_default();
        let params: Vec<String> = r
            .parameters
            .iter()
            .map(|p| format!("{} = {:.4e} +- {:.1e}", p.name, p.value, p.std))
            .collect();
        println!(
            "  {:24} {:8} dAICc {:9.1}  explains {:5.1} % (held-out {:5.1} %)  {}",
            r.kind,
            place,
            r.delta_aicc,
            100.0 * r.share,
            100.0 * r.holdout_share,
            params.join(", ")
        );
    }
    let v = &report.which.verdict;
    println!(
        "verdict: {} {} ({})",
        v.kind,
        v.joint.clone().or(v.point.clone()).unwrap_or_default(),
        v.status
    );
    if let (Some(r), Some(m)) = (&v.rival, &v.separating_motion) {
        println!(
            "  rival: {} {}; to separate them: {m}",
            r.kind,
            r.joint.clone().or(r.point.clone()).unwrap_or_default()
        );
    }
    println!(
        "shrink on held-out data: torque gap -{:.1} %, short-horizon simulation error -{:.1} %",
        100.0 * report.shrink.torque_fraction,
        100.0 * report.shrink.simulation_fraction
    );
    if let Some(path) = json {
        std::fs::write(&path, serde_json::to_string_pretty(&report)?)
            .map_err(|e| format!("{}: {e}", path.display()))?;
        eprintln!("wrote {}", path.display());
    }
    if let Some(dir) = report_dir {
        let traces = robots::gap::traces_files(robot, &train, &holdout, &report)?;
        robots::report::write(&dir, &report, &traces, &options)?;
        eprintln!("wrote the report to {}", dir.join("report.md").display());
    }
    if let Some((dir, truth)) = tmp {
        println!(
            "truth of the built-in case (read after the verdict): {} at {}",
            truth.kind,
            truth.joint.unwrap_or_default()
        );
        let _ = std::fs::remove_dir_all(dir);
    }
    Ok(())
}
