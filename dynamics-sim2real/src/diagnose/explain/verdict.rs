//! The verdict: the top candidate when it wins clearly and carries over to
//! the held-out data (`ambiguous` with a rival close behind), else `none`
//! within noise or `unexplained` when the gap is real.

use super::report::{Ranked, Status, Verdict, VerdictKind};
use crate::diagnose::select::nested_rival_stands;
use crate::diagnose::Options;
use crate::effects::EffectKind;

/// The verdict on `ranked` (best first); `gap` is the largest torque
/// residual RMS over noise of the training data.
pub fn verdict(ranked: &[Ranked], gap: f64, options: &Options) -> Verdict {
    match ranked.first() {
        Some(top)
            if top.delta_aicc >= options.none_margin
                && top.holdout_share > 0.0
                && top.parameters.iter().all(|p| p.note.is_none()) =>
        {
            let rival = ranked
                .iter()
                .skip(1)
                .find(|r| top.aicc - r.aicc > -options.ambiguity_margin && stands(top, r));
            Verdict {
                kind: VerdictKind::Effect(top.kind),
                joint: top.joint.clone(),
                point: top.point.clone(),
                channel: top.channel,
                status: if rival.is_some() {
                    Status::Ambiguous
                } else {
                    Status::Clear
                },
                separating_motion: rival.map(|r| {
                    format!(
                        "{}{}; `dynamics excite --separate report.json` designs such a motion within the robot's limits",
                        separating_motion(top.kind, r.kind),
                        longer(top, r)
                            .map(|f| format!(", on a run about {f:.1} times as long as this one (only more data narrow the breakaway excess's interval)"))
                            .unwrap_or_default()
                    )
                }),
                rival: rival.map(|r| Box::new(r.clone())),
                inseparable: None,
            }
        }
        _ => {
            let (kind, status) = if gap >= options.unexplained_ratio {
                (VerdictKind::Unexplained, Status::Unexplained)
            } else {
                (VerdictKind::Effect(EffectKind::None), Status::WithinNoise)
            };
            Verdict {
                kind,
                joint: None,
                point: None,
                channel: None,
                status,
                rival: None,
                separating_motion: None,
                inseparable: None,
            }
        }
    }
}

/// Whether `rival` leaves `top` ambiguous: at another place always; at
/// the same place, a rival that nests `top` (or is nested by it) only while
/// the data leave the richer one's extra parameter undetermined
/// (`select::nested_rival_stands`).
fn stands(top: &Ranked, rival: &Ranked) -> bool {
    fn tuples(r: &Ranked) -> Vec<(&str, f64, f64)> {
        r.parameters
            .iter()
            .map(|p| (p.name.as_str(), p.value, p.std))
            .collect()
    }
    let (a, b) = (tuples(top), tuples(rival));
    top.joint != rival.joint
        || top.point != rival.point
        || nested_rival_stands((top.kind, &a), (rival.kind, &b))
}

/// For Coulomb against Stribeck friction at one joint, how many times as
/// much data the Stribeck entry says would settle its breakaway excess,
/// when more than these.
fn longer(a: &Ranked, b: &Ranked) -> Option<f64> {
    use EffectKind::{CoulombFriction, StribeckFriction};
    let pair = matches!(
        (a.kind, b.kind),
        (CoulombFriction, StribeckFriction) | (StribeckFriction, CoulombFriction)
    );
    let stribeck = if a.kind == StribeckFriction { a } else { b };
    (pair && a.joint == b.joint)
        .then_some(stribeck.data_needed)
        .flatten()
        .filter(|f| *f > 1.0)
}

/// A motion that would tell `a` and `b` apart.
fn separating_motion(a: EffectKind, b: EffectKind) -> String {
    use EffectKind::*;
    let pair = |x: EffectKind, y: EffectKind| (a == x && b == y) || (a == y && b == x);
    if pair(ViscousFriction, Armature) {
        "decorrelate speed and acceleration: a chirp, or fast cruising at low acceleration followed by hard starts at low speed".into()
    } else if pair(CoulombFriction, EncoderOffset) || pair(PayloadMass, EncoderOffset) {
        "hold still at several poses across the joint's range and reverse the velocity at different positions: gravity's dependence on the angle separates an offset from friction and mass".into()
    } else if pair(EffortOffset, JointSpring) {
        "move the joint across a wider range of positions: a spring's effort grows with the position, an offset's does not".into()
    } else if pair(CoulombFriction, StribeckFriction) {
        "slow velocity reversals (below 0.1 rad/s) where the breakaway level shows".into()
    } else if [a, b]
        .iter()
        .any(|k| matches!(k, JointElasticity | Backlash))
    {
        "quick effort reversals and steps at the joint, so that the motor side rings (elasticity) or crosses its gap (backlash)".into()
    } else {
        "a richer excitation: a chirp up to 5 Hz, slow reversals and holds at several poses".into()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnose::explain::report::Parameter;

    fn entry(kind: EffectKind, aicc: f64, parameters: &[(&str, f64, f64)]) -> Ranked {
        Ranked {
            kind,
            joint: Some("j3".into()),
            point: None,
            parameters: parameters
                .iter()
                .map(|&(name, value, std)| Parameter {
                    name: name.into(),
                    value,
                    std,
                    note: None,
                })
                .collect(),
            share: 0.9,
            aicc,
            delta_aicc: 500.0 - aicc,
            holdout_share: 0.9,
            channel: None,
            data_needed: None,
        }
    }

    #[test]
    fn an_undetermined_breakaway_asks_for_a_longer_run() {
        let coulomb = entry(EffectKind::CoulombFriction, 0.0, &[("fc", 0.0246, 4e-4)]);
        let mut stribeck = entry(
            EffectKind::StribeckFriction,
            2.0,
            &[("fc", 0.0246, 4e-4), ("fs_minus_fc", 0.0, 1.9e-3)],
        );
        // 2 x 1.5 x 1.9e-3 against 10 % of fc: (5.7e-3 / 2.46e-3)^2.
        stribeck.data_needed = crate::diagnose::breakaway_data_needed(0.0246, 0.0, 1.9e-3);
        let v = verdict(
            &[coulomb.clone(), stribeck.clone()],
            10.0,
            &Options::default(),
        );
        assert_eq!(v.status, Status::Ambiguous);
        let words = v.separating_motion.unwrap();
        assert!(words.contains("5.4 times as long"), "{words}");
        // Settled by these data (a tight interval): no rival, no words.
        let tight = entry(
            EffectKind::StribeckFriction,
            2.0,
            &[("fc", 0.0246, 4e-4), ("fs_minus_fc", 0.0, 2e-4)],
        );
        let v = verdict(&[coulomb, tight], 10.0, &Options::default());
        assert_eq!(v.status, Status::Clear);
    }
}
