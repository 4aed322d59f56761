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
        if joints == 0 || part.len() != self.x.nrows() {
            return None;
        }
        let weighted = part
            .iter()
            .enumerate()
            .map(|(r, &p)| {
                let a = p * self.weights[r % joints];
                if a.is_finite() {
                    a
                } else {
                    0.0
                }
            })
            .collect();
        self.split_weighted(set, at, weighted, solve)
    }

    /// [`Pool::split_off`] with the part the term's own column at joint
    /// `joint`'s rows (its other joints' rows the rest): what tells an
    /// effect seen at its own joint alone from one that also moves the
    /// other joints' efforts. `None` as for [`Pool::split_off`], or when
    /// `joint` is not one of the pool's.
    pub fn split_at_joint(
        &self,
        set: &[usize],
        at: usize,
        joint: usize,
        solve: impl Fn(&Pool, &[usize]) -> Solution,
    ) -> Option<Parts> {
        let joints = self.weights.len();
        let &[col] = &self.terms[*set.get(at)?].cols[..] else {
            return None;
        };
        if joint >= joints {
            return None;
        }
        let whole = self.x.column(col);
        let part = (0..self.x.nrows())
            .map(|r| if r % joints == joint { whole[r] } else { 0.0 })
            .collect();
        drop(whole);
        self.split_weighted(set, at, part, solve)
    }

    /// [`Pool::split_off`] of a part already in the pool's weights.
    fn split_weighted(
        &self,
        set: &[usize],
        at: usize,
        part_col: Vec<f64>,
        solve: impl Fn(&Pool, &[usize]) -> Solution,
    ) -> Option<Parts> {
        let n = self.x.nrows();
        let split = &self.terms[*set.get(at)?];
        let [col] = split.cols[..] else {
            return None;
        };
        if n == 0 || part_col.len() != n {
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
        let rest_col = (0..n).map(|r| whole[r] - part_col[r]).collect();
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

/// Whether a common delay `common` (> 0) is shown to help a part of the
/// delay's column whose own lag is `lag` (standard deviation `std`): a
/// part of weight `w` fitted with lag `d_p` has its sum of squares lowered
/// by the common delay `d` by `w (d_p^2 - (d_p - d)^2) = w d (2 d_p - d)`,
/// which is positive only for `d_p > d / 2`. Shown: the part's lag above
/// half the common one by more than two standard deviations (the width
/// the within-a-sample rule asks of the delay itself).
pub fn helps(lag: f64, std: f64, common: f64) -> bool {
    lag - 2.0 * std > 0.5 * common
}

/// Whether an effort scale fitted as `common` (the scale minus one) acts
/// on the whole effort, given its column's two parts (the effort beside
/// gravity, and gravity's) fitted apart: the common scale must help every
/// part whose scale the data determine well enough that the test could
/// pass (a spread below a quarter of the common), as [`helps`] asks of a
/// delay's part. A part the data do not determine (gravity about a
/// vertical axis, a joint barely accelerated) tells nothing either way.
pub fn whole_scale(common: f64, parts: &Parts) -> bool {
    let sign = common.signum();
    [parts.part, parts.rest]
        .into_iter()
        .filter(|&(_, std)| std < 0.25 * common.abs())
        .all(|(v, std)| helps(sign * v, std, sign * common))
}

/// The parameters of the two parts of the one-parameter term at position
/// `at` of `set` (a delay's lags, an effort scale's scales; its column
/// split into `part`, whitened over the pool's rows, and the rest;
/// [`Pool::split_off`]), the set refitted by `solve`, their standard
/// deviations times `inflate` (the rows counted as the noise through the
/// smoothing leaves them independent).
pub fn model_lag(
    pool: &Pool,
    set: &[usize],
    at: usize,
    part: &[f64],
    inflate: f64,
    solve: impl Fn(&Pool, &[usize]) -> Solution,
) -> Option<Parts> {
    let parts = pool.split_off(set, at, part, solve)?;
    Some(Parts {
        part: (parts.part.0, parts.part.1 * inflate),
        rest: (parts.rest.0, parts.rest.1 * inflate),
    })
}

#[cfg(test)]
mod tests {
    use super::super::{test_pool, test_term};
    use super::{helps, whole_scale, Parts};
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
            test_term(Candidate::TimeDelay(0.0), vec![1], vec![true], None),
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
        let terms = vec![test_term(
            Candidate::TimeDelay(0.0),
            vec![0],
            vec![true],
            None,
        )];
        let pool = test_pool(x, y, terms, 1);
        // The part is the whole column: the rest is zero, undetermined.
        assert_eq!(pool.split_off(&[0], 0, &c, |p, s| p.solve(s)), None);
        // A part of the wrong length, a term that is not in the set.
        assert_eq!(pool.split_off(&[0], 0, &c[1..], |p, s| p.solve(s)), None);
        assert_eq!(pool.split_off(&[0], 1, &c, |p, s| p.solve(s)), None);
    }

    /// A sensor's gain scales both parts of the effort; a scale of one
    /// part alone is not one. A part the data do not determine (a spread
    /// of a quarter of the common scale or more) does not count.
    #[test]
    fn an_effort_scale_must_act_on_each_part_the_data_determine() {
        let parts = |part: (f64, f64), rest: (f64, f64)| Parts { part, rest };
        // -5 % on both parts, well determined.
        assert!(whole_scale(-0.05, &parts((-0.048, 0.004), (-0.051, 0.002))));
        // The KUKA's lwr_3_joint on record 3: the effort beside gravity
        // -50 %, gravity's -2.8 %, for a common -6.7 %.
        assert!(!whole_scale(
            -0.067,
            &parts((-0.505, 0.020), (-0.0275, 0.0021))
        ));
        // Gravity about a vertical axis: its part undetermined, no verdict.
        assert!(whole_scale(
            -0.17,
            &parts((-0.175, 0.007), (-8.8e13, 5.2e13))
        ));
        // The other sign: +8 %, gravity's part alone at +8 %.
        assert!(!whole_scale(0.08, &parts((0.001, 0.005), (0.08, 0.004))));
    }

    #[test]
    fn a_part_must_lag_more_than_half_the_common_delay() {
        // Half is where the common delay stops helping.
        assert!(helps(0.006, 0.0, 0.01));
        assert!(!helps(0.004, 0.0, 0.01));
        // Above half, but not by two standard deviations: not shown.
        assert!(!helps(0.006, 0.0006, 0.01));
        assert!(helps(0.006, 0.0004, 0.01));
        assert!(!helps(-0.002, 0.001, 0.01));
    }
}
