//! Forward-dynamics derivatives and the state-space model
//! (`dynamics_runtime::linearize`): against Pinocchio's
//! `computeABADerivatives` (the `ddq_dq`, `ddq_dv` fields of the reference
//! files), central finite differences of our own forward dynamics, closed
//! forms, and a fine RK4 integration of the linear system.

use dynamics_runtime::linearize::{forward_dynamics_derivatives, state_space, DiscretizeError};
use dynamics_runtime::{DynamicsError, Robot};
use nalgebra::{DMatrix, SMatrix, SVector, Vector1};
use robots::registry::AnyRobot;
use serde_json::Value;

fn numbers(v: &Value) -> Vec<f64> {
    match v {
        Value::Array(a) => a.iter().flat_map(numbers).collect(),
        Value::Number(n) => n.as_f64().into_iter().collect(),
        _ => Vec::new(),
    }
}

/// `max |ours - theirs| / max |theirs|` with `ours` read row by row.
fn rel_rows<const N: usize>(ours: &SMatrix<f64, N, N>, theirs: &[f64]) -> f64 {
    assert_eq!(theirs.len(), N * N, "reference matrix size");
    let scale = theirs.iter().fold(0.0f64, |m, x| m.max(x.abs())).max(1e-12);
    let err = (0..N * N)
        .map(|k| (ours[(k / N, k % N)] - theirs[k]).abs())
        .fold(0.0, f64::max);
    err / scale
}

/// Worst relative error of ddq_dq and ddq_dv over the reference states.
fn worst_against_reference<R: Robot<N>, const N: usize>(robot: &R, doc: &Value) -> (f64, f64) {
    let states = doc["states"].as_array().expect("states");
    assert_eq!(states.len(), 20);
    let vec = |s: &Value, k: &str| SVector::<f64, N>::from_column_slice(&numbers(&s[k]));
    let mut worst = (0.0f64, 0.0f64);
    for s in states {
        let d = forward_dynamics_derivatives(robot, &vec(s, "q"), &vec(s, "v"), &vec(s, "tau"))
            .expect("reference state");
        worst.0 = worst.0.max(rel_rows(&d.ddq_dq, &numbers(&s["ddq_dq"])));
        worst.1 = worst.1.max(rel_rows(&d.ddq_dv, &numbers(&s["ddq_dv"])));
    }
    worst
}

#[test]
fn forward_dynamics_derivatives_match_pinocchio_aba_derivatives() {
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
        let robot = AnyRobot::by_name(name).expect("known robot");
        let doc: Value = serde_json::from_str(robot.reference().1).expect("reference JSON");
        let (dq, dv) = robots::each_robot!(&robot, r => worst_against_reference(r, &doc));
        println!("{name}: ddq_dq {dq:.1e}, ddq_dv {dv:.1e} (relative to Pinocchio)");
        assert!(
            dq <= 1e-9,
            "{name}: ddq_dq off Pinocchio by {dq:e} (relative)"
        );
        assert!(
            dv <= 1e-9,
            "{name}: ddq_dv off Pinocchio by {dv:e} (relative)"
        );
    }
}

/// Central differences of the forward dynamics against the derivatives and
/// against A^-1 (the input block of the state-space model).
fn finite_differences<R: Robot<N>, const N: usize>(robot: &R, seed: f64) {
    let q = SVector::<f64, N>::from_fn(|i, _| (1.7 * i as f64 + seed).sin() * 1.5);
    let qd = SVector::<f64, N>::from_fn(|i, _| (0.9 * i as f64 - seed).cos() * 2.0);
    let tau = SVector::<f64, N>::from_fn(|i, _| (2.3 * i as f64 + 0.5 * seed).sin() * 5.0);
    let ss = state_space(robot, &q, &qd, &tau).expect("regular state");
    let d = ss.derivatives();
    let fd = |x: SVector<f64, N>, v: SVector<f64, N>, u: SVector<f64, N>| {
        robot.forward_dynamics(&x, &v, &u).expect("regular")
    };
    assert!((d.qdd - fd(q, qd, tau)).norm() < 1e-12 * d.qdd.norm().max(1.0));
    let h = 1e-6;
    let mut num_q = SMatrix::<f64, N, N>::zeros();
    let (mut num_v, mut num_u) = (num_q, num_q);
    for j in 0..N {
        let e = SVector::<f64, N>::from_fn(|i, _| if i == j { h } else { 0.0 });
        num_q.set_column(j, &((fd(q + e, qd, tau) - fd(q - e, qd, tau)) / (2.0 * h)));
        // Quadratic in qd: central differences are exact but for round-off,
        // which a longer step keeps small.
        let ev = e * 1e3;
        num_v.set_column(
            j,
            &((fd(q, qd + ev, tau) - fd(q, qd - ev, tau)) / (2e3 * h)),
        );
        // Linear in tau: a unit step has no truncation error and little round-off.
        let unit = e / h;
        num_u.set_column(j, &((fd(q, qd, tau + unit) - fd(q, qd, tau - unit)) / 2.0));
    }
    for (what, ours, num) in [
        ("ddq_dq", d.ddq_dq, num_q),
        ("ddq_dv", d.ddq_dv, num_v),
        ("A^-1", ss.b.blocks[1][0], num_u),
    ] {
        let err = (ours - num).abs().max() / num.abs().max();
        assert!(
            err < 1e-6,
            "{}: {what} off central differences by {err:e}",
            R::NAME
        );
    }
}

#[test]
fn forward_dynamics_derivatives_match_finite_differences() {
    for seed in [0.3, 1.9] {
        // With the plunger spring and drag, the MAR's drives and Panda's
        // joint damping: terms Pinocchio does not model.
        finite_differences(&robots::Rrp::default(), seed);
        finite_differences(&robots::Mar::with_drives([0.0; 3]), seed);
        finite_differences(&robots::Arm3r::default(), seed);
        finite_differences(&robots::Ur5::default(), seed);
        finite_differences(&robots::Panda::default(), seed);
    }
}

/// The one-pass `motion_and_jacobians` (A and the bias, then K and D at
/// the accelerations it is handed) against the separate outputs.
fn one_pass_matches_the_separate_outputs<R: Robot<N>, const N: usize>(robot: &R, seed: f64) {
    let q = SVector::<f64, N>::from_fn(|i, _| (seed * (i as f64 + 1.0)).sin());
    let qd = SVector::<f64, N>::from_fn(|i, _| (seed * 0.7 * (i as f64 + 2.0)).cos());
    let qdd = SVector::<f64, N>::from_fn(|i, _| 1.5 - 0.4 * i as f64);
    let mut seen = None;
    let (back, pj) = robot
        .motion_and_jacobians(&q, &qd, |t| {
            seen = Some(*t);
            Some(qdd)
        })
        .expect("the closure gives accelerations");
    assert_eq!(back, qdd);
    let close = |what: &str, a: &[f64], b: &[f64]| {
        let scale = b.iter().fold(1.0f64, |m, x| m.max(x.abs()));
        let err = a
            .iter()
            .zip(b)
            .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
        assert!(err <= 1e-12 * scale, "{}: {what} off by {err:e}", R::NAME);
    };
    let (t, sep) = (seen.expect("called once"), robot.motion_terms(&q, &qd));
    close("A", t.a.as_slice(), sep.a.as_slice());
    close("bias", t.bias().as_slice(), sep.bias().as_slice());
    let sep = robot.perturbation_jacobians(&q, &qd, &qdd);
    close("K", pj.k.as_slice(), sep.k.as_slice());
    close("D", pj.d.as_slice(), sep.d.as_slice());
    assert!(robot.motion_and_jacobians(&q, &qd, |_| None).is_none());
}

#[test]
fn one_pass_terms_match_the_separate_outputs() {
    for seed in [0.3, 1.9] {
        one_pass_matches_the_separate_outputs(&robots::Rrp::default(), seed);
        one_pass_matches_the_separate_outputs(&robots::Mar::with_drives([0.0; 3]), seed);
        one_pass_matches_the_separate_outputs(&robots::Arm3r::default(), seed);
        one_pass_matches_the_separate_outputs(&robots::Ur5::default(), seed);
        one_pass_matches_the_separate_outputs(&robots::Panda::default(), seed);
    }
}

/// RK4 on `X' = M X`, `X(0) = I`, with `M = [[A_c, B_c], [0, 0]]`: the
/// blocks of `X(h)` are the zero-order-hold matrices.
fn zoh_by_rk4(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    h: f64,
    steps: usize,
) -> (DMatrix<f64>, DMatrix<f64>) {
    let (n2, n) = (a.nrows(), b.ncols());
    let mut m = DMatrix::zeros(n2 + n, n2 + n);
    m.view_mut((0, 0), (n2, n2)).copy_from(a);
    m.view_mut((0, n2), (n2, n)).copy_from(b);
    let mut x = DMatrix::identity(n2 + n, n2 + n);
    let dt = h / steps as f64;
    for _ in 0..steps {
        let k1 = &m * &x;
        let k2 = &m * (&x + &k1 * (dt / 2.0));
        let k3 = &m * (&x + &k2 * (dt / 2.0));
        let k4 = &m * (&x + &k3 * dt);
        x += (k1 + k2 * 2.0 + k3 * 2.0 + k4) * (dt / 6.0);
    }
    (
        x.view((0, 0), (n2, n2)).into_owned(),
        x.view((0, n2), (n2, n)).into_owned(),
    )
}

#[test]
fn zero_order_hold_matches_a_fine_rk4_integration() {
    let panda = robots::Panda::default();
    let q = SVector::<f64, 7>::from_fn(|i, _| 0.3 * i as f64 - 0.8);
    let qd = SVector::<f64, 7>::from_fn(|i, _| (i as f64).cos());
    let tau = panda.gravity(&q);
    let ss = state_space(&panda, &q, &qd, &tau).expect("regular");
    for h in [1e-3, 0.01, 0.05] {
        let zoh = ss.discretize(h).expect("finite");
        let (ad, bd) = zoh_by_rk4(&ss.a.to_dmatrix(), &ss.b.to_dmatrix(), h, 2000);
        let ea = (zoh.a.to_dmatrix() - &ad).abs().max() / ad.abs().max();
        let eb = (zoh.b.to_dmatrix() - &bd).abs().max() / bd.abs().max();
        assert!(ea < 1e-12 && eb < 1e-12, "h = {h}: A_d {ea:e}, B_d {eb:e}");
    }
}

dynamics_macros::robot! {
    /// A pendulum of mass 2 kg at 0.5 m, with a cart-like twin below.
    pub robot Pendulum;
    gravity = [0.0, -9.81, 0.0];
    link base;
    link rod { mass = 2.0; com = [0.5, 0.0, 0.0]; }
    joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
}

dynamics_macros::robot! {
    /// A free mass on a rail: the double integrator.
    pub robot Rail;
    gravity = [0.0, 0.0, -9.81];
    link base;
    link cart { mass = 4.0; }
    joint x = prismatic(base -> cart) { axis = [1.0, 0.0, 0.0]; }
}

#[test]
fn zero_order_hold_matches_closed_forms() {
    let z = Vector1::zeros();
    // Double integrator x'' = u / m.
    let ss = state_space(
        &Rail::default(),
        &Vector1::new(0.7),
        &Vector1::new(-1.0),
        &z,
    )
    .expect("regular");
    for h in [1e-4, 0.02, 3.0] {
        let d = ss.discretize(h).expect("finite");
        let m = 4.0;
        let want_a = [1.0, h, 0.0, 1.0];
        let want_b = [h * h / (2.0 * m), h / m];
        for k in 0..4 {
            assert!(
                (d.a[(k / 2, k % 2)] - want_a[k]).abs() < 1e-15 * h.max(1.0),
                "h = {h}"
            );
        }
        for k in 0..2 {
            assert!(
                (d.b[(k, 0)] - want_b[k]).abs() < 1e-15 * want_b[k],
                "h = {h}"
            );
        }
    }
    // Pendulum hanging down: dq'' = -w^2 dq + du / I, w^2 = g / l, I = m l^2.
    let down = Vector1::new(-std::f64::consts::FRAC_PI_2);
    let ss = state_space(&Pendulum::default(), &down, &z, &z).expect("regular");
    let (w, inertia) = ((9.81f64 / 0.5).sqrt(), 2.0 * 0.25);
    for h in [1e-3, 0.1, 2.5] {
        let d = ss.discretize(h).expect("finite");
        let (c, s) = ((w * h).cos(), (w * h).sin());
        let want_a = [c, s / w, -w * s, c];
        let want_b = [(1.0 - c) / (w * w * inertia), s / (w * inertia)];
        for k in 0..4 {
            let err = (d.a[(k / 2, k % 2)] - want_a[k]).abs();
            assert!(err < 1e-13, "h = {h}: A_d[{k}] {err:e}");
        }
        for k in 0..2 {
            let err = (d.b[(k, 0)] - want_b[k]).abs();
            assert!(
                err < 1e-13 * want_b[k].abs().max(1e-3),
                "h = {h}: B_d[{k}] {err:e}"
            );
        }
    }
}

#[test]
fn bad_inputs_give_typed_errors() {
    let p = Pendulum::default();
    let nan = Vector1::new(f64::NAN);
    let z = Vector1::zeros();
    assert_eq!(
        forward_dynamics_derivatives(&p, &z, &z, &nan).unwrap_err(),
        DynamicsError::NonFinite {
            quantity: "tau",
            index: 0
        }
    );
    let ss = state_space(&p, &z, &z, &z).expect("regular");
    assert_eq!(
        ss.discretize(f64::NAN).unwrap_err().to_string(),
        "the step h = NaN s is not a finite positive number"
    );
    assert!(matches!(
        ss.discretize(-1.0),
        Err(DiscretizeError::Step { .. })
    ));
    let mut broken = ss;
    broken.a[(1, 0)] = f64::INFINITY;
    assert_eq!(
        broken.discretize(0.1).unwrap_err(),
        DiscretizeError::NonFinite {
            matrix: "A_c",
            row: 1,
            col: 0
        }
    );
    // exp(1e200 h) cannot be represented.
    let mut fast = ss;
    fast.a[(1, 1)] = 1e200;
    assert!(matches!(
        fast.discretize(1.0),
        Err(DiscretizeError::Overflow { .. })
    ));
}
