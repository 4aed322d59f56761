//! Records that hold too little: a robot that holds still, a joint that
//! does not move, a rate too slow for the fast signatures.

use dynamics_sim2real::effects::Effect;
use dynamics_sim2real::synth::{synthesize, Damage};

use crate::common::Arm2;
use crate::{diagnosed, log, messages, opts, text};

/// A record where the robot holds still (the effort its weight needs).
fn still(seed: u64) -> String {
    let arm = Arm2::default();
    let mut o = opts(seed, 1000.0, Damage::default());
    o.amplitude = [0.0, 0.0].into();
    text(&synthesize(&arm, &[Effect::coulomb(0, 0.5)], &o).expect("synthesizes"))
}

#[test]
fn a_record_where_nothing_moves_is_a_clear_error() {
    let e = diagnosed(&still(13), &still(14)).unwrap_err();
    assert_eq!(
        e.to_string(),
        "training data: no joint moves; nothing about the robot can be identified from them"
    );
}

#[test]
fn a_joint_that_does_not_move_gets_no_candidate() {
    // Joint j1 still, joint j2 moving: j1 is named as not moving.
    let arm = Arm2::default();
    let mut o = opts(15, 1000.0, Damage::default());
    o.amplitude = [0.0, 0.6].into();
    let a = text(&synthesize(&arm, &[], &o).expect("synthesizes"));
    o.seed = 16;
    let b = text(&synthesize(&arm, &[], &o).expect("synthesizes"));
    let r = diagnosed(&a, &b).expect("diagnoses");
    let said = messages(&r.warnings);
    assert!(
        said.iter()
            .any(|s| s.starts_with("joint j1: does not move (peak speed")),
        "{said:?}"
    );
    assert!(r
        .which
        .ranked
        .iter()
        .all(|c| c.joint.as_deref() != Some("j1")));
    assert!(!r.which.verdict.names_effect(), "{:?}", r.which.verdict);
}

#[test]
fn at_100_hz_fast_signatures_are_not_guessed() {
    let a = log(&[], 100.0, Damage::default(), 17);
    let b = log(&[], 100.0, Damage::default(), 18);
    let r = diagnosed(&a, &b).expect("diagnoses");
    let said = messages(&r.warnings);
    assert_eq!(
        said,
        vec![
            "`backlash` (signatures up to 40 Hz) is not identifiable above 25 Hz on these data (sampled at 100 Hz; a signature needs four samples a period): searched only below, not guessed",
            "`joint_elasticity` (signatures up to 45 Hz) is not identifiable above 25 Hz on these data (sampled at 100 Hz; a signature needs four samples a period): searched only below, not guessed",
        ]
    );
    assert!(r.which.ranked.iter().all(|c| c.kind.name() != "backlash"));
    assert_eq!(r.which.verdict.kind.name(), "none");
}
