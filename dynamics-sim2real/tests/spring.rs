//! A spring at a joint (a cable harness, a hose, a compensator's spring):
//! the joint feels `-(k q + preload)`. The data come from the arm with a
//! spring of 0.6 N m/rad at j2, at rest at q2 = 0.25 rad; the diagnosis
//! names it at j2 with the stiffness and preload it was drawn with, and
//! the calibrated model folds it in.

use dynamics_runtime::Robot;
use dynamics_sim2real::diagnose::{diagnose, Options};
use dynamics_sim2real::effects::{Calibrated, Effect};
use dynamics_sim2real::synth::synthesize;
use nalgebra::Vector2;

mod common;
use common::{synth_options, Arm2};

const STIFFNESS: f64 = 0.6;
const REST: f64 = 0.25;

fn spring() -> Effect {
    Effect::JointSpring {
        joint: 1,
        stiffness: STIFFNESS,
        preload: -STIFFNESS * REST,
    }
}

#[test]
fn a_spring_at_a_joint_is_named_with_its_stiffness_and_rest() {
    let arm = Arm2::default();
    let a = synthesize(&arm, &[spring()], &synth_options(6.0, 7)).expect("synthesizes");
    let b = synthesize(&arm, &[spring()], &synth_options(6.0, 107)).expect("synthesizes");
    let r = diagnose(&arm, &a, &b, &Options::default(), &|_, _| {}).expect("diagnoses");
    assert_eq!(
        r.which.verdict.kind.name(),
        "joint_spring",
        "{:#?}",
        r.which.ranked
    );
    assert_eq!(r.which.verdict.joint.as_deref(), Some("j2"));
    let e = r
        .which
        .effects
        .iter()
        .find(|e| e.kind.name() == "joint_spring")
        .unwrap_or_else(|| panic!("{:#?}", r.which.effects));
    assert_eq!(e.joint.as_deref(), Some("j2"));
    let get = |n: &str| e.parameters.iter().find(|p| p.name == n).map(|p| p.value);
    let (k, p) = (
        get("stiffness").unwrap_or(0.0),
        get("preload").unwrap_or(0.0),
    );
    assert!(
        (k - STIFFNESS).abs() < 0.05 * STIFFNESS,
        "{:?}",
        e.parameters
    );
    assert!((-p / k - REST).abs() < 0.05, "{:?}", e.parameters);
    assert!(r.shrink.fraction > 0.9, "{:?}", r.shrink);
}

/// The calibrated model holds the spring: at rest its effort at j2 is the
/// nominal one plus `k (q2 - rest)` (by hand).
#[test]
fn the_calibrated_model_folds_the_spring_in() {
    let arm = Arm2::default();
    let calibrated = Calibrated::new(arm, vec![spring()]).expect("a plant effect");
    let q = Vector2::new(0.3, -0.4);
    let z = Vector2::zeros();
    let extra = calibrated.inverse_dynamics(&q, &z, &z) - arm.inverse_dynamics(&q, &z, &z);
    assert!(extra[0].abs() < 1e-12, "{extra}");
    assert!(
        (extra[1] - STIFFNESS * (-0.4 - REST)).abs() < 1e-12,
        "{extra}"
    );
}
