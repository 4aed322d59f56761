//! Oracle tests: our generated models against Pinocchio 4.1.0 reference
//! values (robots/data/pinocchio/*.json, copied from shared/reference/), and
//! against the hand derivation of arm3r in the reference README.

use dynamics_cli::compare::compare;
use dynamics_runtime::Robot;
use nalgebra::{Matrix3, Vector3};
use robots::registry::AnyRobot;

fn check(name: &str) {
    let robot = AnyRobot::by_name(name).expect("known robot");
    let (file, text) = robot.reference();
    let ours = robot
        .evaluate_json(text, file)
        .expect("reference states evaluate");
    assert_eq!(ours.len(), 20, "{name}: all 20 reference states");
    let doc: serde_json::Value = serde_json::from_str(text).expect("reference JSON");
    assert_eq!(
        doc["joint_names"],
        serde_json::json!(robot.joint_names()),
        "{name}: joint order as Pinocchio's"
    );
    let cmp = compare(&ours, &doc);
    for (field, err) in &cmp.fields {
        assert!(
            *err <= 1e-10,
            "{name}: {field} differs from Pinocchio by {err:e} (relative)"
        );
    }
}

#[test]
fn arm3r_matches_pinocchio() {
    check("arm3r");
}

#[test]
fn rrp_rigid_body_matches_pinocchio() {
    check("rrp-rigid");
}

#[test]
fn mar_matches_pinocchio() {
    check("mar");
}

#[test]
fn arm3r_matches_hand_derivation_at_zero() {
    // shared/reference/pinocchio/README.md, "arm3r by hand".
    let r = robots::Arm3r::default();
    let z = Vector3::zeros();
    let m = r.mass_matrix(&z);
    let expect = Matrix3::new(
        0.89331178, 0.45001938, 0.12170366, 0.45001938, 0.25697856, 0.07284584, 0.12170366,
        0.07284584, 0.02398802,
    );
    assert!((m - expect).abs().max() < 1e-8, "{m}");
    let g = r.gravity(&z);
    assert!(
        (g - Vector3::new(21.93518418, 9.45900018, 2.39403318))
            .abs()
            .max()
            < 1e-8,
        "{g}"
    );
}

#[test]
fn seed_rrp_potential_force_matches_seed_eq_3_11() {
    // Dissertation, eq. 3.11-3.12: Q(0)_3 = -dPi/dq3 - b3 qd3 with
    // Pi = [m1 c1 + (m2+m3+m) l1] g sin q1 + [m2 c2 + m3 c3 + m l3 + (m3 + m) q3] g sin(q1+q2)
    //      + 1/2 c (l0 - q3)^2   (m1 c1 = m2 c2 = 0 here)
    let r = robots::Rrp::default();
    let (q1, q2, q3): (f64, f64, f64) = (0.3, -0.7, 0.12);
    let q = Vector3::new(q1, q2, q3);
    let qd = Vector3::new(0.1, 0.2, -0.3);
    let (m3, m, c3, l1, l3, g, c, b) = (1.0, 10.0, 0.5, 0.5, 1.0, 10.0, 350.0, [0.15, 0.15, 0.25]);
    let a = (1.0 + m3 + m) * l1 * g;
    let bb = (m3 * c3 + m * l3 + (m3 + m) * q3) * g;
    let dpi = [
        a * q1.cos() + bb * (q1 + q2).cos(),
        bb * (q1 + q2).cos(),
        (m3 + m) * g * (q1 + q2).sin() + c * q3,
    ];
    let q0 = r.generalized_forces(&q, &qd);
    for i in 0..3 {
        let expect = -dpi[i] - b[i] * qd[i];
        assert!(
            (q0[i] - expect).abs() < 1e-12,
            "Q0[{i}] = {} vs {expect}",
            q0[i]
        );
    }
}

#[test]
fn ur5_from_urdf_matches_pinocchio() {
    check("ur5");
}

#[test]
fn panda_from_urdf_matches_pinocchio() {
    check("panda");
}

#[test]
fn urdf_twins_of_the_seed_robots_match_pinocchio() {
    for name in ["arm3r-urdf", "rrp-urdf", "mar-urdf"] {
        check(name);
    }
}
