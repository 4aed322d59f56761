//! `dynamics diagnose`: the gap diagnosis on two data files, printed as
//! where / which / shrink, with the JSON and the readable report on request.

use std::path::PathBuf;

use dynamics_runtime::Robot;

use crate::gap::DataFile;
use crate::Res;

/// Runs the diagnosis of `robot` on two data files and prints it.
pub fn diagnose_cmd<R: Robot<N> + Clone + Send + Sync + 'static, const N: usize>(
    robot: &dynamics_sim2real::effects::Calibrated<R, N>,
    train: DataFile,
    holdout: DataFile,
    json: Option<PathBuf>,
    report_dir: Option<PathBuf>,
    options: dynamics_sim2real::diagnose::Options,
) -> Res {
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
    let (report, warnings, about) =
        crate::gap::diagnose_calibrated(robot, &train, &holdout, &options, &progress)?;
    bar.finish_and_clear();
    for line in &about {
        println!("{line}");
    }
    for w in warnings {
        eprintln!("warning: {w}");
    }
    for line in explanation_lines(&report) {
        println!("{line}");
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
    for e in &report.which.suggested {
        let place = e.joint.clone().or(e.point.clone()).unwrap_or_default();
        println!(
            "  suggested, not confirmed: {} {}: {}",
            e.kind,
            crate::report::explanation::late_place(place, e.channel).trim_start(),
            e.reason
        );
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
    println!("the best single effects (supporting detail; best first):");
    for r in report.which.ranked.iter().take(5) {
        let place = r.joint.clone().or(r.point.clone()).unwrap_or_default();
        let params: Vec<String> = r
            .parameters
            .iter()
            .map(|p| match &p.note {
                Some(note) => format!("{}: {note}", p.name),
                None => format!("{} = {:.4e} +- {:.1e}", p.name, p.value, p.std),
            })
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
    let verdict_place = v.joint.clone().or(v.point.clone());
    let in_explanation = report.which.effects.iter().any(|e| {
        Some(e.kind) == v.effect() && e.joint.clone().or(e.point.clone()) == verdict_place
    });
    if v.names_effect() && !report.which.effects.is_empty() && !in_explanation {
        println!(
            "  (the best single effect; the explanation below does without it: its effects \
             account for its part together)"
        );
    }
    if let Some(r) = &v.rival {
        let at = r.joint.clone().or(r.point.clone()).unwrap_or_default();
        if let Some(why) = &v.inseparable {
            println!("  rival: {} {at}; {why}", r.kind);
        } else if let Some(m) = &v.separating_motion {
            println!("  rival: {} {at}; to separate them: {m}", r.kind);
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
        let traces = crate::gap::traces_calibrated(robot, &train, &holdout, &report, &options)?;
        crate::report::write_described(&dir, &report, &traces, &options, &about)?;
        eprintln!("wrote the report to {}", dir.join("report.md").display());
    }
    Ok(())
}

/// The compound explanation as command-line lines: each effect in the
/// order of its gains with its place, share of the training gap, held-out
/// contribution, the held-out gap above noise left once it is added, and
/// its parameters (or its words, when it has some); then the plain figure.
/// One line saying so when the explanation is empty.
///
/// ```
/// use dynamics_cli::diagnose::explanation_lines;
/// use dynamics_sim2real::diagnose::{diagnose, Options};
/// use dynamics_sim2real::effects::Effect;
/// use dynamics_sim2real::synth::{synthesize, SynthOptions};
/// dynamics_macros::robot! {
///     pub robot Pendulum; gravity = [0.0, -9.81, 0.0];
///     link base; link rod { mass = 1.0; com = [0.2, 0.0, 0.0]; inertia = [1e-3, 1e-2, 1e-2]; }
///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
/// }
/// let arm = Pendulum::default();
/// let friction = [Effect::CoulombFriction { joint: 0, fc: 0.3, vw: 0.01 }];
/// let run = |seed| SynthOptions { duration: 4.0, seed, ..Default::default() };
/// let a = synthesize(&arm, &friction, &run(1)).unwrap();
/// let b = synthesize(&arm, &friction, &run(2)).unwrap();
/// let report = diagnose(&arm, &a, &b, &Options::default(), &|_, _| {}).unwrap();
/// let lines = explanation_lines(&report);
/// assert!(lines[0].starts_with("explanation (1 effect, in the order of their gains"));
/// assert!(lines[1].contains("coulomb_friction"));
/// ```
pub fn explanation_lines(report: &dynamics_sim2real::diagnose::Report) -> Vec<String> {
    let effects = &report.which.effects;
    if effects.is_empty() {
        return vec![
            "explanation: no effect both explains the training gap by the margins and holds on the held-out data"
                .to_string(),
        ];
    }
    let n = effects.len();
    let mut lines = vec![format!(
        "explanation ({n} effect{}, in the order of their gains; share of the training gap, held-out \
         contribution, held-out gap above noise left once added):",
        if n == 1 { "" } else { "s" }
    )];
    for (i, e) in effects.iter().enumerate() {
        let place = e.joint.clone().or(e.point.clone()).unwrap_or_default();
        let left = report
            .shrink
            .steps
            .iter()
            .find(|s| s.effects == i + 1)
            .map(|s| format!("{:5.1} %", 100.0 * (1.0 - s.torque_fraction)))
            .unwrap_or_else(|| "    -".into());
        let rival = e
            .ambiguous_with
            .as_ref()
            .map(|r| {
                let at = r.joint.clone().or(r.point.clone()).unwrap_or_default();
                let why = r
                    .inseparable
                    .as_deref()
                    .unwrap_or("these data cannot tell them apart");
                format!(" (or {} {at}: {why})", r.kind)
            })
            .unwrap_or_default();
        lines.push(format!(
            "  {:2} {:24} {:12} {:5.1} %  {:+6.1} %  {left}{rival}",
            i + 1,
            e.kind,
            place,
            100.0 * e.share,
            100.0 * e.holdout_contribution,
        ));
        let detail = e.description.clone().unwrap_or_else(|| {
            e.parameters
                .iter()
                .map(|p| match &p.note {
                    Some(note) => format!("{}: {note}", p.name),
                    None => format!("{} = {:.4e} +- {:.1e}", p.name, p.value, p.std),
                })
                .collect::<Vec<_>>()
                .join(", ")
        });
        if !detail.is_empty() {
            lines.push(format!("       {detail}"));
        }
    }
    lines.push(format!(
        "  with {}: held-out gap above noise -{:.1} %, plain RMS of the effort residual over all joints -{:.1} %",
        if n == 1 { "it".to_string() } else { format!("all {n}") },
        100.0 * report.shrink.torque_fraction,
        100.0 * report.shrink.rms_fraction
    ));
    lines
}
