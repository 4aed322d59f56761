//! The small subcommands: `check`, `scenario`, `eval`, `synth`.

use std::path::PathBuf;

use robots::compare::compare;
use robots::registry::AnyRobot;

use crate::Res;

/// `dynamics check`: every model against the shipped Pinocchio values.
pub fn check() -> Res {
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

/// `dynamics scenario [NAME]`: runs a seed scenario, or lists them.
pub fn scenario(name: Option<String>, out: Option<PathBuf>) -> Res {
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

/// `dynamics eval`: tau, M, g, C, nle, ddq, energies and derivatives at given states.
pub fn eval(name: &str, states: Option<PathBuf>, out: Option<PathBuf>, set: &[String]) -> Res {
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

/// `dynamics synth`: training and held-out CSVs of a robot with a withheld effect.
#[allow(clippy::too_many_arguments)]
pub fn synth_cmd(
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
    use dynamics_sim2real::synth::Noise;
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
