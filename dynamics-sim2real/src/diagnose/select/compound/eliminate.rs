//! Backward elimination from the full linear model: the other end of the
//! compound explanation's search. Forward selection adds one term at a
//! time, so effects that explain the gap only together (a real arm's
//! per-joint effort scales with the links' inertial parameters refitted:
//! a scale alone fights the nominal inertials, the links alone cannot
//! scale one joint's effort) never earn their margin one by one. Starting
//! from every linear term at once (per kind and place the variant whose
//! single fit is best, and every link correction), the term whose removal
//! costs the least is dropped while that cost is under the margin; each
//! cost is the Wald statistic of its parameters in the joint fit (for
//! least squares exactly the rise of the residual sum of squares when the
//! term is left out and the others refitted), so one factorisation per
//! step prices every term. `compound.rs` resumes the selection from what
//! is left and keeps it if its criterion beats the forward path's.

use nalgebra::{DMatrix, DVector};

use crate::diagnose::numeric::aicc;
use crate::diagnose::select::criterion::tie_key;
use crate::diagnose::select::pool::{independent, Pool};

/// Every linear term of `pool`, one per family (kind and place): the
/// variant whose single fit is best; every link correction.
pub fn full(pool: &Pool) -> Vec<usize> {
    let mut best: Vec<((u8, Option<usize>), usize, f64)> = Vec::new();
    for (t, term) in pool.terms.iter().enumerate() {
        if term.fixed.is_some() || term.cols.is_empty() {
            continue;
        }
        let sse = if term.fit.sse.is_finite() {
            term.fit.sse
        } else {
            f64::INFINITY
        };
        match best.iter_mut().find(|b| b.0 == term.family()) {
            Some(b) if sse < b.2 => {
                b.1 = t;
                b.2 = sse;
            }
            Some(_) => {}
            None => best.push((term.family(), t, sse)),
        }
    }
    let mut set: Vec<usize> = best.into_iter().map(|b| b.1).collect();
    set.sort_unstable();
    set
}

/// Drops from `set` the term whose removal raises the information
/// criterion least, while that rise is under `margin` (sign constraints
/// are left to the exact backward pass that follows).
pub fn eliminate(pool: &Pool, mut set: Vec<usize>, margin: f64) -> Vec<usize> {
    let n = pool.n();
    loop {
        let mut cols = Vec::new();
        let mut owner = Vec::new();
        for (i, &t) in set.iter().enumerate() {
            for &c in &pool.terms[t].cols {
                cols.push(c);
                owner.push(i);
            }
        }
        let active = independent(pool.gram(), &cols);
        let idx: Vec<usize> = (0..cols.len()).filter(|&i| active[i]).collect();
        let m = idx.len();
        if m == 0 {
            return set;
        }
        let d: Vec<f64> = idx
            .iter()
            .map(|&i| pool.gram()[(cols[i], cols[i])].sqrt())
            .collect();
        let g = DMatrix::from_fn(m, m, |r, c| {
            pool.gram()[(cols[idx[r]], cols[idx[c]])] / (d[r] * d[c])
        });
        let b = DVector::from_fn(m, |r, _| pool.xty()[cols[idx[r]]] / d[r]);
        let Some(ch) = g.cholesky() else {
            return set;
        };
        let z = ch.solve(&b);
        let inv = ch.inverse();
        let sse = (pool.yy() - z.dot(&b)).max(1e-12 * pool.yy().max(1e-300));
        let now = aicc(sse, n, m);
        let mut weakest: Option<(usize, f64)> = None;
        for i in 0..set.len() {
            let own: Vec<usize> = (0..m).filter(|&r| owner[idx[r]] == i).collect();
            let rise = if own.is_empty() {
                0.0
            } else {
                let block = DMatrix::from_fn(own.len(), own.len(), |a, c| inv[(own[a], own[c])]);
                let zb = DVector::from_fn(own.len(), |a, _| z[own[a]]);
                block.cholesky().map_or(0.0, |c| zb.dot(&c.solve(&zb)))
            };
            let cost = aicc(sse + rise.max(0.0), n, m - own.len()) - now;
            if weakest.is_none_or(|w| tie_key(cost) < tie_key(w.1)) {
                weakest = Some((i, cost));
            }
        }
        match weakest {
            Some((i, cost)) if cost < margin => {
                set.remove(i);
            }
            _ => return set,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnose::candidates::Candidate;
    use crate::diagnose::select::pool::{test_pool, test_term, Term};

    fn term(c: Candidate, col: usize) -> Term {
        test_term(c, vec![col], vec![false], None)
    }

    /// Two columns that explain the data only together (each alone earns
    /// little) survive the elimination, the noise columns go, and the
    /// Wald cost of a term is the exact refit's rise of the criterion.
    #[test]
    fn terms_that_explain_only_together_survive_and_the_costs_are_exact() {
        let n = 600;
        let mut rng = crate::synth::Rng::new(7);
        let s: Vec<f64> = (0..n).map(|i| (i as f64 * 0.02).sin()).collect();
        let u: Vec<f64> = (0..n).map(|i| (i as f64 * 0.31).cos()).collect();
        // a = s + 10 u, b = 10 u: y = 3 (a - b), while a and b alone
        // explain little of it.
        let a: Vec<f64> = (0..n).map(|i| s[i] + 10.0 * u[i]).collect();
        let b: Vec<f64> = (0..n).map(|i| 10.0 * u[i]).collect();
        let y: Vec<f64> = (0..n).map(|i| 3.0 * s[i] + 0.05 * rng.normal()).collect();
        let mut cols = vec![a, b];
        for _ in 0..5 {
            cols.push((0..n).map(|_| rng.normal()).collect());
        }
        let x = DMatrix::from_fn(n, cols.len(), |r, c| cols[c][r]);
        let yv = DVector::from_vec(y);
        let terms = (0..cols.len())
            .map(|c| term(Candidate::EffortOffset(c), c))
            .collect();
        let pool = test_pool(x, yv, terms, 1);
        // One at a time, neither a nor b earns 40 against nothing.
        let none = aicc(pool.yy(), n, 0);
        for t in [0, 1] {
            let alone = pool.solve(&[t]);
            assert!(none - aicc(alone.sse, n, 1) < 40.0, "{t}");
        }
        let all: Vec<usize> = (0..cols.len()).collect();
        assert_eq!(full(&pool), all);
        assert_eq!(eliminate(&pool, all, 40.0), vec![0, 1]);
        // A margin just under the smaller exact cost of leaving one of the
        // pair out keeps both; just over it, one goes.
        let pair = aicc(pool.solve(&[0, 1]).sse, n, 2);
        let exact = [1, 0]
            .map(|t| aicc(pool.solve(&[t]).sse, n, 1) - pair)
            .into_iter()
            .fold(f64::INFINITY, f64::min);
        assert!(exact > 1000.0, "{exact}");
        assert_eq!(eliminate(&pool, vec![0, 1], exact - 1.0), vec![0, 1]);
        assert!(eliminate(&pool, vec![0, 1], exact + 1.0).len() < 2);
    }
}
