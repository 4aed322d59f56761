//! Savitzky-Golay filtering: local least-squares polynomial fits that
//! smooth a sampled signal and give its derivatives without amplifying
//! noise the way finite differences do. The diagnosis applies the same
//! smoothing to the measured efforts and to every candidate's regressor
//! column, so that both sides of the fit see one filter; the generator
//! measures the size of the effects it withholds through it (what the
//! diagnosis can see of them).

use nalgebra::DMatrix;

/// Smoothing half-width of the diagnosis in seconds. 40 ms (cubic fit over
/// 81 samples at 1 kHz) passes motion and resonances up to about 30 Hz;
/// its derivative amplifies velocity noise into acceleration noise 4.4
/// times less than a 15 ms window, and that noise (times the inertia) is
/// the larger part of the torque residual's floor.
pub const SMOOTHING_HALF_WIDTH: f64 = 0.04;

/// A Savitzky-Golay filter of half-width `m` (window 2m + 1) and order 3.
///
/// ```
/// use dynamics_sim2real::smoothing::SavitzkyGolay;
/// let sg = SavitzkyGolay::new(10, 1e-3);
/// let x: Vec<f64> = (0..100).map(|k| (k as f64 * 1e-3).powi(2)).collect();
/// let d = sg.apply(&x, 1);
/// assert!((d[50] - 2.0 * 0.05).abs() < 1e-9); // d/dt t^2 = 2t, exact for polynomials
/// assert!(d[5].is_nan()); // no full window at the edges
/// ```
#[derive(Debug, Clone)]
pub struct SavitzkyGolay {
    half: usize,
    weights: [Vec<f64>; 3],
}

impl SavitzkyGolay {
    /// The diagnosis's smoothing for samples `dt` apart: half-width
    /// [`SMOOTHING_HALF_WIDTH`] (at least 3 samples).
    ///
    /// ```
    /// use dynamics_sim2real::smoothing::SavitzkyGolay;
    /// assert_eq!(SavitzkyGolay::analysis(1e-3).half(), 40);
    /// assert_eq!(SavitzkyGolay::analysis(1e-2).half(), 4);
    /// ```
    pub fn analysis(dt: f64) -> Self {
        Self::new(((SMOOTHING_HALF_WIDTH / dt).round() as usize).max(3), dt)
    }

    /// A filter of half-width `half` for samples `dt` apart.
    pub fn new(half: usize, dt: f64) -> Self {
        let half = half.max(2);
        let w = 2 * half + 1;
        let order = 3;
        let x = DMatrix::from_fn(w, order + 1, |r, c| (r as f64 - half as f64).powi(c as i32));
        // Rows of (X^T X)^-1 X^T give the polynomial coefficients.
        let pinv = (x.transpose() * &x)
            .try_inverse()
            .map(|inv| inv * x.transpose())
            .unwrap_or_else(|| DMatrix::zeros(order + 1, w));
        let row =
            |d: usize, scale: f64| -> Vec<f64> { (0..w).map(|k| pinv[(d, k)] * scale).collect() };
        SavitzkyGolay {
            half,
            weights: [row(0, 1.0), row(1, 1.0 / dt), row(2, 2.0 / (dt * dt))],
        }
    }

    /// Half-width of the window.
    pub fn half(&self) -> usize {
        self.half
    }

    /// Weights of derivative `d` (0 = smoothing).
    pub fn weights(&self, d: usize) -> &[f64] {
        &self.weights[d.min(2)]
    }

    /// Derivative `d` (0, 1, 2) of `x` at sample `k` alone; NaN where the
    /// window does not fit.
    pub fn at(&self, x: &[f64], d: usize, k: usize) -> f64 {
        if k < self.half || k + self.half >= x.len() {
            return f64::NAN;
        }
        self.weights[d.min(2)]
            .iter()
            .zip(&x[k - self.half..=k + self.half])
            .map(|(a, b)| a * b)
            .sum()
    }

    /// Derivative `d` (0, 1, 2) of joint `j` of the series `x` at sample
    /// `k` alone, as [`SavitzkyGolay::at`] of that joint's values; NaN where
    /// the window does not fit.
    pub(crate) fn at_joint<const N: usize>(
        &self,
        x: &[nalgebra::SVector<f64, N>],
        d: usize,
        k: usize,
        j: usize,
    ) -> f64 {
        if k < self.half || k + self.half >= x.len() {
            return f64::NAN;
        }
        self.weights[d.min(2)]
            .iter()
            .zip(&x[k - self.half..=k + self.half])
            .map(|(a, b)| a * b[j])
            .sum()
    }

    /// Derivative `d` (0, 1, 2) of `x`; NaN where the window does not fit.
    pub fn apply(&self, x: &[f64], d: usize) -> Vec<f64> {
        let w = &self.weights[d.min(2)];
        let n = x.len();
        let mut out = vec![f64::NAN; n];
        if n < w.len() {
            return out;
        }
        for (k, o) in out
            .iter_mut()
            .enumerate()
            .take(n - self.half)
            .skip(self.half)
        {
            *o = w
                .iter()
                .zip(&x[k - self.half..=k + self.half])
                .map(|(a, b)| a * b)
                .sum();
        }
        out
    }
}
