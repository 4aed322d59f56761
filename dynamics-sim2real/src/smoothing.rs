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
        if x.len() < 2 * self.half + 1 {
            return vec![f64::NAN; x.len()];
        }
        self.run(d, x, 0, x.len(), (0, x.len()))
    }

    /// Derivative `d` (0, 1, 2) of joint `j` of the series `x` at samples
    /// `lo..hi` (indexed from `lo`), each [`SavitzkyGolay::at_joint`] to
    /// the bit; NaN where the window does not fit.
    pub(crate) fn joint_run<const N: usize>(
        &self,
        x: &[nalgebra::SVector<f64, N>],
        d: usize,
        j: usize,
        (lo, hi): (usize, usize),
    ) -> Vec<f64> {
        // The joint's values the windows reach, side by side.
        let base = lo.saturating_sub(self.half).min(x.len());
        let end = (hi + self.half).min(x.len()).max(base);
        let xj: Vec<f64> = x[base..end].iter().map(|v| v[j]).collect();
        self.run(d, &xj, base, x.len(), (lo, hi))
    }

    /// Derivative `d` at samples `lo..hi` of a series of `len` samples
    /// whose samples `base..base + xs.len()` are `xs` (every window that
    /// fits in the series lies in them). Sixteen samples' sums side by
    /// side (the vector unit's lanes), then four, then one, each term by
    /// term in [`SavitzkyGolay::at`]'s order: the same values to the bit,
    /// many chains of dependent additions at a time instead of one; NaN
    /// where the window does not fit.
    fn run(
        &self,
        d: usize,
        xs: &[f64],
        base: usize,
        len: usize,
        (lo, hi): (usize, usize),
    ) -> Vec<f64> {
        const WIDE: usize = 16;
        let w = &self.weights[d.min(2)];
        let h = self.half;
        let fits = |k: usize| k >= h && k + h < len;
        // The window of sample `k`, `extra` samples longer.
        let window = |k: usize, extra: usize| &xs[k - h - base..k - h - base + w.len() + extra];
        // The value a float sum starts from (`Iterator::sum`).
        let start: f64 = std::iter::empty::<f64>().sum();
        let mut out = Vec::with_capacity(hi.saturating_sub(lo));
        let mut k = lo;
        while k < hi {
            if k + WIDE <= hi && fits(k) && fits(k + WIDE - 1) {
                out.extend_from_slice(&side_by_side::<WIDE>(w, window(k, WIDE - 1), start));
                k += WIDE;
            } else if k + 4 <= hi && fits(k) && fits(k + 3) {
                out.extend_from_slice(&side_by_side::<4>(w, window(k, 3), start));
                k += 4;
            } else {
                out.push(if fits(k) {
                    w.iter().zip(window(k, 0)).map(|(a, b)| a * b).sum()
                } else {
                    f64::NAN
                });
                k += 1;
            }
        }
        out
    }
}

/// The filter `w` at `W` consecutive samples whose windows together are
/// `x` (`w.len() + W - 1` values), each sum from `start` term by term in
/// [`SavitzkyGolay::at`]'s order; the `W` sums side by side (the vector
/// unit's lanes).
fn side_by_side<const W: usize>(w: &[f64], x: &[f64], start: f64) -> [f64; W] {
    let mut s = [start; W];
    for (t, a) in w.iter().enumerate() {
        let seg = &x[t..t + W];
        for r in 0..W {
            s[r] += a * seg[r];
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::SVector;

    /// The filter along a stretch, four samples side by side, is the
    /// filter at each sample alone to the bit, at the record's ends too
    /// (NaN where the window does not fit), for every derivative and any
    /// stretch.
    #[test]
    fn a_stretch_is_each_samples_filter_to_the_bit() {
        let sg = SavitzkyGolay::new(6, 1e-3);
        let mut rng = crate::synth::Rng::new(5);
        let x: Vec<SVector<f64, 3>> = (0..97)
            .map(|k| SVector::from_fn(|j, _| (k as f64 * 0.1 + j as f64).sin() + rng.normal()))
            .collect();
        let same = |a: f64, b: f64| a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan());
        for d in 0..3 {
            for j in 0..3 {
                for (lo, hi) in [
                    (0, 97),
                    (3, 17),
                    (5, 6),
                    (50, 97),
                    (0, 0),
                    (7, 60),
                    (6, 91),
                    (30, 47),
                ] {
                    let run = sg.joint_run(&x, d, j, (lo, hi));
                    assert_eq!(run.len(), hi - lo);
                    for (i, v) in run.iter().enumerate() {
                        let one = sg.at_joint(&x, d, lo + i, j);
                        assert!(same(*v, one), "d {d} j {j} k {}: {v} {one}", lo + i);
                    }
                }
                let xj: Vec<f64> = x.iter().map(|v| v[j]).collect();
                for (k, v) in sg.apply(&xj, d).iter().enumerate() {
                    assert!(same(*v, sg.at(&xj, d, k)), "apply d {d} k {k}");
                }
            }
        }
        assert!(sg.apply(&[1.0; 12], 0).iter().all(|v| v.is_nan()));
    }
}
