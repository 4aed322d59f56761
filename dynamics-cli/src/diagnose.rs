//! `dynamics diagnose`: the gap diagnosis on two data files, printed as
//! where / which / shrink, with the JSON and the readable report on request.

use std::path::PathBuf;

use dynamics_runtime::Robot;

use crate::gap::DataFile;
use crate::Res;

/// Runs the diagnosis of `robot` on two data files and prints it.
pub fn diagnose_cmd<R: Robot<N> + Clone + Sync, const N: usize>(
    robot: &R,
    train: DataFile,
    holdout: DataFile,
    json: Option<PathBuf>,
    report_dir: Option<PathBuf>,
    noise: Option<dynamics_sim2real::diagnose::SensorNoise>,
) -> Res {
    use dynamics_sim2real::diagnose::Options;
    use indicatif::{ProgressBar, ProgressStyle};
    let bar = ProgressBar::new(0);
    bar.set_style(
        ProgressStyle::with_template("fitting candidates {bar:30} {pos}/{len}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let progress = |done: usize, total: usize| {
        bar.set_length(total as u64);
        bar.set_position(done as u64);
    };
    let options = Options {
        noise,
        ..Options::default()
    };
    let (report, warnings) =
        crate::gap::diagnose_data(robot, &train, &holdout, &options, &progress)?;
    bar.finish_and_clear();
    for w in warnings {
        eprintln!("warning: {w}");
    }
    println!("where (training data, nominal model):");
    for j in &report.where_.joints {
        let prediction = match (j.prediction_rms, j.prediction_ratio) {
            (Some(e), Some(r)) => format!("{e:.2e} = {r:.1} x an exact model's"),
            _ => "not made (warnings)".into(),
        };
        println!(
            "  {:8} torque residual {:.4} = {:.1} x noise; 0.1 s prediction error {prediction}",
            j.joint, j.torque_rms, j.torque_ratio
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
    if let Some(c) = &v.channel {
        println!("  late channel: {c}");
    }
    if let (Some(r), Some(m)) = (&v.rival, &v.separating_motion) {
        println!(
            "  rival: {} {}; to separate them: {m}",
            r.kind,
            r.joint.clone().or(r.point.clone()).unwrap_or_default()
        );
    }
    for e in &report.which.effects {
        // An effect that starts and stops: where in time.
        if let Some(w) = &e.window {
            println!(
                "  {} {} is on from {:.3} s to {:.3} s",
                e.kind,
                e.joint.clone().or(e.point.clone()).unwrap_or_default(),
                w.start,
                w.end
            );
        }
    }
    let friction: Vec<_> = report
        .which
        .friction
        .iter()
        .filter(|f| f.corrected || f.coulomb > 0.0 || f.viscous > 0.0)
        .collect();
    if !friction.is_empty() {
        println!("friction in the calibrated model (nominal -> with the explanation):");
        for f in friction {
            let breakaway = if f.breakaway > f.coulomb + 5e-5 {
                format!(" (breaking away at {:.4})", f.breakaway)
            } else {
                String::new()
            };
            println!(
                "  {:<8} Coulomb {:.4} -> {:.4}{breakaway}, viscous {:.4} -> {:.4}{}",
                f.joint,
                f.coulomb_nominal,
                f.coulomb,
                f.viscous_nominal,
                f.viscous,
                if f.corrected { "" } else { " (nominal kept)" }
            );
        }
    }
    let simulation = match report.shrink.simulation_fraction {
        Some(x) => format!("-{:.1} %", 100.0 * x),
        None => "not measured (warnings)".into(),
    };
    println!(
        "shrink on held-out data: torque gap -{:.1} %, short-horizon simulation error {simulation}",
        100.0 * report.shrink.torque_fraction,
    );
    if let Some(path) = json {
        std::fs::write(&path, serde_json::to_string_pretty(&report)?)
            .map_err(|e| format!("{}: {e}", path.display()))?;
        eprintln!("wrote {}", path.display());
    }
    if let Some(dir) = report_dir {
        let traces = crate::gap::traces_data(robot, &train, &holdout, &report, &options)?;
        crate::report::write(&dir, &report, &traces, &options)?;
        eprintln!("wrote the report to {}", dir.join("report.md").display());
    }
    Ok(())
}
