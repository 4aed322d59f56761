//! Values a user can act on, in the report: a parameter the data do not
//! determine, or one outside what its kind can physically be
//! (`evaluate/determinacy.rs`), is reported as the reason rather than as a
//! number ([`Parameter::note`](super::report::Parameter::note)); a ranked
//! candidate with such a parameter is ranked after every candidate whose
//! values stand.

use super::report::{Explained, Ranked, Suggested};
use crate::diagnose::evaluate::why_not;
use dynamics_runtime::JointKind;

/// Notes on every parameter of `ranked` that cannot be acted on, and those
/// candidates moved after the others (the order otherwise kept). `joint`
/// gives a joint's kind and range of motion by name.
pub fn mark_ranked(ranked: &mut Vec<Ranked>, joint: &dyn Fn(&str) -> Option<(JointKind, f64)>) {
    for r in ranked.iter_mut() {
        let at = r.joint.as_deref().and_then(joint);
        for p in r.parameters.iter_mut() {
            p.note = why_not(r.kind, &p.name, p.value, p.std, at);
        }
    }
    let (mut good, bad): (Vec<Ranked>, Vec<Ranked>) = ranked
        .drain(..)
        .partition(|r| r.parameters.iter().all(|p| p.note.is_none()));
    good.extend(bad);
    *ranked = good;
}

/// Notes on every parameter of the explanation's `effects` that cannot be
/// acted on (`joint` as for [`mark_ranked`]).
pub fn mark_explained(effects: &mut [Explained], joint: &dyn Fn(&str) -> Option<(JointKind, f64)>) {
    for e in effects.iter_mut() {
        let at = e.joint.as_deref().and_then(joint);
        for p in e.parameters.iter_mut().filter(|p| p.note.is_none()) {
            p.note = why_not(e.kind, &p.name, p.value, p.std, at);
        }
    }
}

/// Notes on every parameter of the `suggested` effects that cannot be
/// acted on (`joint` as for [`mark_ranked`]).
pub fn mark_suggested(
    suggested: &mut [Suggested],
    joint: &dyn Fn(&str) -> Option<(JointKind, f64)>,
) {
    for e in suggested.iter_mut() {
        let at = e.joint.as_deref().and_then(joint);
        for p in e.parameters.iter_mut() {
            p.note = why_not(e.kind, &p.name, p.value, p.std, at);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnose::explain::report::Parameter;
    use crate::effects::EffectKind;

    fn p(name: &str, value: f64, std: f64) -> Parameter {
        Parameter {
            name: name.into(),
            value,
            std,
            note: None,
        }
    }

    #[test]
    fn undetermined_candidates_go_to_the_end_of_the_ranking() {
        let entry = |kind, value: f64| Ranked {
            kind,
            joint: Some("j1".into()),
            point: None,
            parameters: vec![p("offset", value, 0.01)],
            share: 0.5,
            aicc: 0.0,
            delta_aicc: 1.0,
            holdout_share: 0.5,
            channel: None,
            data_needed: None,
        };
        let mut ranked = vec![
            entry(EffectKind::EncoderOffset, 7.8e15),
            entry(EffectKind::EffortOffset, 0.3),
        ];
        mark_ranked(&mut ranked, &|_| Some((JointKind::Revolute, 0.02)));
        assert_eq!(ranked[0].kind, EffectKind::EffortOffset);
        assert!(ranked[1].parameters[0].note.is_some());
    }
}
