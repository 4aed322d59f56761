//! The runner of `scripts/real-logs.sh` (copied into the throwaway crate it
//! builds beside `robots.rs`): one diagnosis of a recorded log, split into
//! training and held-out data, printed as rows of the table.
//!
//! Usage: real-logs ROBOT MAP TRAIN WINDOW HOLDOUT WINDOW OUT.json PUBLISHED
//! (WINDOW `a:b` seconds from the first sample, or `-`; PUBLISHED: the
//! authors' friction model, Gaz et al.'s get_FrictionTorque.m or a URDF's
//! `<dynamics damping friction>`).

mod baseline;
mod robots;

use std::path::Path;

use dynamics_runtime::Robot;
use dynamics_sim2real::data::import::{import, ColumnMap};
use dynamics_sim2real::data::Measured;
use dynamics_sim2real::diagnose::{diagnose, Options, Report};

type Res<T> = Result<T, Box<dyn std::error::Error>>;

fn main() -> Res<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.len() != 8 {
        return Err(
            "usage: real-logs ROBOT MAP TRAIN WINDOW HOLDOUT WINDOW OUT.json PUBLISHED".into(),
        );
    }
    match args[0].as_str() {
        "kuka" => run(robots::Kuka::default(), &args),
        "kuka-no-friction" => run(robots::KukaNoFriction::default(), &args),
        "panda-arm" => run(robots::PandaArm::default(), &args),
        "panda-hand" => run(robots::PandaHand::default(), &args),
        other => Err(format!("unknown robot `{other}`").into()),
    }
}

fn window(s: &str) -> Res<Option<(f64, f64)>> {
    if s == "-" {
        return Ok(None);
    }
    let (a, b) = s.split_once(':').ok_or("a window is a:b")?;
    Ok(Some((a.parse()?, b.parse()?)))
}

fn run<R: Robot<N> + Clone + Send + Sync + 'static, const N: usize>(robot: R, args: &[String]) -> Res<()> {
    let map: ColumnMap = args[1].parse()?;
    let train = import(
        Path::new(&args[2]),
        &map,
        &R::JOINT_NAMES,
        window(&args[3])?,
    )?;
    let holdout = import(
        Path::new(&args[4]),
        &map,
        &R::JOINT_NAMES,
        window(&args[5])?,
    )?;
    for w in train.warnings.iter().chain(&holdout.warnings) {
        eprintln!("warning: {w}");
    }
    let start = std::time::Instant::now();
    // HOLD_LINKS=1: link corrections held to the nearest physical body
    // (`dynamics diagnose --hold-links`); JUDGE_LINKS=1: never held
    // (`--judge-links`).
    let options = Options {
        hold_links: std::env::var_os("HOLD_LINKS").is_some_and(|v| v == "1"),
        judge_links: std::env::var_os("JUDGE_LINKS").is_some_and(|v| v == "1"),
        ..Options::default()
    };
    let quiet = |_: usize, _: usize| {};
    let (report, how, train, holdout) = match diagnose(&robot, &train, &holdout, &options, &quiet) {
        // (matched by its message, so that this compiles whether or not the
        // diagnosis still has the error)
        Err(e) if e.to_string().contains("sample interval varies") => {
            // Stop-gap until the reader takes irregular clocks (issue 15).
            eprintln!("the diagnosis refuses the clock as recorded ({e}); stop-gap: repeated rows dropped, linear interpolation at the median interval");
            let (a, b) = (uniform(&train), uniform(&holdout));
            let report = diagnose(&robot, &a, &b, &options, &quiet)?;
            (report, "resampled (stop-gap)", a, b)
        }
        other => (other?, "as recorded", train, holdout),
    };
    let seconds = start.elapsed().as_secs_f64();
    std::fs::write(&args[6], serde_json::to_string_pretty(&report)?)?;
    let floors: Vec<f64> = report
        .where_
        .joints
        .iter()
        .map(|j| j.torque_noise)
        .collect();
    let fitted = baseline::baseline(&robot, &train, &holdout);
    if let Some((b, a)) = &fitted {
        let tool: Vec<String> = report
            .shrink
            .joints
            .iter()
            .map(|j| format!("{:.3}", j.torque_after))
            .collect();
        let row =
            |v: &nalgebra::SVector<f64, N>| v.iter().map(|x| format!("{x:.3}")).collect::<Vec<_>>();
        eprintln!(
            "held-out RMS per joint, N m: nominal {:?}; baseline {:?}; diagnosis {:?}",
            row(b),
            row(a),
            tool
        );
    }
    let base = fitted.map(|(b, a)| {
        (
            above_noise(b.as_slice(), a.as_slice(), &floors),
            1.0 - a.norm() / b.norm(),
        )
    });
    // The library's identification (`dynamics identify`) on the same data.
    let library = dynamics_sim2real::identify::identify(
        &robot,
        &train,
        &holdout,
        &dynamics_sim2real::identify::Options::default(),
    );
    match &library {
        Ok(id) => eprintln!(
            "dynamics_sim2real::identify: plain held-out shrink {:.3} (rank {} of {} columns)",
            id.shrink, id.rank, id.columns
        ),
        Err(e) => eprintln!("dynamics_sim2real::identify: {e}"),
    }
    println!(
        "\nbaseline by dynamics_sim2real::identify (plain shrink): {}",
        library
            .map(|id| format!("{:.3}", id.shrink))
            .unwrap_or_else(|e| e.to_string())
    );
    print_rows(&report, args, how, seconds, base);
    print_friction::<N>(&report, &R::JOINT_NAMES, Path::new(&args[7]))?;
    Ok(())
}

/// Repeated rows dropped, then linear interpolation onto the median interval.
fn uniform<const N: usize>(m: &Measured<N>) -> Measured<N> {
    let mut keep = vec![0usize];
    for k in 1..m.len() {
        let last = keep[keep.len() - 1];
        if m.q[k] != m.q[last] || m.tau[k] != m.tau[last] {
            keep.push(k);
        }
    }
    let mut steps: Vec<f64> = m.t.windows(2).map(|w| w[1] - w[0]).collect();
    steps.sort_by(f64::total_cmp);
    let dt = steps[steps.len() / 2];
    let (t0, t1) = (m.t[keep[0]], m.t[keep[keep.len() - 1]]);
    let mut out = Measured::<N> {
        qd_measured: m.qd_measured,
        ..Default::default()
    };
    let mut i = 0;
    for s in 0..((t1 - t0) / dt) as usize {
        let t = t0 + s as f64 * dt;
        while i + 2 < keep.len() && m.t[keep[i + 1]] <= t {
            i += 1;
        }
        let (a, b) = (keep[i], keep[i + 1]);
        let w = ((t - m.t[a]) / (m.t[b] - m.t[a])).clamp(0.0, 1.0);
        out.t.push(t);
        out.q.push(m.q[a] * (1.0 - w) + m.q[b] * w);
        out.qd.push(m.qd[a] * (1.0 - w) + m.qd[b] * w);
        out.tau.push(m.tau[a] * (1.0 - w) + m.tau[b] * w);
    }
    out
}

fn name(path: &str, window: &str) -> String {
    let file = Path::new(path)
        .file_name()
        .map(|f| f.to_string_lossy().into_owned())
        .unwrap_or_default();
    if window == "-" {
        file
    } else {
        format!("{file} {window} s")
    }
}

/// 1 - gap after / gap before, the gaps above the noise floors (as the diagnosis's shrink).
fn above_noise(before: &[f64], after: &[f64], floors: &[f64]) -> f64 {
    let gap = |x: &[f64]| -> f64 {
        x.iter()
            .zip(floors)
            .map(|(r, f)| (r * r - f * f).max(0.0) / (f * f).max(1e-300))
            .sum()
    };
    let (b, a) = (gap(before), gap(after));
    if b > 0.0 {
        1.0 - (a / b).sqrt()
    } else {
        0.0
    }
}

fn print_rows(report: &Report, args: &[String], how: &str, seconds: f64, base: Option<(f64, f64)>) {
    let v = &report.which.verdict;
    let named = match (&v.joint, &v.point) {
        (Some(j), _) | (None, Some(j)) => format!("{} at {j} ({})", v.kind, v.status),
        _ => format!("{} ({})", v.kind, v.status),
    };
    let (mut before, mut after) = (0.0, 0.0);
    for j in &report.shrink.joints {
        before += j.torque_before * j.torque_before;
        after += j.torque_after * j.torque_after;
    }
    let plain = if before > 0.0 {
        1.0 - (after / before).sqrt()
    } else {
        0.0
    };
    let worst = report
        .where_
        .joints
        .iter()
        .map(|j| j.torque_ratio)
        .fold(0.0, f64::max);
    println!();
    let base = base
        .map(|(a, p)| format!("{a:.3} | {p:.3}"))
        .unwrap_or_else(|| "fit failed | fit failed".into());
    println!("| robot | train | hold-out | data | gap (largest, x noise) | effects named | held-out shrink above noise | plain 1-‖after‖/‖before‖ | baseline LS: above noise | baseline LS: plain | diagnosis s |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    println!(
        "| {} | {} | {} | {how}, {}+{} samples | {worst:.1} | {named} | {:.3} | {plain:.3} | {base} | {seconds:.1} |",
        report.robot,
        name(&args[2], &args[3]),
        name(&args[4], &args[5]),
        report.samples[0],
        report.samples[1],
        report.shrink.torque_fraction,
    );
}

/// Per joint: the published friction beside the calibrated model's
/// (`which.friction`: the nominal model's own with the explanation's
/// corrections; `nominal -> calibrated` where corrected) and the effects
/// the explanation names there.
fn print_friction<const N: usize>(
    report: &Report,
    joints: &[&str; N],
    published: &Path,
) -> Res<()> {
    let text = std::fs::read_to_string(published)?;
    let theirs = if text.contains("fp = [") {
        gaz_friction(&text, N)?
    } else {
        urdf_friction(&text, joints)
    };
    println!();
    println!("| joint | published Coulomb | published viscous | calibrated Coulomb | calibrated viscous | named in the explanation (joint fit) |");
    println!("|---|---|---|---|---|---|");
    for (i, j) in joints.iter().enumerate() {
        let ours = report.which.friction.iter().find(|f| f.joint == *j);
        let level = |nominal: f64, calibrated: f64| {
            if (nominal - calibrated).abs() < 5e-4 {
                format!("{calibrated:.3}")
            } else {
                format!("{nominal:.3} -> {calibrated:.3}")
            }
        };
        let (coulomb, viscous) = match ours {
            Some(f) if f.breakaway > f.coulomb + 5e-4 => (
                format!(
                    "{} (breaking away at {:.3})",
                    level(f.coulomb_nominal, f.coulomb),
                    f.breakaway
                ),
                level(f.viscous_nominal, f.viscous),
            ),
            Some(f) => (
                level(f.coulomb_nominal, f.coulomb),
                level(f.viscous_nominal, f.viscous),
            ),
            None => ("-".into(), "-".into()),
        };
        // The explanation's effects at this joint, with their joint fit.
        let named: Vec<String> = report
            .which
            .effects
            .iter()
            .filter(|e| e.joint.as_deref() == Some(*j))
            .map(|e| {
                let p: Vec<String> = e
                    .parameters
                    .iter()
                    .map(|p| format!("{} {:.3} ± {:.3}", p.name, p.value, p.std))
                    .collect();
                format!("{} ({})", e.kind, p.join(", "))
            })
            .collect();
        println!(
            "| {j} | {} | {} | {coulomb} | {viscous} | {} |",
            theirs[i].0,
            theirs[i].1,
            named.join("; ")
        );
    }
    Ok(())
}

/// Gaz et al.'s sigmoid `A/(1+exp(-alpha (qd + phi))) - A/(1+exp(-alpha phi))`
/// read as a Coulomb level A/2 (and its offset), a slope A alpha / 4 at zero.
fn gaz_friction(text: &str, n: usize) -> Res<Vec<(String, String)>> {
    let body = text
        .split("fp = [")
        .nth(1)
        .and_then(|s| s.split("];").next())
        .ok_or("no `fp = [...]` in the friction file")?;
    let v: Vec<f64> = body
        .split(|c: char| c == ',' || c == ';' || c.is_whitespace())
        .filter(|s| !s.is_empty() && !s.chars().all(|c| c == '.'))
        .map(str::parse)
        .collect::<Result<_, _>>()?;
    if v.len() != 4 * n {
        return Err(format!("the friction file has {} numbers, not 4 x {n}", v.len()).into());
    }
    Ok((0..n)
        .map(|j| {
            let (a, phi, alpha) = (v[j], v[2 * n + j], v[3 * n + j]);
            let offset = a / 2.0 - a / (1.0 + (-alpha * phi).exp());
            (
                format!("{:.3} (offset {offset:+.3})", a / 2.0),
                format!("sigmoid, {:.2} at 0", a * alpha / 4.0),
            )
        })
        .collect())
}

/// A URDF's `<dynamics damping friction>` per joint.
fn urdf_friction<const N: usize>(text: &str, joints: &[&str; N]) -> Vec<(String, String)> {
    joints
        .iter()
        .map(|j| {
            let joint = text
                .split(&format!("<joint name=\"{j}\""))
                .nth(1)
                .and_then(|s| s.split("</joint>").next())
                .unwrap_or("");
            let attr = |a: &str| {
                joint
                    .split(&format!("{a}=\""))
                    .nth(1)
                    .and_then(|s| s.split('"').next())
                    .and_then(|s| s.parse::<f64>().ok())
                    .map(|v| format!("{v:.3}"))
                    .unwrap_or_else(|| "-".into())
            };
            (attr("friction"), attr("damping"))
        })
        .collect()
}
