//! The pool of candidate terms of a compound explanation, as whitened
//! regressor columns over the fit's rows, and joint least-squares fits of
//! any subset of them through one Gram matrix.
//!
//! An effect linear in its parameters is one or two free columns. A
//! motor-side effect (elasticity, backlash, the stiff-rotor variant of
//! armature) is a fixed column: what its simulation changes in the
//! residual (measured minus transmitted effort at its joint), coefficient
//! 1, searched again with the other effects' effort removed once chosen
//! (`compound.rs`). Every subset is then solved from the Gram matrix
//! `X^T X`, `X^T y` and `y^T y` built once, without touching the rows
//! again.

use nalgebra::{DMatrix, DVector, SVector};

use super::analysis::{Fit, Prepared};
use super::candidate::Candidate;
use super::links::{combined, link_basis, LinkBasis};
use super::prior;

/// One term of the pool: a fitted single candidate and its columns.
#[derive(Debug, Clone)]
pub struct Term {
    /// The candidate's single fit (its motor-side parameters for a fixed
    /// term).
    pub fit: Fit,
    /// Free columns (linear parameters), indices into the pool.
    pub cols: Vec<usize>,
    /// Which free columns must stay >= 0.
    pub nonneg: Vec<bool>,
    /// Per free column, the largest magnitude its parameter may take
    /// (infinite: none; an effort scale's [`EFFORT_SCALE_LIMIT`]).
    pub limit: Vec<f64>,
    /// The fixed column of a motor-side term.
    pub fixed: Option<usize>,
    /// Parameters counted by the information criterion.
    pub k: usize,
    /// A link correction's determined combinations.
    pub link: Option<LinkBasis>,
}

impl Term {
    /// Exclusive family: at most one term of a family per place (Coulomb
    /// and Stribeck; armature, elasticity and backlash; the grid variants
    /// of one kind).
    pub fn family(&self) -> (u8, Option<usize>) {
        let c = self.fit.candidate;
        let f = match c {
            Candidate::Coulomb(_) | Candidate::Stribeck(..) => 0,
            Candidate::Armature(_) | Candidate::Elasticity(_) | Candidate::Backlash(_) => 1,
            Candidate::Viscous(_) => 2,
            Candidate::Payload => 3,
            Candidate::Environment(_) => 4,
            Candidate::EncoderOffset(_) => 5,
            Candidate::TimeDelay | Candidate::LatePositions | Candidate::LateEffort(_) => 6,
            Candidate::EffortScale(_) => 7,
            Candidate::EffortOffset(_) => 8,
            Candidate::Inertial(l) => return (9, Some(l)),
        };
        (f, c.joint())
    }
}

/// Whitened columns, the Gram matrix and the terms.
#[derive(Debug, Clone)]
pub struct Pool {
    /// Columns (rows x joints, whitened by the noise floor).
    pub x: DMatrix<f64>,
    /// The whitened residual.
    pub y: DVector<f64>,
    /// `X^T X`.
    pub gram: DMatrix<f64>,
    /// `X^T y`.
    pub xty: DVector<f64>,
    /// `y^T y`.
    pub yy: f64,
    /// The terms.
    pub terms: Vec<Term>,
    /// Per joint, the weight of its rows on top of the whitening by the
    /// noise floor (1: the floor alone; `reweight`).
    pub weights: Vec<f64>,
    /// The prior toward the nominal model (`prior.rs`): `theta^T P theta`
    /// over the free columns, in parameter units, added to the Gram matrix
    /// times [`prior::weight`] (0 x 0: none).
    pub prior: DMatrix<f64>,
}

/// A joint fit of a subset of terms.
#[derive(Debug, Clone)]
pub struct Solution {
    /// Per term of the subset (in its order), its free parameters.
    pub theta: Vec<Vec<f64>>,
    /// Their standard deviations.
    pub std: Vec<Vec<f64>>,
    /// Whitened residual sum of squares.
    pub sse: f64,
    /// Parameters counted.
    pub k: usize,
}

/// Whitened column of the rows of `p` from per-sample efforts `f`.
pub fn whitened<const N: usize>(p: &Prepared<N>, f: impl Fn(usize) -> SVector<f64, N>) -> Vec<f64> {
    let mut out = Vec::with_capacity(p.n());
    for &k in &p.rows {
        let v = f(k);
        for j in 0..N {
            let x = v[j] / p.sig.floor[j];
            out.push(if x.is_finite() { x } else { 0.0 });
        }
    }
    out
}

/// The free columns of a linear candidate on the rows of `p`.
pub fn linear_columns<const N: usize>(c: Candidate, p: &Prepared<N>) -> Vec<Vec<f64>> {
    (0..c.linear_parameters().len())
        .map(|i| whitened(p, |k| c.columns(&p.sig, &p.basis, k)[i]))
        .collect()
}

/// The fixed column of a motor-side fit on the rows of `p`: the residual
/// minus the residual it leaves.
pub fn fixed_column<const N: usize>(f: &Fit, p: &Prepared<N>) -> Vec<f64> {
    let after = f.corrected(p);
    whitened(p, |k| p.sig.residual[k] - after[k])
}

impl Pool {
    /// The pool of `fits` on `p` (every single fit, grid variants too) and
    /// of the link corrections whose whitened regressor columns are `links`
    /// (`[link][parameter]`, see `links.rs`; empty: none), with the prior
    /// toward the links' `nominal` parameters (`prior.rs`; empty: none on
    /// the links).
    pub fn new<const N: usize>(
        fits: &[Fit],
        links: &[Vec<Vec<f64>>],
        nominal: &[SVector<f64, 10>],
        p: &Prepared<N>,
    ) -> Pool {
        let mut cols: Vec<Vec<f64>> = Vec::new();
        let mut terms = Vec::new();
        for f in fits {
            if !f.sse.is_finite() {
                continue;
            }
            let c = f.candidate;
            if f.motor.is_some() {
                let col = fixed_column(f, p);
                if col.iter().all(|x| *x == 0.0) {
                    continue;
                }
                cols.push(col);
                terms.push(Term {
                    fit: f.clone(),
                    cols: vec![],
                    nonneg: vec![],
                    limit: vec![],
                    fixed: Some(cols.len() - 1),
                    k: f.k,
                    link: None,
                });
            } else if !c.linear_parameters().is_empty() {
                let new = linear_columns(c, p);
                if new.iter().all(|c| c.iter().all(|x| *x == 0.0)) {
                    continue;
                }
                let at = cols.len();
                cols.extend(new);
                terms.push(Term {
                    fit: f.clone(),
                    cols: (at..cols.len()).collect(),
                    nonneg: c.linear_parameters().iter().map(|p| p.1).collect(),
                    limit: c
                        .linear_parameters()
                        .iter()
                        .map(|_| match c {
                            Candidate::EffortScale(_) => prior::EFFORT_SCALE_LIMIT,
                            _ => f64::INFINITY,
                        })
                        .collect(),
                    fixed: None,
                    k: f.k,
                    link: None,
                });
            }
        }
        // Link inertial corrections: the combinations the data determine.
        for (l, lc) in links.iter().enumerate() {
            let Some(basis) = link_basis(l, lc) else {
                continue;
            };
            let new = combined(lc, &basis);
            let at = cols.len();
            let r = new.len();
            cols.extend(new);
            terms.push(Term {
                fit: Fit {
                    candidate: Candidate::Inertial(l),
                    theta: vec![],
                    std: vec![],
                    motor: None,
                    motor_std: None,
                    sse: f64::NAN,
                    k: r,
                },
                cols: (at..cols.len()).collect(),
                nonneg: vec![false; r],
                limit: vec![f64::INFINITY; r],
                fixed: None,
                k: r,
                link: Some(basis),
            });
        }
        let n = p.n();
        let x = DMatrix::from_fn(n, cols.len(), |r, c| cols[c][r]);
        let y = DVector::from_vec(whitened(p, |k| p.sig.residual[k]));
        let xty = x.tr_mul(&y);
        let yy = y.norm_squared();
        let prior = prior::matrix(&terms, cols.len(), nominal);
        let gram = penalised(&x, &prior, yy);
        Pool {
            x,
            y,
            gram,
            xty,
            yy,
            terms,
            weights: vec![1.0; N],
            prior,
        }
    }

    /// Weighs the rows of joint `j` by `w[j]` on top of the whitening by
    /// the floor (replacing the weights before): the fitted parameters keep
    /// their units, the residual sums of squares are in the new weights.
    pub fn reweight(&mut self, w: &[f64]) {
        let joints = self.weights.len();
        if w.len() != joints || joints == 0 {
            return;
        }
        let s: Vec<f64> = (0..joints).map(|j| w[j] / self.weights[j]).collect();
        for mut col in self.x.column_iter_mut() {
            for (i, x) in col.iter_mut().enumerate() {
                *x *= s[i % joints];
            }
        }
        for (i, y) in self.y.iter_mut().enumerate() {
            *y *= s[i % joints];
        }
        self.xty = self.x.tr_mul(&self.y);
        self.yy = self.y.norm_squared();
        self.gram = penalised(&self.x, &self.prior, self.yy);
        self.weights = w.to_vec();
    }

    /// Per joint RMS of the residual `r` (of this pool's rows) in units of
    /// the noise floor (the weights taken out).
    pub fn floor_rms(&self, r: &DVector<f64>) -> Vec<f64> {
        let joints = self.weights.len().max(1);
        let rows = (r.len() / joints).max(1);
        (0..joints)
            .map(|j| {
                let ms: f64 = (0..rows).map(|i| r[i * joints + j].powi(2)).sum::<f64>();
                (ms / rows as f64).sqrt() / self.weights[j]
            })
            .collect()
    }

    /// Replaces the fixed column of term `t` (a motor side searched again).
    pub fn set_fixed(&mut self, t: usize, fit: Fit, col: Vec<f64>) {
        let Some(c) = self.terms[t].fixed else { return };
        let joints = self.weights.len().max(1);
        let col: Vec<f64> = col
            .iter()
            .enumerate()
            .map(|(i, x)| x * self.weights.get(i % joints).copied().unwrap_or(1.0))
            .collect();
        self.x.set_column(c, &DVector::from_vec(col));
        let v = self.x.tr_mul(&self.x.column(c));
        self.gram.set_column(c, &v);
        self.gram.set_row(c, &v.transpose());
        self.xty[c] = self.x.column(c).dot(&self.y);
        self.terms[t].fit = fit;
    }

    /// Rows in the fit.
    pub fn n(&self) -> usize {
        self.y.len()
    }

    /// The joint least-squares fit of `set` (term indices), penalised by
    /// the prior toward the nominal model (`prior.rs`); sign constraints
    /// kept by dropping the most negative constrained parameter and solving
    /// again, limits by holding the parameter furthest beyond its limit at
    /// the limit and solving again.
    pub fn solve(&self, set: &[usize]) -> Solution {
        // (set pos, column, nonneg, limit)
        let mut free: Vec<(usize, usize, bool, f64)> = Vec::new();
        let mut fixed: Vec<usize> = Vec::new();
        let mut k = 0;
        for (i, &t) in set.iter().enumerate() {
            let term = &self.terms[t];
            k += term.k;
            for (m, c) in term.cols.iter().enumerate() {
                let nn = term.nonneg.get(m).copied().unwrap_or(false);
                let lim = term.limit.get(m).copied().unwrap_or(f64::INFINITY);
                free.push((i, *c, nn, lim));
            }
            fixed.extend(term.fixed);
        }
        // y' = y - sum of the fixed columns.
        let mut yy0 = self.yy;
        for &f in &fixed {
            yy0 -= 2.0 * self.xty[f];
            for &g in &fixed {
                yy0 += self.gram[(f, g)];
            }
        }
        let b0: Vec<f64> = free
            .iter()
            .map(|&(_, c, ..)| self.xty[c] - fixed.iter().map(|&f| self.gram[(c, f)]).sum::<f64>())
            .collect();
        // Columns that a column before them in the set's order already
        // spans are left out: two links' inertial parameters regroup (a
        // link's mass is partly its parent's), and a term added after such
        // a pair keeps its own columns.
        let cols: Vec<usize> = free.iter().map(|f| f.1).collect();
        let mut active = independent(&self.gram, &cols);
        let dependent = active.iter().filter(|a| !**a).count();
        k = k.saturating_sub(dependent);
        // Parameters held at a limit: (free index, value).
        let mut held: Vec<(usize, f64)> = Vec::new();
        let (theta, std, sse) = loop {
            // y'' = y' - the held columns times their values.
            let mut yy = yy0;
            for &(i, v) in &held {
                yy -= 2.0 * v * b0[i];
                for &(j, w) in &held {
                    yy += v * w * self.gram[(free[i].1, free[j].1)];
                }
            }
            let b: Vec<f64> = (0..free.len())
                .map(|i| {
                    b0[i]
                        - held
                            .iter()
                            .map(|&(j, v)| v * self.gram[(free[i].1, free[j].1)])
                            .sum::<f64>()
                })
                .collect();
            let idx: Vec<usize> = (0..free.len()).filter(|&i| active[i]).collect();
            let m = idx.len();
            if m == 0 {
                let at: Vec<(usize, f64)> = held.clone();
                let zero = held.iter().map(|&(i, _)| (i, 0.0)).collect();
                break (at, zero, yy.max(0.0));
            }
            let d: Vec<f64> = idx
                .iter()
                .map(|&i| self.gram[(free[i].1, free[i].1)].sqrt())
                .collect();
            let g = DMatrix::from_fn(m, m, |r, c| {
                self.gram[(free[idx[r]].1, free[idx[c]].1)] / (d[r] * d[c])
            });
            let bv = DVector::from_fn(m, |r, _| b[idx[r]] / d[r]);
            let Some(ch) = g.clone().cholesky() else {
                active[idx[m - 1]] = false;
                continue;
            };
            let z = ch.solve(&bv);
            let worst = idx
                .iter()
                .zip(z.iter())
                .filter(|(&i, &v)| free[i].2 && v < 0.0)
                .min_by(|a, b| a.1.total_cmp(b.1))
                .map(|(&i, _)| i);
            if let Some(i) = worst {
                active[i] = false;
                continue;
            }
            // The parameter furthest beyond its limit (relative to it).
            let beyond = idx
                .iter()
                .enumerate()
                .map(|(r, &i)| (i, z[r] / d[r], free[i].3))
                .filter(|&(_, v, lim)| v.abs() > lim)
                .max_by(|a, b| (a.1.abs() / a.2).total_cmp(&(b.1.abs() / b.2)))
                .map(|(i, v, lim)| (i, lim.copysign(v)));
            if let Some((i, v)) = beyond {
                active[i] = false;
                held.push((i, v));
                continue;
            }
            let sse = (yy - 2.0 * z.dot(&bv) + (g * &z).dot(&z)).max(1e-12 * self.yy.max(1e-300));
            let dof = (self.n() as f64 - m as f64).max(1.0);
            let inv = ch.inverse();
            let mut theta: Vec<(usize, f64, f64)> = (0..m)
                .map(|r| {
                    let s = (inv[(r, r)] * sse / dof).max(0.0).sqrt() / d[r];
                    (idx[r], z[r] / d[r], s)
                })
                .collect();
            theta.extend(held.iter().map(|&(i, v)| (i, v, 0.0)));
            break (
                theta.iter().map(|t| (t.0, t.1)).collect::<Vec<_>>(),
                theta.iter().map(|t| (t.0, t.2)).collect::<Vec<_>>(),
                sse,
            );
        };
        let mut th: Vec<Vec<f64>> = set
            .iter()
            .map(|&t| vec![0.0; self.terms[t].cols.len()])
            .collect();
        let mut sd = th.clone();
        let mut pos = vec![0usize; set.len()];
        for (i, &(s, ..)) in free.iter().enumerate() {
            let at = pos[s];
            pos[s] += 1;
            if let Some(v) = theta.iter().find(|t| t.0 == i) {
                th[s][at] = v.1;
            }
            if let Some(v) = std.iter().find(|t| t.0 == i) {
                sd[s][at] = v.1;
            }
        }
        Solution {
            theta: th,
            std: sd,
            sse: if sse.is_finite() { sse } else { f64::INFINITY },
            k,
        }
    }

    /// The whitened residual left by `set` with parameters `sol`.
    pub fn residual(&self, set: &[usize], sol: &Solution) -> DVector<f64> {
        let mut r = self.y.clone();
        for (i, &t) in set.iter().enumerate() {
            let term = &self.terms[t];
            for (c, th) in term.cols.iter().zip(&sol.theta[i]) {
                r.axpy(-th, &self.x.column(*c), 1.0);
            }
            if let Some(f) = term.fixed {
                r -= self.x.column(f);
            }
        }
        r
    }
}

/// `X^T X` plus the prior's matrix at its weight for a residual of sum of
/// squares `yy` (`prior.rs`).
pub(super) fn penalised(x: &DMatrix<f64>, p: &DMatrix<f64>, yy: f64) -> DMatrix<f64> {
    let mut g = x.tr_mul(x);
    if p.shape() == g.shape() {
        g += p * prior::weight(yy, x.nrows());
    }
    g
}

/// Relative size, in a column's own norm, of the part outside the span of
/// the columns before it below which it counts as dependent.
const DEPENDENT: f64 = 1e-8;

/// Which of `cols` (indices into `gram`, in order) are independent of
/// those kept before them: an incremental Cholesky factorisation of the
/// unit-scaled Gram matrix, skipping a column whose pivot is under
/// [`DEPENDENT`] (a zero column is dependent).
pub(super) fn independent(gram: &DMatrix<f64>, cols: &[usize]) -> Vec<bool> {
    let m = cols.len();
    let d: Vec<f64> = cols.iter().map(|&c| gram[(c, c)].max(0.0).sqrt()).collect();
    let mut l = DMatrix::<f64>::zeros(m, m);
    let mut keep = vec![false; m];
    for i in 0..m {
        if !(d[i] > 0.0 && d[i].is_finite()) {
            continue;
        }
        for j in 0..i {
            if !keep[j] {
                continue;
            }
            let mut v = gram[(cols[i], cols[j])] / (d[i] * d[j]);
            for p in 0..j {
                v -= l[(i, p)] * l[(j, p)];
            }
            l[(i, j)] = v / l[(j, j)];
        }
        let pivot = 1.0 - (0..i).map(|p| l[(i, p)].powi(2)).sum::<f64>();
        if pivot > DEPENDENT {
            l[(i, i)] = pivot.sqrt();
            keep[i] = true;
        } else {
            for p in 0..i {
                l[(i, p)] = 0.0;
            }
        }
    }
    keep
}

/// A term of `cols` for unit tests (`nonneg`: which are held >= 0;
/// `fixed`: a column of its own searched fit).
#[cfg(test)]
pub(crate) fn test_term(
    c: Candidate,
    cols: Vec<usize>,
    nonneg: Vec<bool>,
    fixed: Option<usize>,
) -> Term {
    let k = cols.len().max(fixed.map_or(0, |_| 3));
    Term {
        fit: Fit {
            candidate: c,
            theta: vec![],
            std: vec![],
            motor: None,
            motor_std: None,
            sse: 0.0,
            k,
        },
        limit: vec![f64::INFINITY; cols.len()],
        cols,
        nonneg,
        fixed,
        k,
        link: None,
    }
}

#[cfg(test)]
mod tests {
    use super::test_term as term;
    use super::*;
    use crate::diagnose::fit::constrained_least_squares;

    /// The Gram route against a direct least-squares fit of the same
    /// columns, with a fixed column subtracted and a sign constraint that
    /// becomes active.
    #[test]
    fn joint_fits_from_the_gram_match_direct_least_squares() {
        let n = 300;
        let c0: Vec<f64> = (0..n).map(|i| (i as f64 * 0.05).sin()).collect();
        let c1: Vec<f64> = (0..n).map(|i| (i as f64 * 0.013).cos()).collect();
        let c2: Vec<f64> = (0..n).map(|i| ((i % 7) as f64 - 3.0) * 0.1).collect();
        let fixed: Vec<f64> = (0..n).map(|i| 0.3 * (i as f64 * 0.2).sin()).collect();
        let mut rng = crate::synth::Rng::new(5);
        // y = 2 c0 - 0.7 c1 + 1.5 c2 + fixed + noise.
        let y: Vec<f64> = (0..n)
            .map(|i| 2.0 * c0[i] - 0.7 * c1[i] + 1.5 * c2[i] + fixed[i] + 0.01 * rng.normal())
            .collect();
        let cols = [c0.clone(), c1.clone(), c2.clone(), fixed.clone()];
        let x = DMatrix::from_fn(n, 4, |r, c| cols[c][r]);
        let yv = DVector::from_vec(y.clone());
        let pool = Pool {
            gram: x.tr_mul(&x),
            xty: x.tr_mul(&yv),
            yy: yv.norm_squared(),
            x,
            y: yv.clone(),
            weights: vec![1.0],
            prior: DMatrix::zeros(0, 0),
            terms: vec![
                term(Candidate::Coulomb(0), vec![0], vec![true], None),
                term(Candidate::Viscous(0), vec![1], vec![true], None),
                term(Candidate::EffortOffset(0), vec![2], vec![false], None),
                term(Candidate::Elasticity(1), vec![], vec![], Some(3)),
            ],
        };
        // All four: the viscous coefficient wants -0.7, is held at 0.
        let sol = pool.solve(&[0, 1, 2, 3]);
        let y_minus_fixed = DVector::from_fn(n, |r, _| y[r] - fixed[r]);
        let direct = constrained_least_squares(
            &DMatrix::from_fn(n, 3, |r, c| cols[c][r]),
            &y_minus_fixed,
            &[true, true, false],
        );
        assert_eq!(sol.theta[1][0], 0.0);
        for (t, d) in [(0, 0), (2, 2)] {
            assert!((sol.theta[t][0] - direct.theta[d]).abs() < 1e-9, "{t}");
            assert!((sol.std[t][0] / direct.std[d] - 1.0).abs() < 1e-6);
        }
        assert!((sol.sse / direct.sse - 1.0).abs() < 1e-9);
        assert_eq!(sol.k, 1 + 1 + 1 + 3);
        // The residual it leaves is the direct one.
        let r = pool.residual(&[0, 1, 2, 3], &sol);
        assert!((r.norm_squared() / direct.sse - 1.0).abs() < 1e-9);
        // Without the fixed column the fit is worse.
        assert!(pool.solve(&[0, 1, 2]).sse > sol.sse + 1.0);
    }

    /// A term whose column a term before it already spans is left out of
    /// the fit and of the parameter count, and a term after the pair is
    /// still fitted (not dropped as the last column of a singular set).
    #[test]
    fn a_dependent_column_does_not_hide_the_terms_after_it() {
        let n = 200;
        let c0: Vec<f64> = (0..n).map(|i| (i as f64 * 0.05).sin()).collect();
        let c1: Vec<f64> = (0..n).map(|i| (i as f64 * 0.011).cos()).collect();
        let y: Vec<f64> = (0..n).map(|i| 2.0 * c0[i] + 0.5 * c1[i]).collect();
        // Column 1 repeats column 0 (a regrouped link parameter).
        let cols = [c0.clone(), c0.clone(), c1.clone()];
        let x = DMatrix::from_fn(n, 3, |r, c| cols[c][r]);
        let yv = DVector::from_vec(y);
        let pool = Pool {
            gram: x.tr_mul(&x),
            xty: x.tr_mul(&yv),
            yy: yv.norm_squared(),
            x,
            y: yv,
            weights: vec![1.0],
            prior: DMatrix::zeros(0, 0),
            terms: vec![
                term(Candidate::EffortOffset(0), vec![0], vec![false], None),
                term(Candidate::EffortOffset(1), vec![1], vec![false], None),
                term(Candidate::EffortOffset(2), vec![2], vec![false], None),
            ],
        };
        let sol = pool.solve(&[0, 1, 2]);
        assert!((sol.theta[0][0] - 2.0).abs() < 1e-9, "{:?}", sol.theta);
        assert_eq!(sol.theta[1][0], 0.0);
        assert!((sol.theta[2][0] - 0.5).abs() < 1e-9, "{:?}", sol.theta);
        assert!(sol.sse < 1e-9);
        assert_eq!(sol.k, 2);
    }

    /// Reweighting two joints' rows keeps the residual in floor units,
    /// leaves an exact fit's parameter where it is, and moves a fit that
    /// must compromise between the joints toward the heavier one, as a
    /// direct weighted least-squares fit does.
    #[test]
    fn reweighting_the_joints_rows_is_weighted_least_squares() {
        let rows = 200;
        // Rows interleaved: joint 0, joint 1, joint 0, ...
        let c0: Vec<f64> = (0..2 * rows)
            .map(|i| ((i / 2) as f64 * 0.07).sin())
            .collect();
        // Joint 0 wants 2, joint 1 wants 3.
        let y: Vec<f64> = (0..2 * rows)
            .map(|i| if i % 2 == 0 { 2.0 } else { 3.0 } * c0[i])
            .collect();
        let x = DMatrix::from_column_slice(2 * rows, 1, &c0);
        let yv = DVector::from_vec(y.clone());
        let mut pool = Pool {
            gram: x.tr_mul(&x),
            xty: x.tr_mul(&yv),
            yy: yv.norm_squared(),
            x,
            y: yv,
            weights: vec![1.0, 1.0],
            prior: DMatrix::zeros(0, 0),
            terms: vec![term(Candidate::EffortScale(0), vec![0], vec![false], None)],
        };
        let even = pool.solve(&[0]);
        assert!((even.theta[0][0] - 2.5).abs() < 1e-9, "{:?}", even.theta);
        let before = pool.floor_rms(&pool.residual(&[0], &even));
        pool.reweight(&[1.0, 0.1]);
        // The same parameters leave the same residual in floor units.
        let again = pool.floor_rms(&pool.residual(&[0], &even));
        for j in 0..2 {
            assert!((again[j] / before[j] - 1.0).abs() < 1e-12);
        }
        // Weighted least squares: (2 * 1 + 3 * 0.01) / 1.01.
        let heavy = pool.solve(&[0]);
        assert!(
            (heavy.theta[0][0] - 2.03 / 1.01).abs() < 1e-9,
            "{:?}",
            heavy.theta
        );
        // Back to even weights: the even fit again.
        pool.reweight(&[1.0, 1.0]);
        assert!((pool.solve(&[0]).theta[0][0] - 2.5).abs() < 1e-9);
    }
}
