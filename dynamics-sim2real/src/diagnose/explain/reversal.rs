//! A joint whose velocity never reverses: there a Coulomb friction is a
//! constant effort of one sign, and an effort offset fits it as well (up to
//! where the speed nears zero). Both stay candidates and the better fit is
//! named, but never alone: the verdict is `ambiguous` with the other as
//! its rival, and an explanation's entry carries it as `ambiguous_with`
//! ("Coulomb friction or an effort offset; these data cannot tell them
//! apart").

use super::report::{Explained, Ranked, Rival, Status, Verdict};
use crate::diagnose::candidates::Excitation;
use crate::effects::EffectKind;

const PAIR: [EffectKind; 2] = [EffectKind::CoulombFriction, EffectKind::EffortOffset];

/// The other of the pair, for `kind` at a joint that never reverses.
fn other(
    kind: Option<EffectKind>,
    joint: Option<&str>,
    names: &[&str],
    ex: &Excitation,
) -> Option<EffectKind> {
    let kind = kind?;
    let j = names.iter().position(|n| Some(*n) == joint)?;
    if !ex.moves[j] || ex.reverses[j] {
        return None;
    }
    match PAIR.iter().position(|k| *k == kind)? {
        0 => Some(PAIR[1]),
        _ => Some(PAIR[0]),
    }
}

/// Marks the verdict and the explanation's entries that name one of the
/// pair at a joint whose velocity never reverses.
pub fn mark_reversals(
    verdict: &mut Verdict,
    effects: &mut [Explained],
    ranked: &[Ranked],
    names: &[&str],
    ex: &Excitation,
) {
    if let Some(o) = other(verdict.effect(), verdict.joint.as_deref(), names, ex) {
        let rival = ranked
            .iter()
            .find(|r| r.kind == o && r.joint == verdict.joint);
        if let Some(r) = rival {
            verdict.status = Status::Ambiguous;
            verdict.rival = Some(Box::new(r.clone()));
            verdict.separating_motion = Some(format!(
                "reverse joint {}'s velocity (slowly, under load): Coulomb friction changes sign with it, an effort offset does not; `dynamics excite --separate report.json` designs such a motion within the robot's limits",
                verdict.joint.as_deref().unwrap_or("?")
            ));
        }
    }
    for e in effects.iter_mut() {
        if e.ambiguous_with.is_some() {
            continue;
        }
        if let Some(o) = other(Some(e.kind), e.joint.as_deref(), names, ex) {
            e.ambiguous_with = Some(Rival {
                kind: o,
                joint: e.joint.clone(),
                point: None,
                inseparable: None,
            });
        }
    }
}
