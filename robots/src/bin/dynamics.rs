//! `dynamics`: the command-line program.
//!
//! ```text
//! dynamics                      # check: every seed robot against the shipped Pinocchio values
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
    /// Compare every seed robot with the Pinocchio reference values shipped with it (the default).
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
    let result = match cli.command.unwrap_or(Command::Check) {
        Command::Check => check(),
        Command::List => {
            for (name, what) in ROBOTS {
                println!("{name:12} {what}");
            }
            Ok(())
        }
        Command::Scenario { name, out } => scenario(name, out),
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
