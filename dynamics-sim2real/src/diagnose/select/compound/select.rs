//! The selection of the compound explanation: forward moves (add a term,
//! or swap one for another of its family) by the information criterion
//! of the joint fit, each checked by block cross-validation, then the
//! backward pass; parsimony between a richer term and the simpler one it
//! nests; the selection resumed under feasible weights.

use super::validate::Folds;
use super::weights::{weights, within_noise, REWEIGHTS};
use crate::diagnose::numeric::aicc;
use crate::diagnose::select::criterion::tie_key;
use crate::diagnose::select::nesting::{nesting, simpler};
use crate::diagnose::select::pool::{Pool, Solution};
use crate::diagnose::Options;

pub(super) fn crit(pool: &Pool, s: &Solution) -> f64 {
    aicc(s.sse, pool.n(), s.k)
}

/// The criterion of `set` from its residual computed row by row.
pub(super) fn explicit_crit(pool: &Pool, set: &[usize]) -> f64 {
    let sol = pool.solve(set);
    aicc(pool.residual(set, &sol).norm_squared(), pool.n(), sol.k)
}

/// Moves tried, best first by the criterion, for one that also passes the
/// cross-validation.
const CV_TRIES: usize = 4;

/// Parsimony: an added richer term gives way to the simpler nested term at
/// its place when it does not beat it clearly (`adds`: the criterion of
/// every single addition).
fn parsimony(
    pool: &Pool,
    set: &[usize],
    adds: &[(usize, f64)],
    (c, trial, t): (f64, Vec<usize>, usize),
    cur: f64,
    options: &Options,
) -> (f64, Vec<usize>) {
    let cand = pool.terms[t].fit.candidate;
    if let (Some(is_simpler), true) = (simpler(cand), trial.len() > set.len()) {
        let alt = adds
            .iter()
            .filter(|(u, _)| {
                let cu = pool.terms[*u].fit.candidate;
                is_simpler(&cu) && cu.joint() == cand.joint()
            })
            .min_by_key(|a| (tie_key(a.1), a.0));
        if let Some(&(u, cu)) = alt {
            if cu - c < nesting(cand, options)
                && cur - cu >= options.add_margin.min(options.none_margin)
            {
                let mut s = set.to_vec();
                s.push(u);
                return (cu, s);
            }
        }
    }
    (c, trial)
}

/// Forward selection from `set`, then the backward pass.
pub(super) fn select<const N: usize>(
    pool: &Pool,
    set: Vec<usize>,
    options: &Options,
) -> Vec<usize> {
    select_except::<N>(pool, set, options, &[])
}

/// [`select`] with the terms `banned` never added.
pub(super) fn select_except<const N: usize>(
    pool: &Pool,
    mut set: Vec<usize>,
    options: &Options,
    banned: &[usize],
) -> Vec<usize> {
    let folds = Folds::new(pool, N);
    let mut cur = crit(pool, &pool.solve(&set));
    for _ in 0..(6 * N + 12) {
        let sol = pool.solve(&set);
        if !set.is_empty() && within_noise(pool, &set, &sol, options.floor_ratio) {
            break;
        }
        // Every move that earns its margin: (criterion, new set, added term).
        let mut moves: Vec<(f64, Vec<usize>, usize)> = Vec::new();
        let mut adds: Vec<(usize, f64)> = Vec::new();
        for t in 0..pool.terms.len() {
            if set.contains(&t) || banned.contains(&t) {
                continue;
            }
            let fam = pool.terms[t].family();
            let (trial, need) = match set.iter().position(|&u| pool.terms[u].family() == fam) {
                Some(i) => {
                    let mut s = set.clone();
                    s[i] = t;
                    (s, nesting(pool.terms[t].fit.candidate, options))
                }
                // A wider Coulomb law comes in only in place of the sharp
                // one: added first, it takes viscous friction's place.
                None if pool.terms[t].fit.candidate.widened() => continue,
                None => {
                    let mut s = set.clone();
                    s.push(t);
                    let need = if set.is_empty() {
                        options.none_margin
                    } else {
                        options.add_margin
                    };
                    (s, need)
                }
            };
            let c = crit(pool, &pool.solve(&trial));
            if !c.is_finite() {
                continue;
            }
            if trial.len() > set.len() {
                adds.push((t, c));
            }
            if cur - c >= need {
                moves.push((c, trial, t));
            }
        }
        moves.sort_by_key(|a| (tie_key(a.0), a.2));
        // The best move (by the criterion) that also predicts blocks of the
        // data it was not fitted on better than the set before it.
        let cv_now = folds.as_ref().map(|f| f.deviance(pool, &set));
        let mut chosen = None;
        for (c, trial, t) in moves.into_iter().take(CV_TRIES) {
            let (c, trial) = parsimony(pool, &set, &adds, (c, trial, t), cur, options);
            let need = if trial.len() > set.len() {
                options.cv_margin
            } else {
                0.0
            };
            let ok = match (&folds, cv_now) {
                (Some(f), Some(now)) => now - f.deviance(pool, &trial) >= need,
                _ => true,
            };
            if ok {
                chosen = Some((c, trial));
                break;
            }
        }
        let Some((c, trial)) = chosen else {
            break;
        };
        set = trial;
        cur = c;
    }
    // Backward: drop what costs less than its margin, or does not predict
    // the blocks it was not fitted on.
    loop {
        let full = crit(pool, &pool.solve(&set));
        let cv_full = folds.as_ref().map(|f| f.deviance(pool, &set));
        let need = if set.len() == 1 {
            options.none_margin
        } else {
            options.add_margin
        };
        let weakest = (0..set.len())
            .map(|i| {
                let mut s = set.clone();
                s.remove(i);
                let cost = crit(pool, &pool.solve(&s)) - full;
                let cv_cost = match (&folds, cv_full) {
                    (Some(f), Some(c)) => f.deviance(pool, &s) - c,
                    _ => f64::INFINITY,
                };
                // Failing either test, the smaller shortfall first.
                let short = (cost - need).min(cv_cost - options.cv_margin);
                (i, short)
            })
            .min_by_key(|a| (tie_key(a.1), a.0));
        match weakest {
            Some((i, short)) => {
                if short < 0.0 {
                    set.remove(i);
                } else {
                    break;
                }
            }
            None => break,
        }
    }
    set
}

/// Feasible weighting from `set` (`weights.rs`): the selection resumes
/// under the new weights until they settle.
pub(super) fn reweighted<const N: usize>(
    pool: &mut Pool,
    mut set: Vec<usize>,
    options: &Options,
) -> Vec<usize> {
    for _ in 0..REWEIGHTS {
        let Some(w) = weights(pool, &set) else {
            break;
        };
        pool.reweight(&w);
        set = select::<N>(pool, set, options);
    }
    set
}
