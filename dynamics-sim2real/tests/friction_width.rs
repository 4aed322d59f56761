//! Coulomb friction that turns over a tenth of a rad/s, as real joints'
//! does: the diagnosis names it with the width drawn, and the sharp one
//! with the sharp width.

use dynamics_sim2real::diagnose::{diagnose, Options};
use dynamics_sim2real::effects::{Effect, SIGN_SMOOTHING};
use dynamics_sim2real::synth::{synthesize, SynthOptions};

mod common;
use common::Arm2;

fn named_width(vw: f64) -> (String, Option<f64>, Option<f64>) {
    let arm = Arm2::default();
    let truth = [Effect::CoulombFriction {
        joint: 1,
        fc: 0.4,
        vw,
    }];
    let o = |seed| SynthOptions::<2> {
        duration: 6.0,
        seed,
        ..Default::default()
    };
    let a = synthesize(&arm, &truth, &o(7)).expect("synthesizes");
    let b = synthesize(&arm, &truth, &o(107)).expect("synthesizes");
    let r = diagnose(&arm, &a, &b, &Options::default(), &|_, _| {}).expect("diagnoses");
    let v = &r.which.verdict;
    let e = r
        .which
        .effects
        .iter()
        .find(|e| e.kind.name() == "coulomb_friction" && e.joint.as_deref() == Some("j2"));
    let get = |name: &str| {
        e.and_then(|e| e.parameters.iter().find(|p| p.name == name))
            .map(|p| p.value)
    };
    (format!("{} {:?}", v.kind, v.joint), get("fc"), get("vw"))
}

#[test]
fn a_wide_coulomb_friction_is_named_with_its_width() {
    let (verdict, fc, vw) = named_width(0.15);
    assert_eq!(verdict, "coulomb_friction Some(\"j2\")");
    assert_eq!(vw, Some(0.15), "{fc:?}");
    assert!(fc.is_some_and(|f| (f - 0.4).abs() < 0.04), "{fc:?}");
}

#[test]
fn a_sharp_coulomb_friction_is_named_sharp() {
    let (verdict, fc, vw) = named_width(SIGN_SMOOTHING);
    assert_eq!(verdict, "coulomb_friction Some(\"j2\")");
    assert_eq!(vw, Some(SIGN_SMOOTHING), "{fc:?}");
    assert!(fc.is_some_and(|f| (f - 0.4).abs() < 0.04), "{fc:?}");
}
