//! Least squares on base parameters: the columns the data determine are
//! chosen in order (modified Gram-Schmidt on unit-norm columns: a column is
//! kept when at least `tol` of it lies outside the span of those kept
//! before it), every dropped column is written as a combination of kept
//! ones, and the kept ones are fitted by weighted least squares (QR), with
//! standard deviations inflated for the correlation the smoothing leaves
//! between neighbouring rows.

use nalgebra::{DMatrix, DVector};

/// A weighted least-squares fit on base parameters.
#[derive(Debug, Clone)]
pub struct Solution {
    /// Kept columns, in order.
    pub kept: Vec<usize>,
    /// Per column: the value (0 for a dropped column: its effect is in the
    /// kept ones it is a combination of).
    pub theta: Vec<f64>,
    /// Per column: the standard deviation (`None` for a dropped column).
    pub std: Vec<Option<f64>>,
    /// Dropped columns, each with its combination of kept columns
    /// (`x_dropped = sum coefficient * x_kept`; empty for a zero column).
    pub dropped: Vec<(usize, Vec<(usize, f64)>)>,
}

/// Which columns of `x` to keep (in column order) and which are (nearly)
/// combinations of those before them.
pub fn select(x: &DMatrix<f64>, tol: f64) -> (Vec<usize>, Vec<usize>) {
    let mut basis: Vec<DVector<f64>> = Vec::new();
    let (mut kept, mut dropped) = (Vec::new(), Vec::new());
    for c in 0..x.ncols() {
        let col = x.column(c).into_owned();
        let norm = col.norm();
        if norm == 0.0 || !norm.is_finite() {
            dropped.push(c);
            continue;
        }
        let mut v = col / norm;
        for _ in 0..2 {
            for b in &basis {
                let d = b.dot(&v);
                v.axpy(-d, b, 1.0);
            }
        }
        let rest = v.norm();
        if rest > tol {
            basis.push(v / rest);
            kept.push(c);
        } else {
            dropped.push(c);
        }
    }
    (kept, dropped)
}

/// Fits `y ~ x theta` with row weights `w` on the columns `select` keeps.
/// `vif` multiplies the variances (correlated rows). `None` when nothing
/// is kept or the rows are too few.
pub fn solve(
    x: &DMatrix<f64>,
    y: &DVector<f64>,
    w: &DVector<f64>,
    tol: f64,
    vif: f64,
) -> Option<Solution> {
    let p = x.ncols();
    let xw = DMatrix::from_fn(x.nrows(), p, |r, c| x[(r, c)] * w[r]);
    let yw = y.component_mul(w);
    let (kept, dropped_cols) = select(&xw, tol);
    if kept.is_empty() || xw.nrows() <= kept.len() {
        return None;
    }
    let norms: Vec<f64> = kept.iter().map(|&c| xw.column(c).norm()).collect();
    let xk = DMatrix::from_fn(xw.nrows(), kept.len(), |r, i| xw[(r, kept[i])] / norms[i]);
    let qr = xk.clone().qr();
    let (q, rr) = (qr.q(), qr.r());
    let solve_r = |b: &DVector<f64>| rr.solve_upper_triangular(&(q.transpose() * b));
    let ts = solve_r(&yw)?;
    let resid = &yw - &xk * &ts;
    let dof = (xw.nrows() - kept.len()) as f64;
    let s2 = resid.norm_squared() / dof * vif.max(1.0);
    let rinv = rr.clone().try_inverse()?;
    let mut theta = vec![0.0; p];
    let mut std = vec![None; p];
    for (i, &c) in kept.iter().enumerate() {
        theta[c] = ts[i] / norms[i];
        let var: f64 = rinv.row(i).iter().map(|v| v * v).sum();
        std[c] = Some((var * s2).sqrt() / norms[i]);
    }
    if theta.iter().any(|v| !v.is_finite()) {
        return None;
    }
    let mut dropped = Vec::new();
    for &d in &dropped_cols {
        let col = xw.column(d).into_owned();
        let combo = if col.norm() == 0.0 {
            Vec::new()
        } else {
            // Terms below 1e-3 of the largest (in unit-norm columns) are left out.
            let b = solve_r(&col)?;
            let big = b.amax();
            kept.iter()
                .enumerate()
                .filter(|&(i, _)| b[i].abs() > 1e-3 * big)
                .map(|(i, &c)| (c, b[i] / norms[i]))
                .collect()
        };
        dropped.push((d, combo));
    }
    Some(Solution {
        kept,
        theta,
        std,
        dropped,
    })
}

/// `1 + 2 sum_k rho_k` of a residual series (rows of `r` ordered in
/// time, `n` interleaved joints) over lags up to `lags`: how many times
/// the variance of a mean exceeds the independent-rows value, averaged
/// over the joints.
pub fn variance_inflation(r: &DVector<f64>, n: usize, lags: usize) -> f64 {
    let rows = r.len() / n.max(1);
    let mut total = 0.0;
    for j in 0..n {
        let s: Vec<f64> = (0..rows).map(|k| r[k * n + j]).collect();
        let c0: f64 = s.iter().map(|v| v * v).sum();
        if c0 == 0.0 {
            total += 1.0;
            continue;
        }
        let mut f = 1.0;
        for lag in 1..=lags.min(rows.saturating_sub(1)) {
            let c: f64 = (lag..rows).map(|k| s[k] * s[k - lag]).sum();
            f += 2.0 * c / c0;
        }
        total += f.max(1.0);
    }
    total / n.max(1) as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_duplicated_column_is_dropped_and_written_in_kept_ones() {
        // Columns: a, b, a + 2 b, 0; y = 1 a + 3 b.
        let x = DMatrix::from_fn(50, 4, |r, c| {
            let (a, b) = ((r as f64 * 0.3).sin(), (r as f64 * 0.7).cos());
            [a, b, a + 2.0 * b, 0.0][c]
        });
        let y = DVector::from_fn(50, |r, _| x[(r, 0)] + 3.0 * x[(r, 1)]);
        let w = DVector::repeat(50, 1.0);
        let s = solve(&x, &y, &w, 1e-8, 1.0).unwrap();
        assert_eq!(s.kept, vec![0, 1]);
        assert!((s.theta[0] - 1.0).abs() < 1e-10 && (s.theta[1] - 3.0).abs() < 1e-10);
        assert_eq!(s.std[2], None);
        let (d, combo) = &s.dropped[0];
        assert_eq!(*d, 2);
        assert!((combo[0].1 - 1.0).abs() < 1e-10 && (combo[1].1 - 2.0).abs() < 1e-10);
        assert!(s.dropped[1].1.is_empty());
    }

    #[test]
    fn white_noise_has_no_inflation_and_a_smooth_series_has() {
        let mut x: u64 = 88172645463325252;
        let white = DVector::from_fn(2000, |_, _| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        });
        let slow = DVector::from_fn(2000, |k, _| (k as f64 * 0.01).sin());
        assert!(variance_inflation(&white, 1, 10) < 2.0);
        assert!(variance_inflation(&slow, 1, 10) > 15.0);
    }
}
