//! `dynamics simulate`: a robot with effects it is not told about along a
//! motion, its CSV and plots.

use crate::{dynamics, fails, fresh_dir, succeeds};

/// `simulate`: the arm3r with friction it is not told about follows pick
/// and place; the CSV has the trajectory CSV's columns, its accelerations
/// agree with the velocities' differences, and the plots are written.
#[test]
fn simulate_writes_the_csv_and_plots() {
    let dir = fresh_dir("simulate");
    let effects = dir.join("effects.json");
    std::fs::write(&effects, r#"{"effects": [{"kind": "viscous_friction", "joint": "j2", "parameters": [{"name": "fv", "value": 0.5}]}]}"#).expect("writes");
    succeeds(
        dynamics()
            .args([
                "simulate",
                "--robot",
                "arm3r",
                "--motion",
                "pick-place",
                "--duration",
                "2",
                "--rate",
                "10000",
            ])
            .arg("--effects")
            .arg(&effects)
            .arg("--out")
            .arg(&dir),
    );
    let csv = std::fs::read_to_string(dir.join("arm3r.csv")).expect("csv");
    let mut lines = csv.lines();
    assert_eq!(
        lines.next(),
        Some("t,q_j1,q_j2,q_j3,qd_j1,qd_j2,qd_j3,qdd_j1,qdd_j2,qdd_j3,tau_j1,tau_j2,tau_j3")
    );
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|v| v.parse().expect("number")).collect())
        .collect();
    assert_eq!(rows.len(), 20001);
    for k in [5000, 10000, 15000] {
        for j in 0..3 {
            // The effort is held over each sample interval: the velocity's
            // forward difference is that interval's mean acceleration
            // (which moves off the sample's by jerk x dt / 2: 0.1 ms here).
            let diff = (rows[k + 1][4 + j] - rows[k][4 + j]) / 1e-4;
            let qdd = rows[k][7 + j];
            assert!(
                (diff - qdd).abs() < 1e-2 * (1.0 + qdd.abs()),
                "qdd {qdd} vs {diff}"
            );
        }
    }
    for f in ["q-j1.svg", "error.svg", "tau.svg"] {
        assert!(std::fs::read_to_string(dir.join(f))
            .expect("svg")
            .starts_with("<svg"));
    }
    let err = fails(dynamics().args(["simulate", "--robot", "arm3r", "--motion", "spiral"]));
    assert!(err.contains("--motion `spiral`"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}
