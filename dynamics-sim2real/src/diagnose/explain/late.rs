//! Delayed channels in the report's words: the channel a delay names, and
//! the warnings on a delay the diagnosis names (`candidates/late.rs` finds
//! and offers the delays).

use crate::diagnose::candidates::Candidate;
use crate::diagnose::explain::report::{Explained, Parameter, Ranked, Verdict};
use crate::Warning;

/// The late channel a delay candidate names: `all` (positions and
/// velocities late together against the effort), `positions` or `effort`.
pub fn channel(c: Candidate) -> Option<String> {
    match c {
        Candidate::TimeDelay => Some("all".into()),
        Candidate::LatePositions => Some("positions".into()),
        Candidate::LateEffort(_) => Some("effort".into()),
        _ => None,
    }
}

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
    const KIND: &str = "time_delay";
    let named = effects
        .iter()
        .find(|e| e.kind == KIND)
        .map(|e| (e.channel.as_deref(), &e.parameters))
        .or_else(|| {
            (verdict.kind == KIND)
                .then(|| ranked.first())
                .flatten()
                .map(|r| (r.channel.as_deref(), &r.parameters))
        });
    let Some((channel, parameters)) = named else {
        return;
    };
    let Some(Parameter { value, std, .. }) = parameters.iter().find(|p| p.name == "delay") else {
        return;
    };
    let (delay, std) = (*value, *std);
    match channel {
        Some("effort") => warnings.push(Warning::LateEffort { delay, std }),
        Some("all") if !qd_measured => warnings.push(Warning::LateMotionUnresolved { delay, std }),
        _ => {}
    }
}
