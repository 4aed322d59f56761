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
                separating_motion: rival.map(|r| format!("{}; `dynamics excite --separate report.json` designs such a motion within the robot's limits", separating_motion(top.kind, r.kind))),
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
