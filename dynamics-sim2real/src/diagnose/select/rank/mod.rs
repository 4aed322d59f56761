//! Ranking the fitted candidates: the best grid variant per (kind, place)
//! by AICc, parsimony between nested models (`nesting.rs`), rival motor
//! sides.

use super::nesting::simpler;
use crate::diagnose::candidates::{Candidate, Prepared};
use crate::diagnose::fit::{Fit, Windows};
use crate::diagnose::Options;

/// What the ranking asks of the data beyond a fit's training AICc.
pub struct Judge<'a> {
    /// Whether the fit (a rigid rotor) leaves its joint's residual within
    /// the noise floor (see [`within_floor`]).
    pub quiet: &'a dyn Fn(&Fit) -> bool,
    /// The held-out deviance of the fit's parameters (fitted on the
    /// training data, not refitted): `n ln(sse / n)` of the whitened
    /// held-out residual it leaves, on the scale of the AICc's first term.
    pub held_out: &'a dyn Fn(&Fit) -> f64,
}

/// The best variant of each (kind, place), best AICc first; then two
/// decisions between close relatives at one joint, where said on the
/// evidence of both records: the training AICc plus the held-out deviance
/// (two independent log-likelihoods on one scale; the held-out one has no
/// fitted parameters to pay for).
///
/// - Elasticity and backlash at one joint are rivals that do not contain
///   each other (a spring, a dead zone); where one leads, the other goes
///   first if its evidence of both records is better. The training AICc
///   counts their parameters, not how far each law bends to the record it
///   sees: on generated backlash at the MAR's q2 the elastic fit led on
///   training by 36 and 1 AICc (a stiff, lightly damped spring ringing
///   through the dead zone's crossings) and predicted the held-out record
///   worse than the plain rotor it contains, the backlash fitted there
///   (its true half-width and inertia) by 468 and 301.
/// - A richer model that contains a simpler one at the same joint
///   (Stribeck contains Coulomb; elasticity and backlash contain a rigid
///   rotor; a spring contains an effort offset) must beat it by
///   `nesting_margin`, or the simpler one goes first: Stribeck on the
///   evidence of both records (on a generated Stribeck at 100 Hz, 8.2 AICc
///   ahead on training and 20 on the held-out record), the others on the
///   training AICc alone. A motor side's spring is also a low-pass filter
///   on the effort, and what it fits that way (the velocity loop's
///   reaction to the sensors' noise, see [`within_floor`]) is in every
///   record of the same drive: it predicts the held-out record better too
///   (a generated rotor inertia at 100 Hz: elastic 0.6 AICc ahead on
///   training, 20 on the held-out record), so the held-out record is no
///   evidence for it over its rotor; but it is evidence against it: a
///   motor side must also beat its rotor by the margin on both records
///   together. (On a generated rotor inertia at 100 Hz with a jittered
///   clock, a 16 Hz spring can lead the rotor on training and predict
///   the held-out record far worse, whatever the draw of the noise.) A
///   motor side also goes behind its
///   rotor when `judge.quiet` says the rotor already leaves the joint's
///   residual within the noise floor: then the data show no signature left
///   for the motor side to explain.
pub fn best_per_place(fits: Vec<Fit>, n: usize, nesting_margin: f64, judge: &Judge) -> Vec<Fit> {
    let mut best: Vec<Fit> = Vec::new();
    // A wider Coulomb friction than the sharp one must beat it clearly.
    let cost = |f: &Fit| {
        f.aicc(n)
            + if f.candidate.widened() {
                nesting_margin
            } else {
                0.0
            }
    };
    for f in fits {
        let key = (f.candidate.kind(), f.candidate.joint());
        match best
            .iter_mut()
            .find(|b| (b.candidate.kind(), b.candidate.joint()) == key)
        {
            Some(b) if cost(b) <= cost(&f) => {}
            Some(b) => *b = f,
            None => best.push(f),
        }
    }
    best.sort_by(|a, b| a.aicc(n).total_cmp(&b.aicc(n)));
    if best.len() < 2 {
        return best;
    }
    let evidence = |f: &Fit| f.aicc(n) + (judge.held_out)(f);
    // (Any grid variant of a kind: one per place here.)
    let find = |best: &[Fit], s: Candidate| {
        best.iter()
            .position(|f| f.candidate.kind() == s.kind() && f.candidate.joint() == s.joint())
    };
    // Rival motor sides.
    let rival = match best[0].candidate {
        Candidate::Elasticity(j) => Some(Candidate::Backlash(j)),
        Candidate::Backlash(j) => Some(Candidate::Elasticity(j)),
        _ => None,
    };
    if let Some(i) = rival.and_then(|r| find(&best, r)) {
        if evidence(&best[i]) < evidence(&best[0]) {
            let f = best.remove(i);
            best.insert(0, f);
        }
    }
    // Parsimony (one variant per place here, so the nested one is found by
    // its kind and joint).
    let top = best[0].candidate;
    if let Some(is_simpler) = simpler(top) {
        if let Some(i) = best
            .iter()
            .position(|f| is_simpler(&f.candidate) && f.candidate.joint() == top.joint())
        {
            let s = best[i].candidate;
            let motor_side = matches!(s, Candidate::Armature(_));
            let trained = best[i].aicc(n) - best[0].aicc(n);
            let both = evidence(&best[i]) - evidence(&best[0]);
            let gain = match s {
                Candidate::Coulomb(..) => both,
                // The held-out record may speak against a motor side,
                // never for it.
                Candidate::Armature(_) => trained.min(both),
                _ => trained,
            };
            if gain < nesting_margin || (motor_side && (judge.quiet)(&best[i])) {
                let f = best.remove(i);
                best.insert(0, f);
            }
        }
    }
    best
}

/// Whether the residual `f` leaves at its joint is within `ratio` times the
/// noise floor of `p` (RMS over the fit's rows). Where a rigid rotor leaves
/// no more than noise, what a motor side (elasticity, backlash) still gains
/// over it is not a resonance or a gap in the data: on generated rotor
/// inertias the elastic fit won by 13-32 AICc as a low-pass filter on the
/// effort, absorbing in its rotor the fast effort a velocity loop makes of
/// the encoders' noise, whose effect on the motion lies below the sensors'
/// noise (with that loop closed on noise-free readings the same draws named
/// the rotor), and brought the joint below its noise floor (0.85-0.92 of
/// it) where the rotor left 0.95-1.01.
pub fn within_floor<const N: usize>(f: &Fit, p: &Prepared<N>, ratio: f64) -> bool {
    let Some(j) = f.candidate.joint() else {
        return false;
    };
    let r = f.corrected_rows(p);
    let rows = p.rows.len().max(1) as f64;
    let ms = r
        .iter()
        .map(|v| (v[j] / p.sig.floor[j]).powi(2))
        .sum::<f64>()
        / rows;
    ms.is_finite() && ms.sqrt() <= ratio
}

/// The best variant per (kind, place) of `fits` on training record `p`,
/// best first ([`best_per_place`]), the held-out record `h` adding its
/// evidence where the ranking asks it.
pub fn rank<const N: usize>(
    fits: Vec<Fit>,
    p: &Prepared<N>,
    h: &Prepared<N>,
    windows: &Windows,
    options: &Options,
) -> Vec<Fit> {
    best_per_place(
        fits,
        p.n(),
        options.nesting_margin,
        &Judge {
            quiet: &|f| within_floor(f, p, options.floor_ratio),
            held_out: &|f| super::held_out_deviance(f, h, windows),
        },
    )
}

#[cfg(test)]
mod tests;
