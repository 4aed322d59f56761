//! Dissertation, sec. 3.4: the piston end C on the line KL against the
//! environment's resistance. The orbit error stays below a stated bound,
//! and the energy balance closes: the change of T + Pi equals the work of
//! the drives, of the resistance (computed here from C's velocity, not by
//! the effects library), of the drag and of the control forces.

use dynamics_runtime::{Constrained, Robot};
use nalgebra::Vector3;
use robots::scenarios::environment::{simulate, ALPHA, DRIVES, MU};
use robots::Piston;

/// Composite Simpson rule on equally spaced samples (odd count).
fn simpson(h: f64, f: &[f64]) -> Vec<f64> {
    // Cumulative integral at the even samples.
    let mut out = vec![0.0];
    let mut acc = 0.0;
    let mut k = 0;
    while k + 2 < f.len() {
        acc += h / 3.0 * (f[k] + 4.0 * f[k + 1] + f[k + 2]);
        out.push(acc);
        k += 2;
    }
    out
}

#[test]
fn orbit_error_stays_below_1e9_m() {
    let run = simulate(MU, ALPHA, 3.0, 1e-3).expect("simulates");
    let arm = Piston::default();
    // Recompute the distance of C from KL from C's position itself.
    let mut worst = 0.0f64;
    for q in &run.motion.trajectory.q {
        let c = arm.point_position(0, q).expect("point c");
        let d = (c[1] - 2.0 * c[0] + 2.0 * 1.5).abs() / 5f64.sqrt();
        worst = worst.max(d);
        assert!(arm.constraint_residual(0.0, q)[0].abs() / 5f64.sqrt() - d < 1e-15);
    }
    assert!(worst < 1e-9, "orbit error {worst:e} m");
    assert!((worst - run.max_orbit_error()).abs() < 1e-15);
    // The arm really moves along KL (not a trivial pass).
    let last = arm
        .point_position(0, run.motion.trajectory.q.last().expect("samples"))
        .expect("point c");
    assert!((last - Vector3::new(1.5, 0.0, 0.0)).norm() > 0.5);
}

#[test]
fn energy_change_equals_the_work_of_drives_resistance_drag_and_control() {
    let dt = 1e-3;
    let run = simulate(MU, ALPHA, 3.0, dt).expect("simulates");
    let arm = Piston::default();
    let tr = &run.motion.trajectory;
    let drives = Vector3::from(DRIVES);
    let b = Vector3::new(0.1, 0.1, 0.0);
    let mut p_drive = Vec::new();
    let mut p_res = Vec::new();
    let mut p_drag = Vec::new();
    let mut p_ctrl = Vec::new();
    for k in 0..tr.t.len() {
        let (q, qd) = (&tr.q[k], &tr.qd[k]);
        let v = arm.point_jacobian(0, q).expect("point c") * qd;
        p_drive.push(drives.dot(qd));
        p_res.push(-MU * v.norm().powf(ALPHA + 1.0));
        p_drag.push(-qd.component_mul(qd).dot(&b));
        p_ctrl.push(run.motion.control[k].dot(qd));
    }
    let (w_drive, w_res, w_drag, w_ctrl) = (
        simpson(dt, &p_drive),
        simpson(dt, &p_res),
        simpson(dt, &p_drag),
        simpson(dt, &p_ctrl),
    );
    let e0 = arm.total_energy(&tr.q[0], &tr.qd[0]);
    let mut worst = 0.0f64;
    for (i, k) in (0..tr.t.len()).step_by(2).enumerate() {
        let de = arm.total_energy(&tr.q[k], &tr.qd[k]) - e0;
        let w = w_drive[i] + w_res[i] + w_drag[i] + w_ctrl[i];
        worst = worst.max((de - w).abs());
    }
    let scale = w_drive.iter().fold(0.0f64, |m, w| m.max(w.abs()));
    let last = w_res.len() - 1;
    assert!(
        w_res[last] < -1.0,
        "the resistance removes energy: {}",
        w_res[last]
    );
    assert!(
        w_ctrl[last].abs() < 1e-6 * scale,
        "ideal control does no work: {}",
        w_ctrl[last]
    );
    assert!(
        worst < 1e-6 * scale,
        "balance off by {worst:e} J (scale {scale} J)"
    );
    // The library's force law agrees with the one written here.
    for k in (0..tr.t.len()).step_by(97) {
        let v = arm.point_jacobian(0, &tr.q[k]).expect("point c") * tr.qd[k];
        assert!((run.force[k].dot(&v) - p_res[k]).abs() < 1e-12 * (1.0 + p_res[k].abs()));
    }
}

#[test]
fn scenario_runs_and_writes_its_files() {
    let dir = std::env::temp_dir().join("dynamics-test-environment");
    let lines = robots::scenarios::run("environment", &dir).expect("runs");
    for f in [
        "environment.csv",
        "environment-tip.csv",
        "orbit-error.svg",
        "resistance.svg",
        "piston.svg",
        "path.svg",
    ] {
        let text = std::fs::read_to_string(dir.join(f)).expect(f);
        assert!(text.len() > 1000, "{f} is nearly empty");
    }
    assert!(lines.iter().any(|l| l.contains("orbit error")));
}
