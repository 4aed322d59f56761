//! The numerics every stage shares: plain least squares, least squares
//! with sign constraints, and the corrected information criterion.

use nalgebra::{DMatrix, DVector};

/// Plain least squares: the solution of the normal equations of
/// `x theta = y`, if `x^T x` is positive definite.
pub(crate) fn least_squares(x: &DMatrix<f64>, y: &DVector<f64>) -> Option<DVector<f64>> {
    let xtx = x.transpose() * x;
    let xty = x.transpose() * y;
    xtx.cholesky().map(|c| c.solve(&xty))
}

/// A linear fit: parameters, their standard deviations, the residual sum
/// of squares.
#[derive(Debug, Clone)]
pub struct LinearFit {
    /// Parameters (zero where a sign constraint became active).
    pub theta: Vec<f64>,
    /// Standard deviations (from sigma^2 (X^T X)^-1). A parameter held
    /// at zero by its sign constraint has the spread it would have if
    /// freed (its column added back to the final fit): how firmly the data
    /// hold it there.
    pub std: Vec<f64>,
    /// Residual sum of squares.
    pub sse: f64,
}

/// Solves `x theta ~ y` with `theta_i >= 0` where `nonneg[i]`, by dropping
/// columns whose unconstrained value comes out negative (an active-set
/// method that is exact for the one to three columns used here).
pub fn constrained_least_squares(x: &DMatrix<f64>, y: &DVector<f64>, nonneg: &[bool]) -> LinearFit {
    let p = x.ncols();
    let mut active = vec![true; p];
    // Columns held at zero by their sign constraint.
    let mut bound: Vec<usize> = Vec::new();
    loop {
        let cols: Vec<usize> = (0..p).filter(|&i| active[i]).collect();
        let mut theta = vec![0.0; p];
        let mut std = vec![0.0; p];
        if !cols.is_empty() {
            let xa = x.select_columns(&cols);
            if let Some(sol) = least_squares(&xa, y) {
                let worst = cols
                    .iter()
                    .zip(sol.iter())
                    .filter(|(&i, &v)| nonneg[i] && v < 0.0)
                    .min_by(|a, b| a.1.total_cmp(b.1))
                    .map(|(&i, _)| i);
                if let Some(i) = worst {
                    active[i] = false;
                    bound.push(i);
                    continue;
                }
                let r = y - &xa * &sol;
                let sse = r.norm_squared();
                let dof = (y.len() as f64 - cols.len() as f64).max(1.0);
                let cov = (xa.transpose() * &xa).try_inverse();
                for (n, &i) in cols.iter().enumerate() {
                    theta[i] = sol[n];
                    std[i] = cov
                        .as_ref()
                        .map(|c| (c[(n, n)] * sse / dof).max(0.0).sqrt())
                        .unwrap_or(f64::INFINITY);
                }
                // A held column's variance if freed: sigma^2 over the part
                // of its column outside the others' span (the Schur
                // complement of the Gram matrix with it added).
                let sigma2 = sse / (dof - 1.0).max(1.0);
                for &i in &bound {
                    let xi = x.column(i);
                    let g = xa.transpose() * xi;
                    let own = xi.norm_squared();
                    let outside = cov.as_ref().map_or(0.0, |c| own - g.dot(&(c * &g)));
                    std[i] = if outside > 1e-12 * own && outside.is_finite() {
                        (sigma2 / outside).sqrt()
                    } else {
                        f64::INFINITY
                    };
                }
                return LinearFit { theta, std, sse };
            }
            // Singular: drop the last active column.
            if let Some(&last) = cols.last() {
                active[last] = false;
                continue;
            }
        }
        return LinearFit {
            theta,
            std,
            sse: y.norm_squared(),
        };
    }
}

/// Corrected Akaike information criterion of a least-squares fit with `k`
/// parameters on `n` rows.
///
/// ```
/// use dynamics_sim2real::diagnose::aicc;
/// // Halving the error on 1000 rows is worth far more than 2 parameters.
/// assert!(aicc(250.0, 1000, 2) < aicc(1000.0, 1000, 0) - 1000.0);
/// ```
pub fn aicc(sse: f64, n: usize, k: usize) -> f64 {
    let (n, kf) = (n as f64, k as f64);
    let corr = if n - kf - 1.0 > 0.0 {
        2.0 * kf * (kf + 1.0) / (n - kf - 1.0)
    } else {
        f64::INFINITY
    };
    n * (sse.max(1e-300) / n).ln() + 2.0 * kf + corr
}

/// Integrated autocorrelation time, in rows `spacing` samples apart, of
/// white noise through the smoothing filter of weights `w`: `1 + 2 sum
/// rho(l spacing)` over the lags where the filtered noise is correlated,
/// `rho(m) = sum w_i w_(i+m) / sum w^2` (for rows one sample apart,
/// `(sum w)^2 / sum w^2`; 1 for rows a filter width apart).
pub fn correlation_time(w: &[f64], spacing: usize) -> f64 {
    let s2: f64 = w.iter().map(|x| x * x).sum();
    if s2 <= 0.0 || !s2.is_finite() {
        return 1.0;
    }
    let step = spacing.max(1);
    let mut tau = 1.0;
    let mut lag = step;
    while lag < w.len() {
        let c: f64 = w.iter().zip(&w[lag..]).map(|(a, b)| a * b).sum();
        tau += 2.0 * c / s2;
        lag += step;
    }
    tau.max(1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_negative_coefficient_is_clamped_and_refit() {
        // y = 2 a - 0.5 b exactly; b constrained >= 0 must drop out.
        let x = DMatrix::from_fn(
            20,
            2,
            |r, c| if c == 0 { r as f64 } else { (r as f64).sin() },
        );
        let y = DVector::from_fn(20, |r, _| 2.0 * r as f64 - 0.5 * (r as f64).sin());
        let free = constrained_least_squares(&x, &y, &[false, false]);
        assert!((free.theta[1] + 0.5).abs() < 1e-9 && free.sse < 1e-12);
        let fit = constrained_least_squares(&x, &y, &[true, true]);
        assert_eq!(fit.theta[1], 0.0);
        assert!(fit.theta[0] > 1.9 && fit.sse > 0.1);
        // The held parameter's spread is the one it has when freed: the
        // unconstrained fit's, up to the one degree of freedom its residual
        // has more (same sse up to the constrained fit's, by hand below).
        let y2 = DVector::from_fn(20, |r, _| {
            2.0 * r as f64 - 0.5 * (r as f64).sin() + 0.1 * ((7 * r) as f64).cos()
        });
        let held = constrained_least_squares(&x, &y2, &[true, true]);
        let freed = constrained_least_squares(&x, &y2, &[false, false]);
        assert_eq!(held.theta[1], 0.0);
        assert!(freed.theta[1] < 0.0);
        // sigma^2 of the held fit (18 degrees of freedom left once the
        // held column counts) over the freed variance's (18) scale.
        let expected = freed.std[1] * (held.sse / freed.sse).sqrt();
        assert!(
            (held.std[1] / expected - 1.0).abs() < 1e-9,
            "{} vs {expected}",
            held.std[1]
        );
    }

    #[test]
    fn a_moving_average_correlates_noise_over_its_length() {
        assert!((correlation_time(&[1.0 / 9.0; 9], 1) - 9.0).abs() < 1e-12);
        assert_eq!(correlation_time(&[1.0], 1), 1.0);
        // Rows 3 apart: rho(3) = 6/9, rho(6) = 3/9; 1 + 2 (6 + 3) / 9 = 3.
        assert!((correlation_time(&[1.0 / 9.0; 9], 3) - 3.0).abs() < 1e-12);
        // Rows a filter width apart are independent.
        assert_eq!(correlation_time(&[1.0 / 9.0; 9], 9), 1.0);
        // Savitzky-Golay smoothing keeps fewer samples apart than its width.
        let sg = crate::smoothing::SavitzkyGolay::new(40, 1e-3);
        let t = correlation_time(sg.weights(0), 1);
        assert!(t > 10.0 && t < 81.0, "{t}");
    }
}
