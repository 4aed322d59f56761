//! Exchange: an effect that stands in for several. Forward selection adds
//! the single term that gains most, so one effect whose columns lie near
//! the sum of several others' (a resistance at the tip, a damping on the
//! arm's Cartesian motion, where the joints have viscous friction each)
//! comes in first, and then none of the terms it stands in for earns its
//! margin alone. Here each chosen effect other than joint friction is
//! taken out and the selection resumed without it, adding joint friction
//! only (what it may stand in for; an open selection would let other
//! broad terms, a link correction, take its place instead); the set found
//! so replaces the chosen one when both its criterion (on the residual
//! computed row by row) and its cross-validated deviance are lower: the
//! same criterion, a better optimum of it.

use super::select::{explicit_crit, select_except};
use super::validate::Folds;
use crate::diagnose::select::pool::Pool;
use crate::diagnose::Options;
use crate::effects::EffectKind;

/// Whether term `t` is friction at a joint (never exchanged: it is what the
/// others stand in for).
fn friction(pool: &Pool, t: usize) -> bool {
    matches!(
        pool.terms[t].fit.candidate.kind(),
        EffectKind::CoulombFriction | EffectKind::ViscousFriction | EffectKind::StribeckFriction
    )
}

/// `set` with each effect other than joint friction exchanged, in turn,
/// for the joint friction the selection adds without it, where that is
/// better by the criterion and by cross-validation.
pub(super) fn exchange<const N: usize>(
    pool: &Pool,
    mut set: Vec<usize>,
    options: &Options,
) -> Vec<usize> {
    let folds = Folds::new(pool, N);
    let cv = |s: &[usize]| folds.as_ref().map_or(0.0, |f| f.deviance(pool, s));
    let mut tried: Vec<usize> = Vec::new();
    while let Some(&t) = set
        .iter()
        .find(|&&t| !friction(pool, t) && !tried.contains(&t))
    {
        tried.push(t);
        let rest: Vec<usize> = set.iter().copied().filter(|&u| u != t).collect();
        let banned: Vec<usize> = (0..pool.terms.len())
            .filter(|&u| u == t || (!friction(pool, u) && !rest.contains(&u)))
            .collect();
        let other = select_except::<N>(pool, rest, options, &banned);
        if explicit_crit(pool, &other) < explicit_crit(pool, &set) && cv(&other) < cv(&set) {
            set = other;
        }
    }
    set
}
