//! The traces behind a report's plots are the fits the diagnosis made: a
//! Coulomb friction with its velocity width, an effect that starts and
//! stops within its window.

use dynamics_sim2real::diagnose::traces::traces;
use dynamics_sim2real::diagnose::{diagnose, Options};
use dynamics_sim2real::effects::{Effect, Window};
use dynamics_sim2real::synth::{synthesize, SynthOptions};

mod common;
use common::Arm2;

/// A wide Coulomb friction: the traces' fit has the width the report
/// names and the level it fitted with it.
#[test]
fn a_wide_coulomb_friction_is_traced_with_its_width() {
    let arm = Arm2::default();
    let truth = [Effect::CoulombFriction {
        joint: 1,
        fc: 0.4,
        vw: 0.15,
    }];
    let o = |seed| SynthOptions::<2> {
        duration: 6.0,
        seed,
        ..Default::default()
    };
    let a = synthesize(&arm, &truth, &o(7)).expect("synthesizes");
    let b = synthesize(&arm, &truth, &o(107)).expect("synthesizes");
    let options = Options::default();
    let r = diagnose(&arm, &a, &b, &options, &|_, _| {}).expect("diagnoses");
    let top = &r.which.ranked[0];
    assert_eq!(top.kind.name(), "coulomb_friction");
    let get = |name: &str| {
        top.parameters
            .iter()
            .find(|p| p.name == name)
            .map(|p| p.value)
            .expect("a parameter")
    };
    let t = traces(&arm, &a, &b, Some(top), &options).expect("traces");
    match t.effect {
        Some(Effect::CoulombFriction { joint: 1, fc, vw }) => {
            assert_eq!(vw, get("vw"));
            assert!(
                (fc - get("fc")).abs() <= 1e-9 * fc.abs(),
                "{fc} {}",
                get("fc")
            );
        }
        other => panic!("{other:?}"),
    }
}

/// An encoder that slips at 2 s: the traces' correction acts only from
/// the window the report gives on, the residual before it left as it is.
#[test]
fn an_effect_that_starts_and_stops_is_traced_within_its_window() {
    let arm = Arm2::default();
    let opts = |seed, window| SynthOptions::<2> {
        duration: 6.0,
        home: [0.0, 0.4].into(),
        amplitude: [0.6, 0.6].into(),
        seed,
        windows: vec![window],
        ..Default::default()
    };
    let slip = Effect::EncoderOffset {
        joint: 1,
        offset: 0.02,
    };
    let at = |start| {
        Some(Window {
            start,
            end: f64::INFINITY,
        })
    };
    let a = synthesize(&arm, &[slip], &opts(11, at(2.0))).expect("synthesizes");
    let b = synthesize(&arm, &[slip], &opts(12, at(3.0))).expect("synthesizes");
    let options = Options::default();
    let r = diagnose(&arm, &a, &b, &options, &|_, _| {}).expect("diagnoses");
    let top = &r.which.ranked[0];
    assert_eq!(top.kind.name(), "encoder_offset");
    let w = r.which.effects[0].window.clone().expect("a window");
    let t = traces(&arm, &a, &b, Some(top), &options).expect("traces");
    assert_eq!(t.window.map(|x| x.start), Some(w.start));
    let before = t
        .train
        .t
        .iter()
        .position(|&s| s >= w.start)
        .expect("inside");
    for j in &t.train.joints {
        assert_eq!(
            j.residual_after[..before],
            j.residual[..before],
            "{}",
            j.joint
        );
        let moved = j.residual_after[before..]
            .iter()
            .zip(&j.residual[before..])
            .any(|(x, y)| x != y);
        assert!(moved || j.joint == "j1", "{}: nothing corrected", j.joint);
    }
}
