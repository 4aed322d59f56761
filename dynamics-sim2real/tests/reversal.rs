//! A joint whose velocity never reverses (issue 15's unexcited data): a
//! Coulomb friction there is named, but as ambiguous with an effort offset
//! ("these data cannot tell them apart"), never as `unexplained`.

use dynamics_sim2real::diagnose::{diagnose, Options};
use dynamics_sim2real::effects::Effect;
use dynamics_sim2real::synth::{synthesize, SynthOptions};
use dynamics_sim2real::Warning;

mod common;
use common::Arm2;

#[test]
fn coulomb_friction_where_the_velocity_never_reverses_is_ambiguous_with_an_offset() {
    let arm = Arm2::default();
    let fc = [Effect::coulomb(1, 0.3)];
    let o = SynthOptions::<2> {
        duration: 1.0,
        home: [0.0, 0.4].into(),
        amplitude: [0.6, 0.6].into(),
        seed: 1,
        ..Default::default()
    };
    // One second of training data, in which j2 only moves one way.
    let a = synthesize(&arm, &fc, &o).expect("synthesizes");
    let b = synthesize(
        &arm,
        &fc,
        &SynthOptions {
            seed: 101,
            duration: 2.0,
            ..o.clone()
        },
    )
    .expect("synthesizes");
    let r = diagnose(&arm, &a, &b, &Options::default(), &|_, _| {}).expect("diagnoses");
    assert!(r
        .warnings
        .iter()
        .any(|w| *w == Warning::NoReversal { joint: "j2".into() }));
    let v = &r.which.verdict;
    assert_eq!(
        (v.kind.name(), v.joint.as_deref(), v.status.name()),
        ("coulomb_friction", Some("j2"), "ambiguous"),
        "{v:?}"
    );
    let rival = v.rival.as_ref().expect("a rival");
    assert_eq!(
        (rival.kind.name(), rival.joint.as_deref()),
        ("effort_offset", Some("j2"))
    );
    assert!(v
        .separating_motion
        .as_deref()
        .is_some_and(|m| m.starts_with("reverse joint j2's velocity")));
    let e = r
        .which
        .effects
        .iter()
        .find(|e| e.kind.name() == "coulomb_friction")
        .expect("in the explanation");
    let with = e.ambiguous_with.as_ref().expect("ambiguous");
    assert_eq!(
        (with.kind.name(), with.joint.as_deref()),
        ("effort_offset", Some("j2"))
    );
}
