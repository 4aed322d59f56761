//! Delayed channels (issue 15): the position stream late against velocity
//! and effort is told from the whole measured motion late against the
//! effort by the kinematic consistency of the positions with the measured
//! velocities; `time_delay` names the channel.

use dynamics_sim2real::diagnose::{diagnose, Options, Report};
use dynamics_sim2real::effects::Effect;
use dynamics_sim2real::synth::{synthesize, Damage, SynthOptions};

mod common;
use common::Arm2;

fn opts(seed: u64, q_late: f64) -> SynthOptions<2> {
    SynthOptions {
        duration: 6.0,
        home: [0.0, 0.4].into(),
        amplitude: [0.6, 0.6].into(),
        seed,
        damage: Damage {
            q_late,
            ..Damage::default()
        },
        ..Default::default()
    }
}

fn diagnosed(effects: &[Effect], q_late: f64) -> Report {
    let arm = Arm2::default();
    let a = synthesize(&arm, effects, &opts(21, q_late)).expect("synthesizes");
    let b = synthesize(&arm, effects, &opts(22, q_late)).expect("synthesizes");
    diagnose(&arm, &a, &b, &Options::default(), &|_, _| {}).expect("diagnoses")
}

fn delay(r: &Report) -> (String, Option<String>, f64) {
    let v = &r.which.verdict;
    let top = &r.which.ranked[0];
    eprintln!(
        "{} {:?}: delay {:.5} s, shrink {:.3}",
        v.kind, v.channel, top.parameters[0].value, r.shrink.fraction
    );
    (v.kind.clone(), v.channel.clone(), top.parameters[0].value)
}

#[test]
fn a_late_position_stream_is_named_as_such() {
    let r = diagnosed(&[], 0.01);
    let (kind, channel, d) = delay(&r);
    assert_eq!(
        (kind.as_str(), channel.as_deref()),
        ("time_delay", Some("positions"))
    );
    assert!((d - 0.01).abs() < 0.002, "delay {d}");
    let e = &r.which.effects[0];
    assert_eq!(e.channel.as_deref(), Some("positions"));
    let said: Vec<String> = r.warnings.iter().map(ToString::to_string).collect();
    assert!(
        said.iter()
            .any(|w| w.starts_with("the positions lag the measured velocities by 10.")),
        "{said:?}"
    );
    assert!(r.shrink.fraction > 0.9, "shrink {}", r.shrink.fraction);
}

#[test]
fn the_whole_motion_late_is_channel_all() {
    let r = diagnosed(&[Effect::TimeDelay { delay: 0.01 }], 0.0);
    let (kind, channel, d) = delay(&r);
    assert_eq!(
        (kind.as_str(), channel.as_deref()),
        ("time_delay", Some("all"))
    );
    assert!((d - 0.01).abs() < 0.002, "delay {d}");
}

#[test]
fn consistent_channels_offer_no_late_positions() {
    // An effect that is not a delay: no channel is named late.
    let r = diagnosed(&[Effect::ViscousFriction { joint: 0, fv: 0.5 }], 0.0);
    assert_eq!(r.which.verdict.kind, "viscous_friction");
    assert!(r
        .which
        .ranked
        .iter()
        .all(|e| e.channel.as_deref() != Some("positions")));
    assert!(r.warnings.is_empty(), "{:?}", r.warnings);
}
