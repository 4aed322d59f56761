//! Block cross-validation of a compound explanation on the training data:
//! the fit's rows cut into [`FOLDS`] contiguous blocks of time; each set
//! of effects is fitted on all blocks but one and scored on the block
//! left out, for every block in turn. An effect earns its place only if
//! it predicts the residual of data it was not fitted on; a term with
//! many parameters (a link's ten inertial parameters) that bends to the
//! misfit of others on the data it sees does not.
//!
//! Everything comes from per-block Gram matrices (`X_b^T X_b`, `X_b^T y_b`,
//! `y_b^T y_b`), built once per selection from the pool's columns: the
//! fit on the other blocks subtracts one block's Gram from the whole.

use crate::diagnose::select::pool::{Pool, RowsGram};
use rayon::prelude::*;

/// Contiguous blocks of time.
pub const FOLDS: usize = 4;

/// One block's Gram matrix and the pool fitted on the other blocks.
struct Block {
    own: RowsGram,
    rest: Pool,
}

/// The blocks of a pool.
pub struct Folds {
    blocks: Vec<Block>,
    n: usize,
}

impl Folds {
    /// Cuts the rows of `pool` (`joints` scalar rows per sample) into
    /// [`FOLDS`] blocks of samples; `None` when there are too few rows.
    pub fn new(pool: &Pool, joints: usize) -> Option<Folds> {
        let samples = pool.n() / joints.max(1);
        if samples < 8 * FOLDS {
            return None;
        }
        // The blocks' Gram matrices formed side by side.
        let blocks = (0..FOLDS)
            .into_par_iter()
            .map(|b| {
                let (a, z) = (
                    b * samples / FOLDS * joints,
                    (b + 1) * samples / FOLDS * joints,
                );
                let own = pool.rows_gram(a, z);
                let rest = pool.without(&own, z - a);
                Block { own, rest }
            })
            .collect();
        Some(Folds {
            blocks,
            n: pool.n(),
        })
    }

    /// Follows a change of `pool`'s prior strength (`Pool::set_strength`,
    /// which changes only its Gram matrix): each block's fit on the others
    /// is the pool's Gram less the block's, not formed from the rows again.
    pub fn follow(&mut self, pool: &Pool) {
        for b in &mut self.blocks {
            pool.follow_without(&mut b.rest, &b.own);
        }
    }

    /// The residual sum of squares of `set` on every block, each block
    /// predicted by the fit on the others.
    pub fn sse(&self, pool: &Pool, set: &[usize]) -> f64 {
        let mut total = 0.0;
        for b in &self.blocks {
            let sol = b.rest.solve(set);
            // Coefficients of the pool's columns (fixed columns: 1).
            let mut coef: Vec<(usize, f64)> = Vec::new();
            for (i, &t) in set.iter().enumerate() {
                let term = &pool.terms[t];
                for (c, th) in term.cols.iter().zip(&sol.theta[i]) {
                    if *th != 0.0 && th.is_finite() {
                        coef.push((*c, *th));
                    }
                }
                if let Some(f) = term.fixed {
                    coef.push((f, 1.0));
                }
            }
            let mut s = b.own.yy;
            for &(c, v) in &coef {
                s -= 2.0 * v * b.own.xty[c];
                for &(d, w) in &coef {
                    s += v * w * b.own.gram[(c, d)];
                }
            }
            total += s.max(0.0);
        }
        total
    }

    /// The cross-validated deviance of `set`, `n ln(sse / n)`: on the scale
    /// of the information criterion's first term.
    pub fn deviance(&self, pool: &Pool, set: &[usize]) -> f64 {
        let n = self.n as f64;
        n * (self.sse(pool, set).max(1e-300) / n).ln()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnose::candidates::Candidate;
    use crate::diagnose::select::pool::{test_pool, test_term, Term};
    use nalgebra::{DMatrix, DVector};

    fn term(c: Candidate, col: usize) -> Term {
        test_term(c, vec![col], vec![false], None)
    }

    /// A column that carries the signal lowers the cross-validated
    /// deviance; one that only fits noise (many of them) raises it, though
    /// each lowers the training residual; the Gram route equals a direct
    /// fit on three blocks and prediction of the fourth.
    #[test]
    fn cross_validation_rewards_signal_and_penalises_fitted_noise() {
        let n = 400;
        let mut rng = crate::synth::Rng::new(11);
        let signal: Vec<f64> = (0..n).map(|i| (i as f64 * 0.03).sin()).collect();
        let noise_cols: Vec<Vec<f64>> = (0..30)
            .map(|_| (0..n).map(|_| rng.normal()).collect())
            .collect();
        let y: Vec<f64> = (0..n).map(|i| 3.0 * signal[i] + rng.normal()).collect();
        let mut cols = vec![signal.clone()];
        cols.extend(noise_cols);
        let x = DMatrix::from_fn(n, cols.len(), |r, c| cols[c][r]);
        let yv = DVector::from_vec(y.clone());
        let mut terms = vec![term(
            Candidate::Coulomb(0, crate::effects::SIGN_SMOOTHING),
            0,
        )];
        terms.extend((1..cols.len()).map(|c| term(Candidate::EffortOffset(0), c)));
        let pool = test_pool(x.clone(), yv.clone(), terms, 1);
        let folds = Folds::new(&pool, 1).expect("enough rows");
        let none = folds.deviance(&pool, &[]);
        let sig = folds.deviance(&pool, &[0]);
        let all: Vec<usize> = (0..cols.len()).collect();
        let over = folds.deviance(&pool, &all);
        assert!(sig < none - 100.0, "{sig} {none}");
        assert!(over > sig + 5.0, "{over} {sig}");
        assert!(pool.solve(&all).sse < pool.solve(&[0]).sse);
        // Direct: fit the signal column on blocks 1-3, predict block 0.
        let (a, z) = (0, n / 4);
        let rest: Vec<usize> = (z..n).collect();
        let xs: f64 = rest.iter().map(|&r| signal[r] * y[r]).sum::<f64>()
            / rest.iter().map(|&r| signal[r] * signal[r]).sum::<f64>();
        let direct0: f64 = (a..z).map(|r| (y[r] - xs * signal[r]).powi(2)).sum();
        let one = Folds {
            blocks: folds.blocks.into_iter().take(1).collect(),
            n,
        };
        assert!((one.sse(&pool, &[0]) / direct0 - 1.0).abs() < 1e-9);
    }
}
