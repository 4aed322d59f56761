//! The URDF-built robots against the hand-written DSL ones, and what the
//! URDF reader exposes (limits, damping parameters).

use dynamics_runtime::{Parameters, Robot};
use nalgebra::SVector;
use proptest::prelude::*;

fn same<A: Robot<N>, B: Robot<N>, const N: usize>(
    a: &A,
    b: &B,
    q: [f64; N],
    v: [f64; N],
    acc: [f64; N],
) {
    let (q, v, acc) = (SVector::from(q), SVector::from(v), SVector::from(acc));
    let close = |x: f64, y: f64| (x - y).abs() <= 1e-12 * (1.0 + y.abs());
    let (ma, mb) = (a.mass_matrix(&q), b.mass_matrix(&q));
    assert!(
        ma.iter().zip(mb.iter()).all(|(x, y)| close(*x, *y)),
        "M: {ma} vs {mb}"
    );
    let (na, nb) = (a.nonlinear_effects(&q, &v), b.nonlinear_effects(&q, &v));
    assert!(
        na.iter().zip(nb.iter()).all(|(x, y)| close(*x, *y)),
        "nle: {na} vs {nb}"
    );
    let (ga, gb) = (a.gravity(&q), b.gravity(&q));
    assert!(ga.iter().zip(gb.iter()).all(|(x, y)| close(*x, *y)), "g");
    let (ta, tb) = (
        a.inverse_dynamics(&q, &v, &acc),
        b.inverse_dynamics(&q, &v, &acc),
    );
    assert!(ta.iter().zip(tb.iter()).all(|(x, y)| close(*x, *y)), "tau");
    assert!(
        close(a.total_energy(&q, &v), b.total_energy(&q, &v)),
        "energy"
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn twins_agree_with_the_dsl_robots(
        q in prop::array::uniform3(-3.1f64..3.1),
        v in prop::array::uniform3(-2.0f64..2.0),
        a in prop::array::uniform3(-2.0f64..2.0),
    ) {
        same(&robots::Arm3rUrdf::default(), &robots::Arm3r::default(), q, v, a);
        let qs = [q[0], q[1], q[2] / 10.0];
        same(&robots::RrpUrdf::rigid(), &robots::Rrp::rigid(), qs, v, a);
        same(&robots::MarUrdf::default(), &robots::Mar::default(), qs, v, a);
    }
}

#[test]
fn limits_come_from_the_urdf() {
    assert_eq!(robots::Panda::LOWER[3], -3.0718);
    assert_eq!(robots::Panda::UPPER[3], -0.0698);
    assert_eq!(robots::Panda::EFFORT[6], 12.0);
    assert_eq!(robots::Ur5::VELOCITY[0], 3.15);
    // A DSL robot has no limits.
    assert_eq!(robots::Arm3r::LOWER, [f64::NEG_INFINITY; 3]);
}

#[test]
fn urdf_damping_is_a_parameter_of_the_generalized_forces() {
    let damped = robots::Panda::default();
    assert_eq!(damped.params.get("damping_panda_joint4"), Some(0.003));
    let rigid = robots::Panda::rigid();
    let q = SVector::<f64, 7>::from_fn(|i, _| 0.1 * i as f64);
    let v = SVector::<f64, 7>::from_fn(|i, _| 1.0 - 0.2 * i as f64);
    let (q0_rigid, q0_damped) = (
        rigid.generalized_forces(&q, &v),
        damped.generalized_forces(&q, &v),
    );
    let diff = q0_rigid - q0_damped;
    // Both are sums with the gravity torques (up to tens of N m): their
    // difference is exact to a few ulp of those, not of the damping term.
    let tol = 4.0 * f64::EPSILON * q0_rigid.abs().max().max(1.0);
    assert!((diff - v * 0.003).abs().max() < tol, "{diff}");
    // RRP: the URDF's 0.15, 0.15, 0.25 are the dissertation's b1..b3.
    let rrp = robots::RrpUrdf::default();
    assert_eq!(rrp.params.get("damping_q3"), Some(0.25));
}

#[test]
fn a_urdf_mass_can_be_made_a_parameter() {
    let fixed = robots::Panda::default();
    let mut symbolic = robots::PandaPayload::default();
    let q = SVector::<f64, 7>::from_fn(|i, _| 0.3 - 0.1 * i as f64);
    let v = SVector::<f64, 7>::from_fn(|i, _| 0.5 - 0.15 * i as f64);
    let a = SVector::<f64, 7>::from_fn(|i, _| 0.2 * i as f64 - 0.6);
    let (t1, t2) = (
        fixed.inverse_dynamics(&q, &v, &a),
        symbolic.inverse_dynamics(&q, &v, &a),
    );
    assert!((t1 - t2).abs().max() < 1e-12, "same default: {t1} vs {t2}");
    // The payload enters linearly: tau(m + 1) - tau(m) = d tau / d payload.
    let k = robots::urdf_robots::PandaPayloadParams::NAMES
        .iter()
        .position(|n| *n == "payload")
        .expect("declared");
    let slope = symbolic
        .parameter_sensitivity(k, &q, &v, &a)
        .expect("a parameter");
    symbolic.params.set("payload", 1.73).expect("known");
    let t3 = symbolic.inverse_dynamics(&q, &v, &a);
    assert!(
        (t3 - t2 - slope).abs().max() < 1e-12,
        "{} vs {slope}",
        t3 - t2
    );
    assert!(
        slope.abs().max() > 0.1,
        "the hand's weight matters: {slope}"
    );
}
