//! Invariants that hold for every correct model, checked on random states
//! with proptest: A symmetric positive definite; dA/dt - 2C skew-symmetric;
//! Qqt1 + Qqt2 equal to the Christoffel form computed from finite
//! differences of A alone; g = dPi/dq; point Jacobians = d(position)/dq;
//! power balance along a path; forward and inverse dynamics inverse to
//! each other.

use dynamics_runtime::Robot;
use dynamics_tests::{christoffel_bias, mass_matrix_rate, scale};
use nalgebra::SVector;
use proptest::prelude::*;

fn state() -> impl Strategy<Value = ([f64; 3], [f64; 3], [f64; 3])> {
    let v = || prop::array::uniform3(-2.0f64..2.0);
    (prop::array::uniform3(-3.1f64..3.1), v(), v())
}

fn vec3(a: [f64; 3]) -> SVector<f64, 3> {
    SVector::from(a)
}

/// Every invariant at one state.
fn invariants<R: Robot<N>, const N: usize>(
    r: &R,
    q: &SVector<f64, N>,
    qd: &SVector<f64, N>,
    qdd: &SVector<f64, N>,
) {
    let a = r.mass_matrix(q);
    assert!(
        (a - a.transpose()).abs().max() <= 1e-14 * scale(&a, 1.0),
        "A symmetric"
    );
    assert!(a.cholesky().is_some(), "A positive definite: {a}");

    let c = r.coriolis_matrix(q, qd);
    let n = mass_matrix_rate(r, q, qd) - c * 2.0;
    let tol = 1e-6 * scale(&a, 1.0) * (1.0 + qd.norm());
    assert!(
        (n + n.transpose()).abs().max() < tol,
        "dA/dt - 2C skew: {n}"
    );

    let qqt = r.qqt1(q, qd) + r.qqt2(q, qd);
    assert!((r.qqt(q, qd) - qqt).abs().max() < 1e-12 * (1.0 + qqt.abs().max()));
    assert!(
        (c * qd + qqt).abs().max() < 1e-10 * (1.0 + qqt.abs().max()),
        "C qd = -(Qqt1 + Qqt2)"
    );
    let fd = christoffel_bias(r, q, qd);
    assert!(
        (qqt + fd).abs().max() < tol,
        "Christoffel form: {qqt} vs {fd}"
    );

    // Gravity = gradient of the gravity potential (with springs off this is Pi).
    let h = 1e-6;
    let grad = SVector::<f64, N>::from_fn(|i, _| {
        let mut e = SVector::<f64, N>::zeros();
        e[i] = h;
        (r.potential_energy(&(q + e)) - r.potential_energy(&(q - e))) / (2.0 * h)
    });
    let q0_static = r.generalized_forces(q, &SVector::zeros());
    assert!(
        (grad + q0_static).abs().max() < 1e-5 * (1.0 + grad.abs().max()),
        "Q(0) at rest = -dPi/dq"
    );

    for p in 0..R::POINT_NAMES.len() {
        let jac = r.point_jacobian(p, q).expect("point");
        for i in 0..N {
            let mut e = SVector::<f64, N>::zeros();
            e[i] = h;
            let d = (r.point_position(p, &(q + e)).expect("point")
                - r.point_position(p, &(q - e)).expect("point"))
                / (2.0 * h);
            assert!(
                (jac.column(i) - d).abs().max() < 1e-6,
                "point Jacobian column {i}"
            );
        }
    }

    let tau = r.inverse_dynamics(q, qd, qdd);
    let back = r.forward_dynamics(q, qd, &tau).expect("forward dynamics");
    assert!(
        (back - qdd).abs().max() < 1e-8 * (1.0 + qdd.abs().max()),
        "forward(inverse) = id"
    );
    let terms = r.motion_terms(q, qd);
    assert!(
        (terms.a - a).abs().max() == 0.0
            && (terms.q0 - r.generalized_forces(q, qd)).abs().max() < 1e-12
    );
}

/// d(T + Pi)/dt = qd . (U + Q_nc) along q(t) = q0 + w sin(t), where
/// Q_nc = Q(0)(q, qd) - Q(0)(q, 0) is the non-conservative part.
fn power_balance<R: Robot<N>, const N: usize>(r: &R, q0: &SVector<f64, N>, w: &SVector<f64, N>) {
    let path = |t: f64| (q0 + w * t.sin(), w * t.cos(), -w * t.sin());
    let energy = |t: f64| {
        let (q, qd, _) = path(t);
        r.total_energy(&q, &qd)
    };
    for k in 0..20 {
        let t = 0.1 + 0.3 * k as f64;
        let (q, qd, qdd) = path(t);
        let h = 1e-5;
        let de = (energy(t + h) - energy(t - h)) / (2.0 * h);
        let u = r.inverse_dynamics(&q, &qd, &qdd);
        let qnc = r.generalized_forces(&q, &qd) - r.generalized_forces(&q, &SVector::zeros());
        let power = qd.dot(&(u + qnc));
        // Central differences of E lose about eps |E| / h to rounding: the
        // MAR's drive springs hold up to ~1e6 J while the power is ~1 W.
        let rounding = 1e-10 * energy(t).abs();
        assert!(
            (de - power).abs() < 1e-6 * (1.0 + power.abs()) + rounding,
            "t = {t}: dE/dt = {de}, power = {power}, E = {}",
            energy(t)
        );
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn arm3r_invariants((q, qd, qdd) in state()) {
        invariants(&robots::Arm3r::default(), &vec3(q), &vec3(qd), &vec3(qdd));
    }

    #[test]
    fn rrp_invariants((q, qd, qdd) in state()) {
        // Keep the plunger inside its stroke.
        let q = [q[0], q[1], q[2] / 6.0];
        let r = robots::Rrp::rigid();
        invariants(&r, &vec3(q), &vec3(qd), &vec3(qdd));
    }

    #[test]
    fn mar_invariants((q, qd, qdd) in state()) {
        let q = [q[0], q[1], q[2] / 10.0];
        invariants(&robots::Mar::default(), &vec3(q), &vec3(qd), &vec3(qdd));
    }

    #[test]
    fn power_balance_with_damping_springs_and_drives((q, w, _) in state()) {
        power_balance(&robots::Arm3r::new(robots::Arm3rParams { b1: 1.0, b2: 1.0, b3: 1.0, m: 2.0 }), &vec3(q), &vec3(w));
        let q_rrp = vec3([q[0], q[1], q[2] / 10.0]);
        power_balance(&robots::Rrp::default(), &q_rrp, &vec3([w[0], w[1], w[2] / 10.0]));
        power_balance(&robots::Mar::with_drives([0.1, -0.2, 0.05]), &vec3([q[0], q[1], q[2] / 10.0]), &vec3([w[0], w[1], w[2] / 10.0]));
    }
}

/// K, D and dF/dp against central finite differences of the inverse
/// dynamics (with damping, springs and drives switched on).
fn perturbation_by_differences<R: Robot<N> + Clone, const N: usize>(
    r: &R,
    q: &SVector<f64, N>,
    qd: &SVector<f64, N>,
    qdd: &SVector<f64, N>,
) {
    use dynamics_runtime::Parameters;
    let pj = r.perturbation_jacobians(q, qd, qdd);
    let h = 1e-6;
    let tau = |q: &SVector<f64, N>, qd: &SVector<f64, N>| r.inverse_dynamics(q, qd, qdd);
    let scale = 1.0 + tau(q, qd).abs().max();
    for j in 0..N {
        let mut e = SVector::<f64, N>::zeros();
        e[j] = h;
        let dk = (tau(&(q + e), qd) - tau(&(q - e), qd)) / (2.0 * h);
        let dd = (tau(q, &(qd + e)) - tau(q, &(qd - e))) / (2.0 * h);
        assert!(
            (pj.k.column(j) - dk).abs().max() < 1e-6 * scale,
            "K column {j}: {} vs {dk}",
            pj.k.column(j)
        );
        assert!(
            (pj.d.column(j) - dd).abs().max() < 1e-6 * scale,
            "D column {j}"
        );
    }
    for (p, name) in R::Params::NAMES.iter().enumerate() {
        let value = r.params().get(name).expect("parameter");
        let dh = h * (1.0 + value.abs());
        let (mut up, mut down) = (r.clone(), r.clone());
        up.params_mut().set(name, value + dh).expect("set");
        down.params_mut().set(name, value - dh).expect("set");
        let fd = (up.inverse_dynamics(q, qd, qdd) - down.inverse_dynamics(q, qd, qdd)) / (2.0 * dh);
        let ours = r.parameter_sensitivity(p, q, qd, qdd).expect("sensitivity");
        assert!(
            (ours - fd).abs().max() < 1e-5 * scale,
            "d tau/d {name}: {ours} vs {fd}"
        );
    }
    assert!(r
        .parameter_sensitivity(R::Params::NAMES.len(), q, qd, qdd)
        .is_none());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]

    #[test]
    fn perturbation_jacobians_match_finite_differences((q, qd, qdd) in state()) {
        perturbation_by_differences(&robots::Arm3r::new(robots::Arm3rParams { m: 2.0, b1: 1.0, b2: 0.5, b3: 0.2 }), &vec3(q), &vec3(qd), &vec3(qdd));
        let small = vec3([q[0], q[1], q[2] / 10.0]);
        perturbation_by_differences(&robots::Rrp::default(), &small, &vec3(qd), &vec3(qdd));
        perturbation_by_differences(&robots::Mar::with_drives([0.1, 0.2, 0.0]), &small, &vec3(qd), &vec3(qdd));
    }
}

/// The constraint Jacobian and acceleration bias against finite
/// differences along a path: d2f/dt2 = J qdd + bias.
fn constraint_by_differences<
    R: dynamics_runtime::Constrained<N, M>,
    const N: usize,
    const M: usize,
>(
    r: &R,
    q0: &SVector<f64, N>,
    w: &SVector<f64, N>,
) {
    let path = |t: f64| (q0 + w * t.sin(), w * t.cos(), -w * t.sin());
    let f = |t: f64| r.constraint_residual(t, &path(t).0);
    for k in 0..10 {
        let t = 0.2 + 0.5 * k as f64;
        let (q, qd, qdd) = path(t);
        let h = 1e-4;
        let d2 = (f(t + h) - f(t) * 2.0 + f(t - h)) / (h * h);
        let ours = r.constraint_jacobian(t, &q) * qdd + r.constraint_bias(t, &q, &qd);
        assert!(
            (d2 - ours).abs().max() < 1e-5 * (1.0 + ours.abs().max()),
            "t = {t}: {d2} vs {ours}"
        );
        let d1 = (f(t + h) - f(t - h)) / (2.0 * h);
        assert!(
            (d1 - r.constraint_jacobian(t, &q) * qd).abs().max() < 1e-6 * (1.0 + d1.abs().max())
        );
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]

    #[test]
    fn rrp_line_constraint_derivatives((q, w, _) in state()) {
        constraint_by_differences(&robots::Rrp::default(), &vec3([q[0], q[1], q[2] / 10.0]), &vec3(w));
    }
}

fn vec_n<const N: usize>(x: &[f64]) -> SVector<f64, N> {
    SVector::from_fn(|i, _| x[i])
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(16))]

    #[test]
    fn industrial_arm_invariants(
        x in prop::collection::vec(-3.1f64..3.1, 7),
        v in prop::collection::vec(-2.0f64..2.0, 7),
        a in prop::collection::vec(-2.0f64..2.0, 7),
    ) {
        invariants(&robots::Ur5::default(), &vec_n::<6>(&x), &vec_n::<6>(&v), &vec_n::<6>(&a));
        invariants(&robots::Panda::rigid(), &vec_n::<7>(&x), &vec_n::<7>(&v), &vec_n::<7>(&a));
        perturbation_by_differences(&robots::Panda::default(), &vec_n::<7>(&x), &vec_n::<7>(&v), &vec_n::<7>(&a));
    }
}
