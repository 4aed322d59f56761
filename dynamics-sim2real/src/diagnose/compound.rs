//! The compound explanation: the set of effects that together explain the
//! gap, chosen over every term of the pool (every candidate of the
//! vocabulary on every joint).
//!
//! Forward selection: each step makes the move that most lowers the
//! corrected information criterion of the JOINT fit of the set (linear
//! effects refitted together by sign-constrained least squares, motor
//! sides as fixed columns): adding a term (it must gain
//! [`Options::none_margin`] for the first, [`Options::add_margin`] for the
//! others; a richer nested term, Stribeck over Coulomb or elasticity and
//! backlash over a rotor, must beat its simpler one by
//! [`Options::nesting_margin`]), or swapping a chosen term for another of
//! its family at the same place (by the nesting margin). It stops when
//! the residual is within the noise floor on every joint
//! ([`Options::floor_ratio`]) or no move earns its margin. A move must
//! also pass block cross-validation on the training data (`validate.rs`):
//! an added effect must lower the deviance of blocks of time predicted by
//! the fit on the others by [`Options::cv_margin`], a swap must not raise
//! it (the best of [`CV_TRIES`] moves that do is made). A backward pass
//! then drops any effect whose removal costs less than the margin, or
//! whose removal does not raise the cross-validated deviance. The
//! motor sides of the chosen set, and of every joint still above noise,
//! are then searched again with the other effects' effort removed, and the
//! selection resumes from the set (alternation, [`ROUNDS`] times).
//!
//! Where the set leaves joints above their floor, the rows are weighed by
//! the residual left rather than by the floor alone and the selection
//! resumes (`weights.rs`); where it leaves every joint at [`EVERYWHERE`]
//! x its floor (model error, not a missed effect), the search also starts
//! from the full linear model (`eliminate.rs`) and keeps the better set.

use nalgebra::SVector;

use super::analysis::{fit, Prepared};
use super::eliminate::{eliminate, full};
use super::fit::aicc;
use super::parallel;
use super::pool::{fixed_column, Pool, Solution};
use super::validate::Folds;
use super::weights::{loud_joints, weights, within_noise, REWEIGHTS};
use super::Options;
use crate::diagnose::candidate::Candidate;
use dynamics_runtime::Robot;

/// Rounds of selection and motor-side search.
pub const ROUNDS: usize = 2;

/// Residual left on every joint, in units of the floor ratio, above which
/// the search also starts from the full linear model.
pub const EVERYWHERE: f64 = 2.0;

/// The chosen set, its joint fit and the rival of each effect.
#[derive(Debug, Clone)]
pub struct Explanation {
    /// Term indices into the pool, in the order chosen.
    pub set: Vec<usize>,
    /// The joint fit of the whole set.
    pub sol: Solution,
    /// Per effect, a term the data cannot tell from it within the set
    /// (swapped in for it, the criterion moves less than the ambiguity
    /// margin).
    pub rivals: Vec<Option<usize>>,
}

/// Criteria closer than this (in the criterion's units, where margins are
/// several units) are a tie, broken by the pool's order of the terms: a
/// selection must not hang on the last bits of a sum, which differ from
/// build to build (the model's sums are fused multiply-adds where the CPU
/// has them, `dynamics_runtime::fma`).
pub const TIE: f64 = 1e-3;

/// The criterion `c` rounded to [`TIE`], for ordering.
pub fn tie_key(c: f64) -> i64 {
    if c.is_finite() {
        (c / TIE).round() as i64
    } else if c > 0.0 {
        i64::MAX
    } else {
        i64::MIN
    }
}

fn crit(pool: &Pool, s: &Solution) -> f64 {
    aicc(s.sse, pool.n(), s.k)
}

/// The criterion of `set` from its residual computed row by row.
fn explicit_crit(pool: &Pool, set: &[usize]) -> f64 {
    let sol = pool.solve(set);
    aicc(pool.residual(set, &sol).norm_squared(), pool.n(), sol.k)
}

/// The simpler term a richer one nests at its place.
fn simpler(c: Candidate) -> Option<fn(&Candidate) -> bool> {
    match c {
        Candidate::Stribeck(..) => Some(|s| matches!(s, Candidate::Coulomb(_))),
        Candidate::Elasticity(_) | Candidate::Backlash(_) => {
            Some(|s| matches!(s, Candidate::Armature(_)))
        }
        // A point mass at the tip is an inertial change of the tip's link
        // with one parameter instead of up to ten.
        Candidate::Inertial(_) => Some(|s| matches!(s, Candidate::Payload)),
        _ => None,
    }
}

/// What a richer term must gain over the simpler one it nests (or a term
/// over another of its family it replaces): Stribeck's breakaway level is
/// one more parameter on top of Coulomb friction, and must earn it like
/// a first effect (a Stribeck curve at 0.01 rad/s otherwise reshapes
/// the smooth sign of a large Coulomb friction); the motor sides and link
/// corrections the nesting margin.
fn nesting(c: Candidate, options: &Options) -> f64 {
    match c {
        Candidate::Stribeck(..) => options.none_margin.max(options.nesting_margin),
        _ => options.nesting_margin,
    }
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
fn select<const N: usize>(pool: &Pool, mut set: Vec<usize>, options: &Options) -> Vec<usize> {
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
            if set.contains(&t) {
                continue;
            }
            let fam = pool.terms[t].family();
            let (trial, need) = match set.iter().position(|&u| pool.terms[u].family() == fam) {
                Some(i) => {
                    let mut s = set.clone();
                    s[i] = t;
                    (s, nesting(pool.terms[t].fit.candidate, options))
                }
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
fn reweighted<const N: usize>(
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

/// `p` with the effort of the linear joint and tip terms of `set` (fitted
/// `sol`), except position `skip`, added to the model: what a motor side at one joint is
/// searched against.
pub fn without_others<const N: usize>(
    p: &Prepared<N>,
    pool: &Pool,
    set: &[usize],
    sol: &Solution,
    skip: Option<usize>,
) -> Prepared<N> {
    let mut q = p.clone();
    let (a, z) = p.sig.range;
    for (i, &t) in set.iter().enumerate() {
        let term = &pool.terms[t];
        // (A link correction's columns exist on the fit's rows only: the
        // motor sides are searched without it.)
        if Some(i) == skip || term.fixed.is_some() || term.link.is_some() {
            continue;
        }
        let c = term.fit.candidate;
        for k in a..z {
            let cols = c.columns(&p.sig, &p.basis, k);
            let mut e = SVector::<f64, N>::zeros();
            for (m, th) in sol.theta[i].iter().enumerate() {
                e += cols[m] * *th;
            }
            q.sig.model[k] += e;
            q.sig.residual[k] -= e;
        }
    }
    q
}

/// Searches the motor sides of terms `todo` again on `q` (the others'
/// effort removed), on `threads` threads, and puts each in the pool when
/// its search succeeds.
fn research<R: Robot<N>, const N: usize>(
    pool: &mut Pool,
    todo: &[usize],
    q: &Prepared<N>,
    threads: usize,
) {
    let terms = &pool.terms;
    let found = parallel::map(todo, threads, |&t| {
        let f = fit::<R, N>(terms[t].fit.candidate, q);
        (f.motor.is_some() && f.sse.is_finite()).then(|| {
            let col = fixed_column(&f, q);
            (f, col)
        })
    });
    for (&t, found) in todo.iter().zip(found) {
        if let Some((f, col)) = found {
            pool.set_fixed(t, f, col);
        }
    }
}

/// The compound explanation of the residual of `p` over the terms of
/// `pool` (whose motor-side columns are searched again as it goes).
pub fn explain<R: Robot<N>, const N: usize>(
    pool: &mut Pool,
    p: &Prepared<N>,
    options: &Options,
) -> Explanation {
    let mut set = select::<N>(pool, vec![], options);
    set = reweighted::<N>(pool, set, options);
    // Model error left everywhere (every joint still at `EVERYWHERE` x its
    // floor: a missed effect leaves its own joint loud, a real robot's
    // model error all of them): the search from the other end, from every
    // linear term at once, where effects that explain only together are
    // found (`eliminate.rs`). Its set is kept if both its criterion (on the
    // residual computed row by row, not through the Gram matrix, which
    // nearly dependent columns make inexact) and its cross-validated
    // deviance beat the forward path's.
    let gap = pool.floor_rms(&pool.residual(&set, &pool.solve(&set)));
    if gap.iter().all(|&r| r >= EVERYWHERE * options.floor_ratio) {
        let start = eliminate(pool, full(pool), options.add_margin);
        let other = select::<N>(pool, start, options);
        let cv = |s: &[usize]| Folds::new(pool, N).map_or(0.0, |f| f.deviance(pool, s));
        if explicit_crit(pool, &other) < explicit_crit(pool, &set) && cv(&other) < cv(&set) {
            set = reweighted::<N>(pool, other, options);
        }
    }
    for _ in 0..ROUNDS {
        let sol = pool.solve(&set);
        let loud = loud_joints(pool, &set, &sol, options.floor_ratio);
        // Motor sides: those chosen, and all at joints still above noise.
        let todo: Vec<usize> = (0..pool.terms.len())
            .filter(|&t| {
                let term = &pool.terms[t];
                term.fixed.is_some()
                    && (set.contains(&t)
                        || term
                            .fit
                            .candidate
                            .joint()
                            .is_some_and(|j| loud.contains(&j)))
            })
            .collect();
        if todo.is_empty() {
            break;
        }
        let base = without_others(p, pool, &set, &sol, None);
        research::<R, N>(pool, &todo, &base, options.threads);
        let next = select::<N>(pool, set.clone(), options);
        if next == set {
            break;
        }
        set = next;
    }
    // Parsimony once more: a richer nested term the simpler one at its
    // place now fits within the nesting margin gives way to it, and so
    // does a motor side where the rigid rotor in its stead leaves its joint
    // within the noise floor (as in the ranking, `rank::within_floor`).
    for i in 0..set.len() {
        let me = pool.terms[set[i]].fit.candidate;
        let Some(is_simpler) = simpler(me) else {
            continue;
        };
        let full = crit(pool, &pool.solve(&set));
        let alt = (0..pool.terms.len())
            .filter(|&u| {
                let c = pool.terms[u].fit.candidate;
                is_simpler(&c) && c.joint() == me.joint()
            })
            .map(|u| {
                let mut s = set.clone();
                s[i] = u;
                (u, crit(pool, &pool.solve(&s)))
            })
            .min_by_key(|a| (tie_key(a.1), a.0));
        if let Some((u, c)) = alt {
            let quiet = || {
                let mut s = set.clone();
                s[i] = u;
                let sol = pool.solve(&s);
                matches!(me, Candidate::Elasticity(_) | Candidate::Backlash(_))
                    && me.joint().is_some_and(|j| {
                        !loud_joints(pool, &s, &sol, options.floor_ratio).contains(&j)
                    })
            };
            if c - full < nesting(me, options) || quiet() {
                set[i] = u;
            }
        }
    }
    let sol = pool.solve(&set);
    let full = crit(pool, &sol);
    let rivals = (0..set.len())
        .map(|i| {
            let me = pool.terms[set[i]].fit.candidate;
            (0..pool.terms.len())
                .filter(|t| !set.contains(t))
                .filter(|&t| {
                    let c = pool.terms[t].fit.candidate;
                    (c.kind(), c.joint()) != (me.kind(), me.joint())
                        && !set.iter().enumerate().any(|(m, &u)| {
                            m != i && pool.terms[u].family() == pool.terms[t].family()
                        })
                })
                .map(|t| {
                    let mut s = set.clone();
                    s[i] = t;
                    (t, crit(pool, &pool.solve(&s)) - full)
                })
                .filter(|(_, d)| *d < options.ambiguity_margin)
                .min_by_key(|a| (tie_key(a.1), a.0))
                .map(|(t, _)| t)
        })
        .collect();
    Explanation { set, sol, rivals }
}
