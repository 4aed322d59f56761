//! The scenarios of the two source works (docs/references.md), runnable by name (`dynamics scenario NAME`): each
//! writes a CSV of the motion and SVG plots into a folder and returns a
//! short summary.

use std::path::Path;

use dynamics_runtime::ode::Tolerances;
use dynamics_runtime::{simulate, simulate_program, Baumgarte, Robot, Trajectory};
use nalgebra::Vector3;
use thiserror::Error;

use dynamics_cli::plot::{svg, Series};

mod circle;
pub mod clearance;
mod clearance_files;
pub mod clearance_modes;
pub mod clearance_run;
pub mod elastic_grip;
pub mod environment;
pub mod mar;
mod support;

/// Scenario names with a line each.
pub const SCENARIOS: &[(&str, &str)] = &[
    (
        "arm3r-free",
        "dissertation, sec. 3.1.1: the 3R arm released from rest at q = 0 (Figs. 3.2-3.3)",
    ),
    (
        "rrp-line",
        "dissertation, sec. 3.1.2: the RRP arm carrying M along the line KL (eq. 3.7/3.14)",
    ),
    (
        "arm3r-circle",
        "dissertation, ch. 4: the 3R arm's tool on a circle under PD + gravity, computed torque and sliding mode",
    ),
    (
        "mar-vibration",
        "vibration paper: inertial vibrations of the MAR's links 2 and 3 on the Table 2 path (Figs. 3-8)",
    ),
    (
        "environment",
        "dissertation, sec. 3.4: the piston end C on the line KL against F = -mu |v|^(alpha-1) v",
    ),
    (
        "elastic-grip",
        "dissertation, sec. 3.3: arm with an elastic push rod, handle massless or lumped by eq. 3.58",
    ),
    (
        "clearance",
        "dissertation, sec. 3.2: pin rolling in a ring with clearance, contact loss and re-contact by events",
    ),
];

/// Why a scenario failed.
#[derive(Debug, Error)]
pub enum ScenarioError {
    /// No scenario of that name.
    #[error("unknown scenario `{0}`; known: {known}", known = SCENARIOS.iter().map(|s| s.0).collect::<Vec<_>>().join(", "))]
    Unknown(String),
    /// The simulation stopped.
    #[error(transparent)]
    Sim(#[from] dynamics_runtime::SimError),
    /// The scenario's data are unusable.
    #[error("bad scenario data: {0}")]
    Data(String),
    /// Writing the outputs failed.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// The error.
        source: std::io::Error,
    },
    /// The MAR vibration analysis failed.
    #[error(transparent)]
    Mar(#[from] mar::MarError),
}

/// Runs scenario `name`, writing into `dir`; returns summary lines.
///
/// ```
/// let dir = std::env::temp_dir().join("dynamics-doc-scenario");
/// let lines = robots::scenarios::run("arm3r-free", &dir).unwrap();
/// assert!(dir.join("arm3r-free.csv").exists() && dir.join("q.svg").exists());
/// assert!(!lines.is_empty());
/// ```
pub fn run(name: &str, dir: &Path) -> Result<Vec<String>, ScenarioError> {
    std::fs::create_dir_all(dir).map_err(|source| io(dir, source))?;
    match name {
        "arm3r-free" => arm3r_free(dir),
        "rrp-line" => rrp_line(dir),
        "arm3r-circle" => circle::run(dir),
        "mar-vibration" => mar::run(dir),
        "environment" => environment::run(dir),
        "elastic-grip" => elastic_grip::run(dir),
        "clearance" => clearance_files::run(dir),
        other => Err(ScenarioError::Unknown(other.to_string())),
    }
}

fn io(path: &Path, source: std::io::Error) -> ScenarioError {
    ScenarioError::Io {
        path: path.display().to_string(),
        source,
    }
}

pub(crate) fn write(dir: &Path, file: &str, text: &str) -> Result<(), ScenarioError> {
    let path = dir.join(file);
    std::fs::write(&path, text).map_err(|e| io(&path, e))
}

/// The trajectory as `<name>.csv`.
pub(crate) fn outputs_csv<R: Robot<3>>(
    name: &str,
    tr: &Trajectory<3>,
    dir: &Path,
) -> Result<(), ScenarioError> {
    let mut csv = Vec::new();
    tr.write_csv(&mut csv, &R::JOINT_NAMES)
        .map_err(|e| io(dir, e))?;
    write(dir, &format!("{name}.csv"), &String::from_utf8_lossy(&csv))
}

/// CSV plus q, qd, tau plots and the path of a named point.
fn outputs<R: Robot<3>>(
    robot: &R,
    name: &str,
    tr: &Trajectory<3>,
    point: usize,
    dir: &Path,
) -> Result<(), ScenarioError> {
    outputs_csv::<R>(name, tr, dir)?;
    for (file, label, data) in [
        ("q.svg", "q", &tr.q),
        ("qd.svg", "qd", &tr.qd),
        ("tau.svg", "tau", &tr.tau),
    ] {
        let series: Vec<Series> = (0..3)
            .map(|j| Series {
                name: R::JOINT_NAMES[j],
                points: tr
                    .t
                    .iter()
                    .zip(data.iter())
                    .map(|(t, v)| (*t, v[j]))
                    .collect(),
            })
            .collect();
        write(
            dir,
            file,
            &svg(&format!("{name}: {label}"), "t [s]", label, &series, false),
        )?;
    }
    let path: Vec<(f64, f64)> =
        tr.q.iter()
            .filter_map(|q| robot.point_position(point, q))
            .map(|p| (p[0], p[1]))
            .collect();
    let pname = R::POINT_NAMES.get(point).copied().unwrap_or("point");
    write(
        dir,
        "path.svg",
        &svg(
            &format!("{name}: path of {pname}"),
            "x [m]",
            "y [m]",
            &[Series {
                name: pname,
                points: path,
            }],
            true,
        ),
    )?;
    Ok(())
}

fn arm3r_free(dir: &Path) -> Result<Vec<String>, ScenarioError> {
    let arm = crate::Arm3r::default();
    let tol = Tolerances {
        rtol: 1e-10,
        atol: 1e-12,
        ..Default::default()
    };
    let tr = simulate(
        &arm,
        Vector3::zeros(),
        Vector3::zeros(),
        |_, _, _| Vector3::zeros(),
        3.0,
        0.005,
        tol,
    )?;
    outputs(&arm, "arm3r-free", &tr, 0, dir)?;
    let e0 = arm.total_energy(&tr.q[0], &tr.qd[0]);
    let drift =
        tr.q.iter()
            .zip(&tr.qd)
            .map(|(q, qd)| (arm.total_energy(q, qd) - e0).abs())
            .fold(0.0, f64::max);
    let last = tr.q.len() - 1;
    Ok(vec![
        format!(
            "3 s from rest at q = 0, no drive torque, payload {} kg",
            arm.params.m
        ),
        format!(
            "q(3 s) = [{:.4}, {:.4}, {:.4}] rad",
            tr.q[last][0], tr.q[last][1], tr.q[last][2]
        ),
        format!("largest |T + V - E0| = {drift:.2e} J"),
    ])
}

fn rrp_line(dir: &Path) -> Result<Vec<String>, ScenarioError> {
    let rrp = crate::Rrp::default();
    // Drive efforts of sec. 3.1.2: M1 = 2.5 N m, M2 = 1.5 N m, F = 5 N;
    // the control forces J^T lambda keep the load on KL.
    let drives = Vector3::new(2.5, 1.5, 5.0);
    let tol = Tolerances {
        rtol: 1e-10,
        atol: 1e-12,
        ..Default::default()
    };
    let run = simulate_program(
        &rrp,
        Vector3::zeros(),
        Vector3::zeros(),
        |_, _, _| drives,
        3.0,
        0.005,
        tol,
        Baumgarte::default(),
    )?;
    outputs(&rrp, "rrp-line", &run.trajectory, 0, dir)?;
    let lam: Vec<Series> = vec![Series {
        name: "lambda",
        points: run
            .trajectory
            .t
            .iter()
            .zip(&run.lambda)
            .map(|(t, l)| (*t, l[0]))
            .collect(),
    }];
    write(
        dir,
        "lambda.svg",
        &svg(
            "rrp-line: constraint multiplier",
            "t [s]",
            "lambda",
            &lam,
            false,
        ),
    )?;
    let last = run.trajectory.q.len() - 1;
    Ok(vec![
        "3 s from q = 0 with M1 = 2.5 N m, M2 = 1.5 N m, F = 5 N, spring c = 350 N/m, drag b = 0.15, 0.15, 0.25".to_string(),
        format!("largest constraint violation |f| = {:.2e} m", run.max_violation),
        format!("q(3 s) = [{:.4}, {:.4}, {:.4}]", run.trajectory.q[last][0], run.trajectory.q[last][1], run.trajectory.q[last][2]),
    ])
}
