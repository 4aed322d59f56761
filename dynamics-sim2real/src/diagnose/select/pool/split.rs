//! A term's column split by joint: the same joint fit with one parameter
//! per joint in place of the term's one, what tells an effect common to
//! every joint (a late stream shifts every joint's effort alike) from one
//! that only some joints show (`evaluate/confirm.rs`).

use nalgebra::{DMatrix, DVector};

use super::prior::Prior;
use super::{penalised, Pool, Solution, Term};

impl Pool {
    /// The pool of `set`'s columns alone with the single free column of
    /// term `set[at]` split by joint: its rows of joint `j` (the pool's
    /// rows are `row * joints + j`) become a column of their own, each a
    /// term with a free sign and no limit. Returns that pool and its set
    /// (the other terms in their order, then the joints' terms in joint
    /// order, those whose column is zero left out, with their joints);
    /// `None` when the term has not exactly one free column or the pool
    /// keeps no rows.
    pub fn split_by_joint(&self, set: &[usize], at: usize) -> Option<(Pool, Vec<usize>, Vec<usize>)> {
        let joints = self.weights.len();
        let split = &self.terms[*set.get(at)?];
        let [col] = split.cols[..] else {
            return None;
        };
        if self.x.nrows() == 0 || joints == 0 {
            return None;
        }
        // The columns of the other terms, renumbered in order.
        let mut cols: Vec<usize> = Vec::new();
        let mut terms: Vec<Term> = Vec::new();
        let renumber = |c: usize, cols: &mut Vec<usize>| -> usize {
            cols.push(c);
            cols.len() - 1
        };
        for (i, &t) in set.iter().enumerate() {
            if i == at {
                continue;
            }
            let mut term = self.terms[t].clone();
            term.cols = term.cols.iter().map(|&c| renumber(c, &mut cols)).collect();
            term.fixed = term.fixed.map(|f| renumber(f, &mut cols));
            terms.push(term);
        }
        let kept = cols.len();
        let n = self.x.nrows();
        let source = self.x.column(col);
        let mut x = DMatrix::<f64>::zeros(n, kept + joints);
        for (k, &c) in cols.iter().enumerate() {
            x.set_column(k, &self.x.column(c));
        }
        for r in 0..n {
            x[(r, kept + r % joints)] = source[r];
        }
        let mut which = Vec::new();
        for j in 0..joints {
            if x.column(kept + j).iter().all(|v| *v == 0.0) {
                continue;
            }
            let mut term = split.clone();
            term.cols = vec![kept + j];
            term.lower = vec![f64::NEG_INFINITY];
            term.limit = vec![f64::INFINITY];
            term.k = 1;
            terms.push(term);
            which.push(j);
        }
        // The prior over the kept columns (none on the split ones).
        let sub = |m: &DMatrix<f64>| {
            if m.nrows() <= cols.iter().copied().max().unwrap_or(0) {
                return DMatrix::zeros(0, 0);
            }
            DMatrix::from_fn(kept + joints, kept + joints, |r, c| {
                if r < kept && c < kept {
                    m[(cols[r], cols[c])]
                } else {
                    0.0
                }
            })
        };
        let prior = Prior {
            links: sub(&self.prior.links),
            scales: sub(&self.prior.scales),
        };
        let y: DVector<f64> = self.y.clone();
        let yy = self.yy;
        let gram = penalised(&x, &prior, yy, self.strength);
        let xty = x.tr_mul(&y);
        let count = terms.len();
        let pool = Pool {
            x,
            y,
            gram,
            xty,
            yy,
            terms,
            weights: self.weights.clone(),
            prior,
            strength: self.strength,
        };
        Some((pool, (0..count).collect(), which))
    }
}

/// Per joint, the parameter of a split term and its standard deviation
/// from the joint fit `sol` of the split pool's set (`which`: the joints
/// of its last terms, as [`Pool::split_by_joint`] gives them).
pub fn per_joint(sol: &Solution, which: &[usize]) -> Vec<(usize, f64, f64)> {
    let first = sol.theta.len().saturating_sub(which.len());
    which
        .iter()
        .enumerate()
        .filter_map(|(m, &j)| {
            let th = sol.theta.get(first + m)?.first()?;
            let sd = sol.std.get(first + m)?.first()?;
            Some((j, *th, *sd))
        })
        .collect()
}
