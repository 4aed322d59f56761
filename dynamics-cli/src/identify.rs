//! `dynamics identify`: the plain least-squares identification baseline
//! (`dynamics_sim2real::identify`) on two data files: the fitted friction,
//! offsets and rotor inertias per joint, the link corrections in words,
//! what the data could not determine, and the held-out shrink; the same as
//! JSON on request.

use std::path::PathBuf;

use dynamics_runtime::Robot;
use dynamics_sim2real::identify::{identify, Estimate, Identification, Options};
use dynamics_sim2real::inertial::describe;
use serde_json::{json, Value};

use crate::Res;

fn estimate(e: Estimate) -> Value {
    json!({ "value": e.value, "std": e.std })
}

/// Identifies `robot`'s corrections on `train`, judges them on `holdout`
/// (CSV, Parquet or ROS 2 bags: [`crate::gap::DataFile`]), prints them and
/// writes the JSON to `json` when given.
pub fn identify_cmd<R: Robot<N>, const N: usize>(
    robot: &R,
    train: crate::gap::DataFile,
    holdout: crate::gap::DataFile,
    json_out: Option<PathBuf>,
) -> Res {
    let (a, about_a) = train.read_described(&R::JOINT_NAMES)?;
    let (b, about_b) = holdout.read_described(&R::JOINT_NAMES)?;
    for about in about_a.iter().chain(&about_b) {
        println!("data: {about}");
    }
    let all: Vec<_> = a.warnings.iter().chain(&b.warnings).cloned().collect();
    for w in crate::warnings::lines(&all) {
        eprintln!("warning: {w}");
    }
    let id = identify(robot, &a, &b, &Options::default())?;
    let pm = |e: Estimate| match e.std {
        Some(s) => format!("{:+.4e} +- {s:.1e}", e.value),
        None => "(in a combination)".to_string(),
    };
    println!(
        "{} base parameters of {} columns, {} training rows",
        id.rank, id.columns, id.train_rows
    );
    for t in &id.joints {
        println!(
            "  {:10} coulomb {}  viscous {}  offset {}  armature {}  held-out {:.4} -> {:.4}",
            t.joint,
            pm(t.coulomb),
            pm(t.viscous),
            pm(t.offset),
            pm(t.armature),
            t.holdout_before,
            t.holdout_after
        );
    }
    for l in &id.links {
        let delta = nalgebra::SVector::<f64, 10>::from(l.delta.map(|e| e.value));
        println!("  {}", describe(l.link, &l.nominal, &delta));
    }
    println!("not determined on their own ({}):", id.dropped.len());
    for d in id.dropped.iter().filter(|d| !d.combination.is_empty()) {
        let combo: Vec<String> = d
            .combination
            .iter()
            .map(|(c, v)| format!("{v:+.3} {c}"))
            .collect();
        println!("  {} = {}", d.column, combo.join(" "));
    }
    let zero = id
        .dropped
        .iter()
        .filter(|d| d.combination.is_empty())
        .count();
    println!("  and {zero} columns not excited at all");
    println!(
        "held-out torque RMS shrink (all joints, noise included): {:.1} %",
        100.0 * id.shrink
    );
    if let Some(path) = json_out {
        let doc = to_json(R::NAME, &id);
        std::fs::write(&path, serde_json::to_string_pretty(&doc)?)
            .map_err(|e| format!("{}: {e}", path.display()))?;
        eprintln!("wrote {}", path.display());
    }
    Ok(())
}

/// The identification as the JSON `identify --json` writes: robot, rank,
/// columns, training rows, shrink, per joint the friction, offset and
/// rotor inertia estimates (`{value, std}`, `std` null where only a
/// combination is determined) with the held-out RMS before and after, per
/// link the nominal parameters and their corrections, and what was dropped.
///
/// ```
/// use dynamics_sim2real::identify::Identification;
/// let id = Identification {
///     joints: vec![], links: vec![], columns: 12, rank: 9, dropped: vec![],
///     train_rows: 3000, shrink: 0.25,
/// };
/// let doc = dynamics_cli::identify::to_json("arm", &id);
/// assert_eq!(doc["robot"], "arm");
/// assert_eq!((doc["rank"].as_u64(), doc["shrink"].as_f64()), (Some(9), Some(0.25)));
/// ```
pub fn to_json(robot: &str, id: &Identification) -> Value {
    json!({
        "robot": robot,
        "rank": id.rank,
        "columns": id.columns,
        "train_rows": id.train_rows,
        "shrink": id.shrink,
        "joints": id.joints.iter().map(|t| json!({
            "joint": t.joint,
            "coulomb": estimate(t.coulomb),
            "viscous": estimate(t.viscous),
            "offset": estimate(t.offset),
            "armature": estimate(t.armature),
            "holdout_before": t.holdout_before,
            "holdout_after": t.holdout_after,
        })).collect::<Vec<_>>(),
        "links": id.links.iter().map(|l| json!({
            "link": l.link,
            "nominal": l.nominal.as_slice(),
            "delta": l.delta.iter().map(|e| estimate(*e)).collect::<Vec<_>>(),
        })).collect::<Vec<_>>(),
        "dropped": id.dropped.iter().map(|d| json!({
            "column": d.column,
            "combination": d.combination.iter().map(|(c, v)| json!({ "column": c, "coefficient": v })).collect::<Vec<_>>(),
        })).collect::<Vec<_>>(),
    })
}
