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
//! resumes (`weights.rs`); where it leaves half the joints or more at
//! [`EVERYWHERE`] x their floor (model error, not a missed effect), the
//! search also starts from the full linear model (`eliminate.rs`) and
//! keeps the better set. Each chosen effect other than joint friction is
//! then exchanged for what the selection finds without it, where that is
//! better (`exchange.rs`). What the set holds that is not what it seems
//! (a link correction or payload that leaves no physical body, an effort
//! scale of part of the effort) then leaves the candidates, the motor
//! sides are searched again without it and the selection resumes
//! (`resume.rs`). The set is read in the order of its gains
//! (`order.rs`).

mod bodies;
mod eliminate;
mod exchange;
mod left_out;
mod offsets;
mod order;
mod resume;
mod scales;
mod select;
mod strength;
#[cfg(test)]
mod tests;
mod validate;
mod weights;

use nalgebra::SVector;
use rayon::prelude::*;

use super::criterion::tie_key;
use super::nesting::{nested_rival_stands, nesting, simpler};
use super::pool::prior::STRENGTHS;
use super::pool::{Carrier, Pool, Solution};
use crate::diagnose::candidates::{Candidate, Friction, Prepared};
use crate::diagnose::fit::{fit_against, fixed_column_against, Against, Fit};
use crate::diagnose::Options;
use crate::effects::Effect;
use eliminate::{eliminate, full};
pub use left_out::{LeftOut, Why};
pub use offsets::{partial_offset, partial_offsets};
use resume::without_left_out;
pub use scales::{partial_scale, partial_scales, BesideGravity};
use select::{crit, explicit_crit, reweighted, select, select_except};
use validate::Folds;
use weights::loud_joints;

use dynamics_runtime::Robot;

/// Rounds of selection and motor-side search.
pub const ROUNDS: usize = 2;

/// Rounds of leaving out what is not what it seems, and searching the
/// motor sides again without it.
pub const LEFT_OUT_ROUNDS: usize = 2;

/// Residual left on every joint, in units of the floor ratio, above which
/// the search also starts from the full linear model.
pub const EVERYWHERE: f64 = 2.0;

/// Loud joints at least (and half the joints) for the search from the full
/// linear model.
pub const MODEL_ERROR_JOINTS: usize = 2;

/// The chosen set, its joint fit and the rival of each effect.
#[derive(Debug, Clone)]
pub struct Explanation {
    /// Term indices into the pool, in the order of their gains (`order.rs`).
    pub set: Vec<usize>,
    /// The joint fit of the whole set.
    pub sol: Solution,
    /// Per effect, a term the data cannot tell from it within the set
    /// (swapped in for it, the criterion moves less than the ambiguity
    /// margin).
    pub rivals: Vec<Option<usize>>,
    /// What the selection chose and left out: link corrections that leave
    /// no physical body, effort scales of part of the effort
    /// (`resume.rs`).
    pub left_out: Vec<LeftOut>,
}

/// `p` against the effort of the linear joint and tip terms of `set`
/// (fitted `sol`) added to its model: what a motor side at one joint is
/// searched against. The others' efforts are made where read (at the
/// rows, and at the motor side's joint over what it simulates), not
/// along the whole record.
pub fn against_others<'a, const N: usize>(
    p: &'a Prepared<N>,
    pool: &Pool,
    set: &[usize],
    sol: &'a Solution,
) -> Against<'a, N> {
    let others = set
        .iter()
        .enumerate()
        .filter(|&(_, &t)| {
            let term = &pool.terms[t];
            // (A link correction's columns exist on the fit's rows only:
            // the motor sides are searched without it.)
            term.fixed.is_none() && term.link.is_none()
        })
        .map(|(i, &t)| (pool.terms[t].fit.candidate, sol.theta[i].as_slice()))
        .collect();
    Against::others(p, others)
}

/// `p` with the effort of the linear joint and tip terms of `set` (fitted
/// `sol`) added to the model and taken from the residual at every sample:
/// what [`against_others`] gives where read, copied along the record.
#[cfg(test)]
pub fn without_others<const N: usize>(
    p: &Prepared<N>,
    pool: &Pool,
    set: &[usize],
    sol: &Solution,
) -> Prepared<N> {
    let mut q = p.clone();
    let (a, z) = p.sig.range;
    for (i, &t) in set.iter().enumerate() {
        let term = &pool.terms[t];
        if term.fixed.is_some() || term.link.is_some() {
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
    // Another model on the same motion: the motor sides' kept tracks are
    // told apart by the motion.
    q.sig.motion = crate::diagnose::signals::Motion::of(&q.sig.record, &q.sig.sg);
    q
}

/// Searches the motor sides of terms `todo` again against `on` (the
/// others' effort removed), on the current rayon pool, and puts each in
/// the pool when its search succeeds.
fn research<R: Robot<N>, const N: usize>(pool: &mut Pool, todo: &[usize], on: &Against<N>) {
    let terms = &pool.terms;
    // Joint by joint: the model's effort along the record at a joint is
    // made once for the motor sides there and dropped after the last.
    let joint = |t: usize| terms[t].fit.candidate.joint().unwrap_or(0);
    let mut order: Vec<usize> = (0..todo.len()).collect();
    order.sort_by_key(|&i| (joint(todo[i]), i));
    for &t in todo {
        on.expect(joint(t), 1);
    }
    let mut found: Vec<_> = order
        .par_iter()
        .with_max_len(1)
        .map(|&i| {
            let t = todo[i];
            let f = fit_against::<R, N>(terms[t].fit.candidate, on);
            let found = (f.motor.is_some() && f.sse.is_finite()).then(|| {
                let col = fixed_column_against(&f, on);
                (f, col)
            });
            on.done(joint(t));
            (i, found)
        })
        .collect();
    found.sort_by_key(|a| a.0);
    for (&t, (_, found)) in todo.iter().zip(found) {
        if let Some((f, col)) = found {
            pool.set_fixed(t, f, col);
        }
    }
}

/// Motor sides searched again against the rest of `set` (those chosen,
/// and all at joints still above noise) and the selection resumed without
/// the terms `banned`, [`ROUNDS`] times at most (until the set stays).
fn alternate<R: Robot<N>, const N: usize>(
    pool: &mut Pool,
    p: &Prepared<N>,
    mut set: Vec<usize>,
    options: &Options,
    banned: &[usize],
) -> Vec<usize> {
    for _ in 0..ROUNDS {
        let sol = pool.solve(&set);
        let loud = loud_joints(pool, &set, &sol, options.floor_ratio);
        // Motor sides: those chosen, and all at joints still above noise.
        let todo: Vec<usize> = (0..pool.terms.len())
            .filter(|&t| {
                let term = &pool.terms[t];
                term.fixed.is_some()
                    && !banned.contains(&t)
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
        let on = against_others(p, pool, &set, &sol);
        research::<R, N>(pool, &todo, &on);
        let next = select_except::<N>(pool, set.clone(), options, banned);
        if next == set {
            break;
        }
        set = next;
    }
    set
}

/// The compound explanation of the residual of `p` over the terms of
/// `pool` (whose motor-side columns are searched again as it goes);
/// `beside`: the model's effort beside gravity, what an effort scale's
/// column is split by (`None`: scales not split).
pub fn explain<R: Robot<N>, const N: usize>(
    pool: &mut Pool,
    p: &Prepared<N>,
    nominal: &[SVector<f64, 10>],
    carrier: Option<&Carrier>,
    beside: Option<&BesideGravity>,
    options: &Options,
) -> Explanation {
    let mut set = select::<N>(pool, vec![], options);
    set = reweighted::<N>(pool, set, options);
    // Model error left all over (half the joints or more, at least
    // [`MODEL_ERROR_JOINTS`], still at `EVERYWHERE` x their floor: a
    // missed effect leaves its own joint loud, a real robot's model error
    // most of them; an effect that quiets one joint, a spring at the
    // Panda's wrist, does not make it a missed effect): the search from the
    // other end, from every
    // linear term at once, where effects that explain only together are
    // found (`eliminate.rs`). Its set is kept if both its criterion (on the
    // residual computed row by row, not through the Gram matrix, which
    // nearly dependent columns make inexact) and its cross-validated
    // deviance beat the forward path's.
    let gap = pool.floor_rms(&pool.residual(&set, &pool.solve(&set)));
    let loud = gap
        .iter()
        .filter(|&&r| r >= EVERYWHERE * options.floor_ratio)
        .count();
    if loud >= MODEL_ERROR_JOINTS.max(N.div_ceil(2)).min(N) {
        let start = eliminate(pool, full(pool), options.add_margin);
        let other = select::<N>(pool, start, options);
        let cv = |s: &[usize]| Folds::new(pool, N).map_or(0.0, |f| f.deviance(pool, s));
        if explicit_crit(pool, &other) < explicit_crit(pool, &set) && cv(&other) < cv(&set) {
            set = reweighted::<N>(pool, other, options);
        }
    }
    // An effect that stands in for several others (`exchange.rs`).
    set = exchange::exchange::<N>(pool, set, options);
    // The prior's strength by cross-validation of the set (`strength.rs`);
    // the selection resumes from the set under a weaker one.
    if strength::choose::<N>(pool, &set) != STRENGTHS[0] {
        set = select::<N>(pool, set, options);
    }
    set = alternate::<R, N>(pool, p, set, options, &[]);
    // Link corrections and payloads that leave no physical body, effort
    // scales of part of the effort: out, and the selection resumes
    // without them (`resume.rs`); the motor sides, searched beside what
    // was left out, are searched again without it, and the selection
    // resumes (at most [`LEFT_OUT_ROUNDS`] times).
    let mut left_out = Vec::new();
    let mut banned = Vec::new();
    for round in 0..LEFT_OUT_ROUNDS {
        let (next, out, ban) =
            without_left_out::<N>(pool, set, nominal, carrier, beside, &banned, options);
        set = next;
        let done = out.is_empty();
        left_out.extend(out);
        banned.extend(ban);
        if done || round + 1 == LEFT_OUT_ROUNDS {
            break;
        }
        set = alternate::<R, N>(pool, p, set, options, &banned);
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
    // Read in the order of the gains (`order.rs`).
    let set = order::by_gain(pool, &set);
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
                .filter_map(|t| {
                    let mut s = set.clone();
                    s[i] = t;
                    let swapped = pool.solve(&s);
                    let d = crit(pool, &swapped) - full;
                    // A rival nesting the chosen effect (or nested by it)
                    // at its place: its extra parameter's interval, in the
                    // fit that holds the richer of the two, decides.
                    let c = pool.terms[t].fit.candidate;
                    let stands = c.joint() != me.joint() || {
                        let mine = joint_fit(pool, set[i], &sol.theta[i], &sol.std[i]);
                        let theirs = joint_fit(pool, t, &swapped.theta[i], &swapped.std[i]);
                        nested_rival_stands(
                            (me.kind(), &mine.parameters()),
                            (c.kind(), &theirs.parameters()),
                        )
                    };
                    (d < options.ambiguity_margin && stands).then_some((t, d))
                })
                .min_by_key(|a| (tie_key(a.1), a.0))
                .map(|(t, _)| t)
        })
        .collect();
    Explanation {
        set,
        sol,
        rivals,
        left_out,
    }
}

/// The fit of term `t` with the joint fit's parameters.
pub fn joint_fit(pool: &Pool, t: usize, theta: &[f64], std: &[f64]) -> Fit {
    let mut f = pool.terms[t].fit.clone();
    if pool.terms[t].fixed.is_none() {
        f.theta = theta.to_vec();
        f.std = std.to_vec();
    }
    f
}

/// The effects of the set with their fitted parameters (a friction
/// correction may take away the nominal model's own `friction`, its
/// Coulomb levels and viscous coefficients per joint).
pub fn effects<const N: usize>(
    pool: &Pool,
    e: &Explanation,
    friction: &Friction<N>,
) -> Vec<Effect> {
    e.set
        .iter()
        .enumerate()
        .filter_map(|(i, &t)| joint_fit(pool, t, &e.sol.theta[i], &e.sol.std[i]).effect())
        // (A late effort is a negative delay here, `candidate.rs`.)
        .filter(|e| {
            e.validate_beside_friction(friction.0.as_slice(), friction.1.as_slice())
                .is_ok()
                || matches!(e, Effect::TimeDelay { delay } if delay.is_finite())
                // Bounded by the tip body's mass in the fit (`lower_bounds`).
                || matches!(e, Effect::PayloadMass { mass, .. } if mass.is_finite())
        })
        .collect()
}
