//! The joint least-squares fit of a subset of the pool's terms, from the
//! Gram matrix alone: sign constraints, limits, columns a term before
//! them already spans.

use nalgebra::{DMatrix, DVector};

use super::{Pool, Solution};

impl Pool {
    /// The joint least-squares fit of `set` (term indices), penalised by
    /// the prior toward the nominal model (`prior.rs`); lower bounds (a
    /// sign constraint is one at 0) kept by holding the parameter furthest
    /// below its bound at the bound and solving again, limits by holding
    /// the parameter furthest beyond its limit at the limit and solving
    /// again. A parameter held at its lower bound has the spread it would
    /// have if freed (its column added back to the final fit): how firmly
    /// the data hold it there; one held at a limit or preset has none.
    pub fn solve(&self, set: &[usize]) -> Solution {
        self.solve_held(set, &[])
    }

    /// [`Pool::solve`] with the free columns of `preset` (pool column,
    /// value) held at their values (their standard deviations zero).
    pub(super) fn solve_held(&self, set: &[usize], preset: &[(usize, f64)]) -> Solution {
        // (set pos, column, lower bound, limit)
        let mut free: Vec<(usize, usize, f64, f64)> = Vec::new();
        let mut fixed: Vec<usize> = Vec::new();
        let mut k = 0;
        for (i, &t) in set.iter().enumerate() {
            let term = &self.terms[t];
            k += term.k;
            for (m, c) in term.cols.iter().enumerate() {
                let low = term.lower.get(m).copied().unwrap_or(f64::NEG_INFINITY);
                let lim = term.limit.get(m).copied().unwrap_or(f64::INFINITY);
                free.push((i, *c, low, lim));
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
        // Parameters held at a limit or preset: (free index, value).
        let mut held: Vec<(usize, f64)> = Vec::new();
        // Parameters held at their lower bound (free index).
        let mut bound: Vec<usize> = Vec::new();
        for &(c, v) in preset {
            if let Some(i) = free.iter().position(|f| f.1 == c) {
                active[i] = false;
                held.push((i, v));
            }
        }
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
                // Every column held: one at its lower bound, freed alone,
                // has sigma^2 over its own norm as its variance.
                let sigma2 = yy.max(0.0) / (self.n() as f64 - 1.0).max(1.0);
                let mut at: Vec<(usize, f64)> = held.clone();
                let mut spread: Vec<(usize, f64)> = held.iter().map(|&(i, _)| (i, 0.0)).collect();
                for &i in &bound {
                    let own = self.gram[(free[i].1, free[i].1)];
                    let s = if own > 0.0 {
                        (sigma2 / own).sqrt()
                    } else {
                        f64::INFINITY
                    };
                    match spread.iter_mut().find(|t| t.0 == i) {
                        Some(t) => t.1 = s,
                        None => {
                            at.push((i, 0.0));
                            spread.push((i, s));
                        }
                    }
                }
                break (at, spread, yy.max(0.0));
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
            // The parameter furthest below its bound (in the column's unit
            // scale), held at it.
            let worst = idx
                .iter()
                .enumerate()
                .map(|(r, &i)| (i, (z[r] / d[r] - free[i].2) * d[r]))
                .filter(|&(_, below)| below < 0.0)
                .min_by(|a, b| a.1.total_cmp(&b.1))
                .map(|(i, _)| i);
            if let Some(i) = worst {
                active[i] = false;
                bound.push(i);
                if free[i].2 != 0.0 {
                    held.push((i, free[i].2));
                }
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
            // A column held at its lower bound: the spread it has if
            // freed, sigma^2 over the part of its (unit-scaled) column
            // outside the active ones' span.
            let sigma2 = sse / (dof - 1.0).max(1.0);
            let freed = |i: usize| {
                let c = free[i].1;
                let di = self.gram[(c, c)].sqrt();
                let gv = DVector::from_fn(m, |r, _| self.gram[(c, free[idx[r]].1)] / (di * d[r]));
                let outside = 1.0 - gv.dot(&ch.solve(&gv));
                if outside > DEPENDENT && di > 0.0 {
                    (sigma2 / outside).sqrt() / di
                } else {
                    f64::INFINITY
                }
            };
            theta.extend(held.iter().map(|&(i, v)| (i, v, 0.0)));
            for &i in &bound {
                let s = freed(i);
                match theta.iter_mut().find(|t| t.0 == i) {
                    Some(t) => t.2 = s,
                    None => theta.push((i, 0.0, s)),
                }
            }
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
}

/// Relative size, in a column's own norm, of the part outside the span of
/// the columns before it below which it counts as dependent.
const DEPENDENT: f64 = 1e-8;

/// Which of `cols` (indices into `gram`, in order) are independent of
/// those kept before them: an incremental Cholesky factorisation of the
/// unit-scaled Gram matrix, skipping a column whose pivot is under
/// [`DEPENDENT`] (a zero column is dependent).
pub(in crate::diagnose) fn independent(gram: &DMatrix<f64>, cols: &[usize]) -> Vec<bool> {
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
