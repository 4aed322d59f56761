//! The verdict: the top candidate when it wins clearly and carries over to
//! the held-out data (`ambiguous` with a rival close behind), else `none`
//! within noise or `unexplained` when the gap is real.

use crate::diagnose::explain::report::{Ranked, Verdict};
use crate::diagnose::Options;

/// The verdict on `ranked` (best first); `gap` is the largest torque
/// residual RMS over noise of the training data.
pub fn verdict(ranked: &[Ranked], gap: f64, options: &Options) -> Verdict {
    match ranked.first() {
        Some(top) if top.delta_aicc >= options.none_margin && top.holdout_share > 0.0 => {
            let rival = ranked
                .iter()
                .skip(1)
                .find(|r| top.aicc - r.aicc > -options.ambiguity_margin);
            Verdict {
                kind: top.kind.clone(),
                joint: top.joint.clone(),
                point: top.point.clone(),
                channel: top.channel.clone(),
                status: if rival.is_some() {
                    "ambiguous"
                } else {
                    "clear"
                }
                .into(),
                separating_motion: rival.map(|r| separating_motion(&top.kind, &r.kind)),
                rival: rival.map(|r| Box::new(r.clone())),
            }
        }
        _ => {
            let word = if gap >= options.unexplained_ratio {
                "unexplained"
            } else {
                "none"
            };
            Verdict {
                kind: word.into(),
                joint: None,
                point: None,
                channel: None,
                status: if word == "none" { "within_noise" } else { word }.into(),
                rival: None,
                separating_motion: None,
            }
        }
    }
}

/// A motion that would tell `a` and `b` apart.
fn separating_motion(a: &str, b: &str) -> String {
    let pair = |x: &str, y: &str| (a == x && b == y) || (a == y && b == x);
    if pair("viscous_friction", "armature") {
        "decorrelate speed and acceleration: a chirp, or fast cruising at low acceleration followed by hard starts at low speed".into()
    } else if pair("coulomb_friction", "encoder_offset") || pair("payload_mass", "encoder_offset") {
        "hold still at several poses across the joint's range and reverse the velocity at different positions: gravity's dependence on the angle separates an offset from friction and mass".into()
    } else if pair("effort_offset", "joint_spring") {
        "move the joint across a wider range of positions: a spring's effort grows with the position, an offset's does not".into()
    } else if pair("coulomb_friction", "stribeck_friction") {
        "slow velocity reversals (below 0.1 rad/s) where the breakaway level shows".into()
    } else if a == "joint_elasticity"
        || b == "joint_elasticity"
        || a == "backlash"
        || b == "backlash"
    {
        "quick effort reversals and steps at the joint, so that the motor side rings (elasticity) or crosses its gap (backlash)".into()
    } else {
        "a richer excitation: a chirp up to 5 Hz, slow reversals and holds at several poses".into()
    }
}
