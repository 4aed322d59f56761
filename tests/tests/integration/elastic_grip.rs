//! Dissertation, sec. 3.3: the arm with an elastic grip. The generated model is
//! the dissertation's (kinetic energy of M written here by hand from the transfer
//! matrices 3.49, potential 3.56); the energy balance closes against the
//! work of drives and drag; the equivalent-mass factor of eq. 3.58 is the
//! integral it claims to be, and the equivalent-mass model agrees with the
//! full beam model of the handle in the limit it is meant for (end mass
//! heavy against the rod) and not outside it.

use dynamics_runtime::Robot;
use nalgebra::Vector4;
use robots::scenarios::elastic_grip::{
    beam_frequencies, equivalent_frequency, simulate, DRAG, DRIVES, EI, HANDLE_MASS, KM, LOAD, ROD,
};
use robots::{ElasticGrip, ElasticGripParams};

/// Kinetic and potential energy written from the dissertation: M at
/// `R(q1) [l1, 0] + R(q1 + q2) [l3 + q3, q4]`, arms J1 about O, J2 about A.
fn hand_energies(q: &Vector4<f64>, qd: &Vector4<f64>, m: f64) -> (f64, f64) {
    let (l1, l3, g) = (0.3, 0.5, 10.0);
    let s = qd[0] + qd[1];
    let ve = l1 * qd[0] * q[1].sin() + qd[2] - q[3] * s;
    let vn = l1 * qd[0] * q[1].cos() + (l3 + q[2]) * s + qd[3];
    let t = 0.5 * 4.0 * qd[0] * qd[0] + 0.5 * 4.0 * s * s + 0.5 * m * (ve * ve + vn * vn);
    let a = q[0] + q[1];
    let c4 = 3.0 * 6.626e10 * 1.14197e-8 / 0.125;
    let pi = m * g * (l1 * q[0].sin() + (q[2] + l3) * a.sin() + q[3] * a.cos())
        + 0.5 * 125.0 * (q[2] - 0.15).powi(2)
        + 0.5 * c4 * q[3] * q[3];
    (t, pi)
}

#[test]
fn generated_model_has_the_seeds_energies() {
    let grip = ElasticGrip::default();
    let mut worst = 0.0f64;
    for k in 0..50 {
        let x = |i: usize| ((k * 7 + i * 13) as f64 * 0.618).sin();
        let q = Vector4::new(3.0 * x(0), 3.0 * x(1), 0.3 * x(2), 0.01 * x(3));
        let qd = Vector4::new(2.0 * x(4), 2.0 * x(5), x(6), 0.5 * x(7));
        let (t, pi) = hand_energies(&q, &qd, 1.0);
        worst = worst
            .max((grip.kinetic_energy(&q, &qd) - t).abs() / (1.0 + t))
            .max((grip.potential_energy(&q) - pi).abs() / (1.0 + pi.abs()));
    }
    assert!(worst < 1e-12, "relative difference {worst:e}");
}

#[test]
fn energy_change_equals_the_work_of_drives_and_drag() {
    for mass in [LOAD, LOAD + KM * HANDLE_MASS] {
        let dt = 1e-3;
        let run = simulate(mass, 3.0, dt).expect("simulates");
        let model = ElasticGrip::new(ElasticGripParams {
            m: mass,
            ..ElasticGripParams::default()
        });
        let tr = &run.trajectory;
        let e0 = model.total_energy(&tr.q[0], &tr.qd[0]);
        let scale = run.drive_work.iter().fold(1.0f64, |m, w| m.max(w.abs()));
        // The work integrated beside the motion against Simpson's rule on
        // the samples, with the dissertation's coefficients.
        let u = Vector4::from(DRIVES);
        let b = Vector4::from(DRAG);
        let power: Vec<f64> = tr
            .qd
            .iter()
            .map(|qd| u.dot(qd) - qd.component_mul(qd).dot(&b))
            .collect();
        let mut acc = 0.0;
        let mut worst_w = 0.0f64;
        let mut worst_e = 0.0f64;
        for k in (2..tr.t.len()).step_by(2) {
            acc += dt / 3.0 * (power[k - 2] + 4.0 * power[k - 1] + power[k]);
            let w = run.drive_work[k] + run.drag_work[k];
            worst_w = worst_w.max((acc - w).abs());
            let de = model.total_energy(&tr.q[k], &tr.qd[k]) - e0;
            worst_e = worst_e.max((de - w).abs());
        }
        assert!(
            worst_w < 1e-6 * scale,
            "m = {mass}: work off by {worst_w:e}"
        );
        assert!(
            worst_e < 1e-8 * scale,
            "m = {mass}: balance off by {worst_e:e} J"
        );
        let last = run.drag_work.len() - 1;
        assert!(run.drag_work[last] < 0.0);
        // The rod really vibrates and the arm really moves.
        assert!(tr.q.iter().any(|q| q[3].abs() > 5e-4));
        assert!(tr.q[last][0].abs() > 0.5);
    }
}

#[test]
fn equivalent_mass_factor_is_the_integral_of_eq_3_58() {
    // Static deflection of a cantilever under an end load, from the beam
    // equation E I w'''' = 0 with w(0) = w'(0) = 0, M(l) = 0, V(l) = P.
    let shape = |s: f64| s * s * (3.0 - s) / 2.0;
    let n = 2000;
    let h = 1.0 / n as f64;
    let integral: f64 = (0..n)
        .map(|k| {
            let (a, b) = (k as f64 * h, (k + 1) as f64 * h);
            h / 6.0 * (shape(a).powi(2) + 4.0 * shape(0.5 * (a + b)).powi(2) + shape(b).powi(2))
        })
        .sum();
    assert!((integral - KM).abs() < 1e-12, "{integral} vs {KM}");
}

#[test]
fn equivalent_mass_matches_the_full_beam_where_it_is_meant_to() {
    let mut last = f64::INFINITY;
    for ratio in [0.75, 0.3, 0.1, 0.01] {
        let m0 = ratio * LOAD;
        let full = beam_frequencies(LOAD, m0, EI, ROD, 40).expect("beam")[0];
        let eq = equivalent_frequency(LOAD, m0);
        let err = (eq - full).abs() / full;
        // Rayleigh's quotient: an upper bound, tight for a heavy end mass.
        assert!(eq >= full * (1.0 - 1e-9), "m0/m = {ratio}");
        assert!(err < 1e-3 && err < last, "m0/m = {ratio}: {err:e}");
        last = err;
    }
    assert!(last < 1e-6, "m0/m = 0.01: {last:e}");
    // Without an end mass the lumped model misses the first mode by 1.5 %
    // (3.567 vs 3.516 sqrt(E I / (rho A l^4))): outside its limit.
    let full = beam_frequencies(1e-9, HANDLE_MASS, EI, ROD, 40).expect("beam")[0];
    let eq = equivalent_frequency(1e-9, HANDLE_MASS);
    assert!((eq / full - 3.567 / 3.516).abs() < 2e-3, "{}", eq / full);
}

#[test]
fn scenario_runs_and_writes_its_files() {
    let dir = std::env::temp_dir().join("dynamics-test-elastic-grip");
    let lines = robots::scenarios::run("elastic-grip", &dir).expect("runs");
    for f in [
        "elastic-grip-massless.csv",
        "elastic-grip-handle.csv",
        "u.svg",
        "y.svg",
        "y-zoom.svg",
        "phi.svg",
    ] {
        let text = std::fs::read_to_string(dir.join(f)).expect(f);
        assert!(text.len() > 1000, "{f} is nearly empty");
    }
    assert!(lines.iter().any(|l| l.contains("equivalent mass")));
}
