//! The strength of the prior toward the nominal model (`prior.rs`),
//! chosen by block cross-validation on the training data (`validate.rs`).
//!
//! How far a CAD model's inertial parameters are off is not known in
//! advance: a prior strong enough to keep a fit with every link's
//! parameters physical on a few seconds of one record holds back the
//! corrections a richer record determines. The set of effects chosen at
//! the strongest prior is therefore fitted at each strength of
//! [`STRENGTHS`] of the links' prior, on all blocks of time but one and
//! scored on the block left out, for every block in turn; the strength
//! whose fits predict the left-out blocks best is kept (the stronger on a
//! tie). Parameters the data do not determine stay near their nominal
//! values at any strength; those they do move as far as blocks of data
//! they were not fitted on bear out. The effort scales' prior keeps its
//! strength (`prior::SCALE_STRENGTH`): a common scale and a common
//! scaling of the links are the one direction no block of data can tell
//! apart.

use crate::diagnose::select::compound::validate::Folds;
use crate::diagnose::select::criterion::tie_key;
use crate::diagnose::select::pool::prior::STRENGTHS;
use crate::diagnose::select::pool::Pool;

/// Whether `set` has a term the links' prior holds: the others are the
/// same at every strength.
fn held(pool: &Pool, set: &[usize]) -> bool {
    set.iter()
        .any(|&t| pool.prior().holds_links(&pool.terms[t].cols))
}

/// The strength of [`STRENGTHS`] under which `set` best predicts blocks
/// of the training rows of `pool` (`joints` rows per sample) it was not
/// fitted on; `pool` is left at it. Without a held term or enough rows for
/// the blocks, the pool's strength stays.
pub fn choose<const N: usize>(pool: &mut Pool, set: &[usize]) -> f64 {
    if !held(pool, set) {
        return pool.strength();
    }
    let start = pool.strength();
    let Some(mut folds) = Folds::new(pool, N) else {
        return start;
    };
    let mut scored: Vec<(usize, f64)> = Vec::new();
    for (i, &s) in STRENGTHS.iter().enumerate() {
        pool.set_strength(s);
        folds.follow(pool);
        let d = folds.deviance(pool, set);
        if d.is_finite() {
            scored.push((i, d));
        }
    }
    let best = scored
        .iter()
        .min_by_key(|&&(i, d)| (tie_key(d), i))
        .map_or(start, |&(i, _)| STRENGTHS[i]);
    pool.set_strength(best);
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnose::candidates::Candidate;
    use crate::diagnose::select::pool::{test_pool, test_term};
    use nalgebra::{DMatrix, DVector};

    /// A link's parameter off by two prior spreads (-0.4 on a spread of
    /// 0.2) that few rows determine well: the strongest prior (one row per
    /// spread, a tenth of the data's information here) pulls the fit
    /// toward nominal and predicts left-out blocks worse, so a weaker one
    /// is chosen and the fit comes close to the truth.
    #[test]
    fn a_determined_link_parameter_weakens_the_prior() {
        let n = 40;
        let mut rng = crate::synth::Rng::new(5);
        let c: Vec<f64> = (0..n).map(|i| (i as f64 * 0.3).sin()).collect();
        let y: Vec<f64> = c.iter().map(|x| -0.4 * x + 0.05 * rng.normal()).collect();
        let x = DMatrix::from_fn(n, 1, |r, _| c[r]);
        let link = test_term(Candidate::Inertial(0), vec![0], vec![false], None);
        let mut pool = test_pool(x, DVector::from_vec(y), vec![link], 1);
        let mut prior = pool.prior().clone();
        prior.links = DMatrix::from_element(1, 1, 1.0 / 0.04);
        pool.set_prior(prior);
        let strong = pool.solve(&[0]).theta[0][0];
        let s = choose::<1>(&mut pool, &[0]);
        let weak = pool.solve(&[0]).theta[0][0];
        assert!(s < STRENGTHS[0], "{s}");
        assert_eq!(pool.strength(), s);
        assert!((weak + 0.4).abs() < (strong + 0.4).abs(), "{weak} {strong}");
        assert!((weak + 0.4).abs() < 0.02, "{weak}");
    }

    /// Folds that follow the pool's strength score a set as folds built
    /// afresh at that strength do.
    #[test]
    fn folds_that_follow_the_strength_equal_folds_built_at_it() {
        let n = 64;
        let c: Vec<f64> = (0..n).map(|i| (i as f64 * 0.3).sin()).collect();
        let y: Vec<f64> = (0..n)
            .map(|i| -0.4 * c[i] + 0.1 * (i as f64 * 1.7).cos())
            .collect();
        let x = DMatrix::from_fn(n, 1, |r, _| c[r]);
        let link = test_term(Candidate::Inertial(0), vec![0], vec![false], None);
        let mut pool = test_pool(x, DVector::from_vec(y), vec![link], 1);
        let mut prior = pool.prior().clone();
        prior.links = DMatrix::from_element(1, 1, 1.0 / 0.04);
        pool.set_prior(prior);
        let mut folds = Folds::new(&pool, 1).expect("enough rows");
        for &s in &STRENGTHS[1..] {
            pool.set_strength(s);
            folds.follow(&pool);
            let fresh = Folds::new(&pool, 1).expect("enough rows");
            let (a, b) = (folds.deviance(&pool, &[0]), fresh.deviance(&pool, &[0]));
            assert!((a - b).abs() < 1e-9 * b.abs().max(1.0), "{s}: {a} {b}");
        }
    }

    /// A term the links' prior does not hold (here an effort scale, whose
    /// prior keeps its own strength): the strength stays.
    #[test]
    fn a_set_without_a_held_term_keeps_the_strength() {
        let n = 400;
        let c: Vec<f64> = (0..n).map(|i| (i as f64 * 0.02).cos()).collect();
        let x = DMatrix::from_fn(n, 1, |r, _| c[r]);
        let y = DVector::from_fn(n, |r, _| 0.3 * c[r]);
        let t = test_term(Candidate::EffortScale(0), vec![0], vec![false], None);
        let mut pool = test_pool(x, y, vec![t], 1);
        let mut prior = pool.prior().clone();
        prior.links = DMatrix::zeros(1, 1);
        prior.scales = DMatrix::from_element(1, 1, 25.0);
        pool.set_prior(prior);
        assert_eq!(choose::<1>(&mut pool, &[0]), STRENGTHS[0]);
    }
}
