//! A term's column split in two: the same joint fit with a parameter for
//! a given part of the term's column and one for the rest, what tells an
//! effect on the whole of a signal (a late stream shifts every part of
//! the effort alike) from one that only part of it shows
//! (`evaluate/confirm.rs`).

use nalgebra::DMatrix;

use super::prior::Prior;
use super::{penalised, Blocks, Pool, Solution};

/// The two parts of a split term as the joint fit gives them: the part
/// asked for and the rest of the column, each a value and its standard
/// deviation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Parts {
    /// The given part's parameter and its standard deviation.
    pub part: (f64, f64),
    /// The rest's.
    pub rest: (f64, f64),
}

impl Pool {
    /// The joint fit of `set` with the single free column of term
    /// `set[at]` split into `part` (whitened like the pool's columns, its
    /// rows `row * joints + joint`, before the pool's weights) and the rest
    /// of that column, each with a parameter of free sign and no limit
    /// (`solve`: [`Pool::solve`] or [`Pool::solve_physical`] on the split
    /// pool and its set). `None` when the term has not exactly one free
    /// column, the pool keeps no rows, `part` is not of them, or either
    /// part is not determined in the fit (it lies in the span of the
    /// others: no spread).
    pub fn split_off(
        &self,
        set: &[usize],
        at: usize,
        part: &[f64],
        solve: impl Fn(&Pool, &[usize]) -> Solution,
    ) -> Option<Parts> {
        let joints = self.weights.len();
        let n = self.x.nrows();
        let split = &self.terms[*set.get(at)?];
        let [col] = split.cols[..] else {
            return None;
        };
        if n == 0 || joints == 0 || part.len() != n {
            return None;
        }
        // The other terms' columns, renumbered in order, then the two parts.
        let mut cols: Vec<usize> = Vec::new();
        let mut terms = Vec::new();
        for (i, &t) in set.iter().enumerate() {
            if i == at {
                continue;
            }
            let mut term = self.terms[t].clone();
            let mut renumber = |c: usize| {
                cols.push(c);
                cols.len() - 1
            };
            term.cols = term.cols.iter().map(|&c| renumber(c)).collect();
            term.fixed = term.fixed.map(renumber);
            terms.push(term);
        }
        let kept = cols.len();
        let mut x = self.x.subset(&cols);
        let whole = self.x.column(col);
        let mut part_col = vec![0.0; n];
        let mut rest_col = vec![0.0; n];
        for r in 0..n {
            let a = part[r] * self.weights[r % joints];
            let a = if a.is_finite() { a } else { 0.0 };
            part_col[r] = a;
            rest_col[r] = whole[r] - a;
        }
        drop(whole);
        x.push(part_col);
        x.push(rest_col);
        for c in [kept, kept + 1] {
            let mut term = split.clone();
            term.cols = vec![c];
            term.lower = vec![f64::NEG_INFINITY];
            term.limit = vec![f64::INFINITY];
            term.k = 1;
            terms.push(term);
        }
        // The prior over the kept columns (none on the parts).
        let sub = |m: &DMatrix<f64>| {
            if m.nrows() != self.gram.nrows() {
                return DMatrix::zeros(0, 0);
            }
            DMatrix::from_fn(kept + 2, kept + 2, |r, c| {
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
        let gram = penalised(&x, &prior, self.yy, self.strength);
        let xty = x.tr_mul(self.y.as_slice(), 0, n);
        let count = terms.len();
        let pool = Pool {
            x,
            y: self.y.clone(),
            gram,
            xty,
            yy: self.yy,
            terms,
            weights: self.weights.clone(),
            prior,
            strength: self.strength,
            blocks: Blocks::default(),
        };
        let all: Vec<usize> = (0..count).collect();
        let sol = solve(&pool, &all);
        let value = |t: usize| -> Option<(f64, f64)> {
            let (v, s) = (*sol.theta.get(t)?.first()?, *sol.std.get(t)?.first()?);
            (v.is_finite() && s.is_finite() && s > 0.0).then_some((v, s))
        };
        Some(Parts {
            part: value(count - 2)?,
            rest: value(count - 1)?,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::super::{test_pool, test_term};
    use crate::diagnose::candidates::Candidate;
    use nalgebra::{DMatrix, DVector};

    /// Two joints; a friction-like column `f` at joint 0, a delay column
    /// `a + b` (its model part `a`, the rest `b`); the residual `y` from
    /// the given lags of the two parts and a friction coefficient.
    fn fit(lag_a: f64, lag_b: f64) -> super::Parts {
        let rows = 400;
        let n = rows * 2;
        let a: Vec<f64> = (0..n)
            .map(|i| ((i / 2) as f64 * 0.031).sin() * (1.0 + (i % 2) as f64))
            .collect();
        let b: Vec<f64> = (0..n)
            .map(|i| {
                if i % 2 == 0 {
                    ((i / 2) as f64 * 0.11).cos().signum() * 0.3
                } else {
                    0.0
                }
            })
            .collect();
        let f: Vec<f64> = (0..n)
            .map(|i| {
                if i % 2 == 0 {
                    ((i / 2) as f64 * 0.017).sin()
                } else {
                    0.0
                }
            })
            .collect();
        let mut rng = crate::synth::Rng::new(3);
        let y: Vec<f64> = (0..n)
            .map(|i| lag_a * a[i] + lag_b * b[i] + 0.8 * f[i] + 1e-3 * rng.normal())
            .collect();
        let x = DMatrix::from_fn(n, 2, |r, c| if c == 0 { f[r] } else { a[r] + b[r] });
        let terms = vec![
            test_term(Candidate::Viscous(0), vec![0], vec![true], None),
            test_term(Candidate::TimeDelay, vec![1], vec![true], None),
        ];
        let pool = test_pool(x, DVector::from_vec(y), terms, 2);
        pool.split_off(&[0, 1], 1, &a, |p, s| p.solve(s))
            .expect("a split")
    }

    #[test]
    fn a_split_gives_each_part_its_own_lag() {
        let late = fit(0.02, 0.02);
        assert!((late.part.0 - 0.02).abs() < 1e-3, "{late:?}");
        assert!((late.rest.0 - 0.02).abs() < 1e-3, "{late:?}");
        let rest_alone = fit(0.0, 0.02);
        assert!(rest_alone.part.0.abs() < 1e-3, "{rest_alone:?}");
        assert!((rest_alone.rest.0 - 0.02).abs() < 1e-3, "{rest_alone:?}");
        // The other way round, and of the other sign: the split is free.
        let other = fit(-0.01, 0.0);
        assert!((other.part.0 + 0.01).abs() < 1e-3, "{other:?}");
        assert!(other.part.1 > 0.0 && other.rest.1 > 0.0);
    }

    #[test]
    fn a_part_the_others_span_gives_no_split() {
        let rows = 50;
        let c: Vec<f64> = (0..rows).map(|i| (i as f64 * 0.3).sin()).collect();
        let y = DVector::from_fn(rows, |r, _| 0.5 * c[r]);
        let x = DMatrix::from_fn(rows, 1, |r, _| c[r]);
        let terms = vec![test_term(Candidate::TimeDelay, vec![0], vec![true], None)];
        let pool = test_pool(x, y, terms, 1);
        // The part is the whole column: the rest is zero, undetermined.
        assert_eq!(pool.split_off(&[0], 0, &c, |p, s| p.solve(s)), None);
        // A part of the wrong length, a term that is not in the set.
        assert_eq!(pool.split_off(&[0], 0, &c[1..], |p, s| p.solve(s)), None);
        assert_eq!(pool.split_off(&[0], 1, &c, |p, s| p.solve(s)), None);
    }
}
