//! Tests of [`Calibrated`]: a folded-in payload against the same mass
//! written into the model, friction and rotor inertia against the plant,
//! refusals by name.

use super::*;
use dynamics_runtime::Parameters;
use nalgebra::Vector3 as V3;

dynamics_macros::robot! {
    pub robot Arm;
    gravity = [0.0, 0.0, -9.81];
    param load = 0.0;
    link base;
    link a { mass = 2.0; com = [0.0, 0.0, 0.2]; inertia = [0.02, 0.02, 0.01]; }
    link b { mass = 1.0; com = [0.2, 0.0, 0.0]; inertia = [0.005, 0.01, 0.01]; }
    link c {
        mass = 0.5; com = [0.15, 0.0, 0.0]; inertia = [0.002, 0.004, 0.004];
        point_mass tool = load at [0.3, 0.0, 0.0];
    }
    joint j1 = revolute(base -> a) { transfer = [rot_z(q)]; }
    joint j2 = revolute(a -> b) { transfer = [trans_z(0.4), rot_y(q)]; }
    joint j3 = revolute(b -> c) { transfer = [trans_x(0.4), rot_y(q)]; }
}

/// A payload folded in equals the same mass written into the model
/// (`point_mass` at the tip, derived symbolically): every quantity.
#[test]
fn a_payload_folded_in_matches_the_model_with_the_mass_written_in() {
    let mut truth = Arm::default();
    truth.params_mut().set("load", 1.7).expect("param");
    let folded = Calibrated::new(
        Arm::default(),
        vec![Effect::PayloadMass {
            mass: 1.7,
            com: [0.0; 3],
        }],
    )
    .expect("nominal");
    assert_eq!(Tip::of::<Arm, 3>().name::<Arm, 3>(), "tool");
    let q = V3::new(0.3, -0.7, 1.1);
    let qd = V3::new(0.8, -1.2, 0.5);
    let qdd = V3::new(-0.4, 2.0, 1.5);
    // The tip's velocity terms come from a central difference of its
    // Jacobian (1e-6 relative), K and D from one more (1e-5).
    let near = |a: f64, b: f64, tol: f64, what: &str| {
        assert!((a - b).abs() <= tol * (1.0 + b.abs()), "{what}: {a} vs {b}")
    };
    let close = |a: f64, b: f64, what: &str| near(a, b, 1e-6, what);
    let id = (
        folded.inverse_dynamics(&q, &qd, &qdd),
        truth.inverse_dynamics(&q, &qd, &qdd),
    );
    let m = (folded.mass_matrix(&q), truth.mass_matrix(&q));
    let g = (folded.gravity(&q), truth.gravity(&q));
    let cv = (
        folded.coriolis_matrix(&q, &qd) * qd,
        truth.coriolis_matrix(&q, &qd) * qd,
    );
    let nle = (
        folded.nonlinear_effects(&q, &qd),
        truth.nonlinear_effects(&q, &qd),
    );
    let pj = (
        folded.perturbation_jacobians(&q, &qd, &qdd),
        truth.perturbation_jacobians(&q, &qd, &qdd),
    );
    for i in 0..3 {
        close(id.0[i], id.1[i], "tau");
        close(g.0[i], g.1[i], "g");
        close(cv.0[i], cv.1[i], "C qd");
        close(nle.0[i], nle.1[i], "nle");
        for j in 0..3 {
            close(m.0[(i, j)], m.1[(i, j)], "M");
            near(pj.0.k[(i, j)], pj.1.k[(i, j)], 1e-5, "K");
            near(pj.0.d[(i, j)], pj.1.d[(i, j)], 1e-5, "D");
        }
    }
    close(
        folded.kinetic_energy(&q, &qd),
        truth.kinetic_energy(&q, &qd),
        "T",
    );
    close(folded.potential_energy(&q), truth.potential_energy(&q), "V");
}

/// Friction and rotor inertia enter the residual as the plant adds them.
#[test]
fn friction_and_armature_add_what_the_plant_adds() {
    let effects = vec![
        Effect::coulomb(0, 0.4),
        Effect::ViscousFriction { joint: 1, fv: 0.3 },
        Effect::Armature {
            joint: 2,
            inertia: 0.05,
        },
    ];
    let r = Calibrated::new(Arm::default(), effects.clone()).expect("nominal");
    let plant = crate::effects::Plant::new(Arm::default(), effects).expect("plant");
    let (q, qd, qdd) = (
        V3::new(0.1, 0.2, 0.3),
        V3::new(1.0, -2.0, 0.5),
        V3::new(0.3, 0.1, -0.2),
    );
    let (a, f) = plant.mass_and_forces(&q, &qd);
    assert!((r.inverse_dynamics(&q, &qd, &qdd) - (a * qdd - f)).norm() < 1e-12);
    let fwd = r
        .forward_dynamics(&q, &qd, &V3::new(1.0, 2.0, 3.0))
        .expect("fwd");
    assert!((r.inverse_dynamics(&q, &qd, &fwd) - V3::new(1.0, 2.0, 3.0)).norm() < 1e-10);
}

/// The joints' friction of a calibrated model is the friction folded in,
/// not the environment's resistance at the tip, which grows with the
/// tip's speed like a viscous law of degree alpha: read at a thousand
/// rad/s it was taken for a viscous coefficient of hundreds.
#[test]
fn a_resistance_at_the_tip_is_not_joint_friction() {
    let resist = Effect::EnvironmentResistance {
        mu: 0.5,
        alpha: 1.5,
    };
    let viscous = Effect::ViscousFriction { joint: 1, fv: 0.3 };
    let r = Calibrated::new(
        Arm::default(),
        vec![resist, viscous, Effect::coulomb(2, 0.2)],
    )
    .expect("nominal");
    let q = V3::new(0.1, 0.6, -0.4);
    let (coulomb, fv) = crate::effects::nominal_friction(&r, &q);
    assert!((fv - V3::new(0.0, 0.3, 0.0)).norm() < 1e-9, "{fv}");
    assert!(
        (coulomb - V3::new(0.0, 0.0, 0.2)).norm() < 1e-6,
        "{coulomb}"
    );
    // The resistance is still in the forces: the tip moves at j1.
    let qd = V3::new(2.0, 0.0, 0.0);
    let all = r.generalized_forces(&q, &qd) - r.generalized_forces(&q, &V3::zeros());
    assert!((all - r.joint_friction(&q, &qd)).norm() > 0.1);
}

#[test]
fn motor_sides_and_sensor_effects_are_kept_apart() {
    let elastic = Effect::JointElasticity {
        joint: 0,
        stiffness: 100.0,
        damping: 1.0,
        motor_inertia: 0.01,
    };
    let r = Calibrated::new(Arm::default(), vec![elastic]).expect("taken");
    assert_eq!(r.motor_effects(), &[elastic]);
    assert!(r.effects().is_empty() && !r.model_only());
    // A motor side's state carries over a window's edges.
    let held = Window {
        start: 1.0,
        end: 2.0,
    };
    let e = Calibrated::timed(Arm::default(), vec![(elastic, Some(held))]);
    assert!(matches!(e, Err(CalibratedError::NotWindowed { .. })));
    let late = Effect::TimeDelay { delay: 0.01 };
    let scale = Effect::EffortScale {
        joint: 1,
        scale: 2.0,
    };
    let friction = Effect::ViscousFriction { joint: 1, fv: 0.6 };
    let r = Calibrated::new(Arm::default(), vec![late, scale, friction]).expect("taken");
    assert_eq!(r.sensor_effects(), &[late, scale]);
    // The scaled joint's own friction, fitted in measured units, in applied ones.
    assert_eq!(
        r.effects(),
        &[Effect::ViscousFriction { joint: 1, fv: 0.3 }]
    );
    let e = Calibrated::new(
        Arm::default(),
        vec![Effect::Armature {
            joint: 5,
            inertia: 0.1,
        }],
    );
    assert!(matches!(
        e,
        Err(CalibratedError::Joint { joint: 5, n: 3, .. })
    ));
}
