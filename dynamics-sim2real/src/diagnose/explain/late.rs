//! Delayed channels in the report's words: the warnings on a delay the
//! diagnosis names (`candidates/late.rs` finds
//! and offers the delays).

use super::report::{Explained, Parameter, Ranked, Verdict, VerdictKind};
use crate::diagnose::candidates::Channel;
use crate::effects::EffectKind;
use crate::Warning;

/// Warnings on the delay the diagnosis names (in the explanation
/// `effects`, else the verdict's first ranked entry): the effort late
/// (channel `effort`), or, when the velocities were derived from the
/// positions (`qd_measured` false), the motion late (channel `all`), which
/// these data cannot tell from the position stream alone late.
pub fn warn_delays(
    qd_measured: bool,
    effects: &[Explained],
    verdict: &Verdict,
    ranked: &[Ranked],
    warnings: &mut Vec<Warning>,
) {
    const KIND: EffectKind = EffectKind::TimeDelay;
    let named = effects
        .iter()
        .find(|e| e.kind == KIND)
        .map(|e| (e.channel, &e.parameters))
        .or_else(|| {
            (verdict.kind == VerdictKind::Effect(KIND))
                .then(|| ranked.first())
                .flatten()
                .map(|r| (r.channel, &r.parameters))
        });
    let Some((channel, parameters)) = named else {
        return;
    };
    let Some(Parameter { value, std, .. }) = parameters.iter().find(|p| p.name == "delay") else {
        return;
    };
    let (delay, std) = (*value, *std);
    match channel {
        Some(Channel::Effort) => warnings.push(Warning::LateEffort { delay, std }),
        Some(Channel::All) if !qd_measured => {
            warnings.push(Warning::LateMotionUnresolved { delay, std })
        }
        _ => {}
    }
}
