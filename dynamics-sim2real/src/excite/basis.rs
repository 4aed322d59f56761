//! The trajectory basis: a finite Fourier series per joint about a start
//! pose, periodic, constrained so that it starts and ends every period at
//! rest (zero displacement, velocity and acceleration) at the start pose.
//!
//! `q_j(t) = q0_j + sum_{k=1..H} a_jk sin(k w t) + b_jk cos(k w t)` with
//! `w = 2 pi / period`. Rest at `t = 0` (and so at every multiple of the
//! period) is three linear conditions on each joint's coefficients:
//! `sum_k b_jk = 0` (position), `sum_k k a_jk = 0` (velocity) and
//! `sum_k k^2 b_jk = 0` (acceleration). [`Fourier::to_rest`] projects any
//! coefficients orthogonally onto them, so the search moves freely and the
//! motion stays periodic and smooth across repeated periods (no blending
//! polynomial that would break the periodicity the information matrix of
//! one period relies on).

use std::f64::consts::PI;

use nalgebra::SVector;

use dynamics_runtime::control::Reference;

/// A periodic Fourier motion of every joint.
///
/// ```
/// use dynamics_sim2real::excite::Fourier;
/// let mut f = Fourier::<1>::new([0.3].into(), 4.0, 4);
/// f.sin[0][0] = 0.2;
/// f.cos[1][0] = 0.1;
/// f.to_rest();
/// for t in [0.0, 4.0, 8.0] {
///     let r = f.at(t);
///     assert!((r.q[0] - 0.3).abs() < 1e-12 && r.qd[0].abs() < 1e-12 && r.qdd[0].abs() < 1e-12);
/// }
/// assert!(f.at(1.0).qd[0].abs() > 0.0);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Fourier<const N: usize> {
    /// The start (and end) pose.
    pub q0: SVector<f64, N>,
    /// The period, s.
    pub period: f64,
    /// Sine coefficients: entry `k - 1` holds harmonic `k` of every joint.
    pub sin: Vec<SVector<f64, N>>,
    /// Cosine coefficients, in the same layout.
    pub cos: Vec<SVector<f64, N>>,
}

impl<const N: usize> Fourier<N> {
    /// The motion resting at `q0` (all coefficients zero) with `harmonics`
    /// harmonics of the fundamental `1 / period`.
    ///
    /// ```
    /// use dynamics_sim2real::excite::Fourier;
    /// let f = Fourier::<2>::new(nalgebra::Vector2::zeros(), 5.0, 3);
    /// assert_eq!(f.harmonics(), 3);
    /// assert_eq!(f.at(1.2).q, nalgebra::Vector2::zeros());
    /// ```
    pub fn new(q0: SVector<f64, N>, period: f64, harmonics: usize) -> Self {
        Fourier {
            q0,
            period,
            sin: vec![SVector::zeros(); harmonics],
            cos: vec![SVector::zeros(); harmonics],
        }
    }

    /// The number of harmonics.
    pub fn harmonics(&self) -> usize {
        self.sin.len()
    }

    /// The fundamental angular frequency `2 pi / period`, rad/s.
    pub fn omega(&self) -> f64 {
        2.0 * PI / self.period
    }

    /// Position, velocity and acceleration at time `t`.
    pub fn at(&self, t: f64) -> Reference<N> {
        let w = self.omega();
        let mut r = Reference {
            q: self.q0,
            qd: SVector::zeros(),
            qdd: SVector::zeros(),
        };
        for k in 0..self.harmonics() {
            let kw = (k + 1) as f64 * w;
            let (s, c) = (kw * t).sin_cos();
            let (a, b) = (&self.sin[k], &self.cos[k]);
            r.q += a * s + b * c;
            r.qd += (a * c - b * s) * kw;
            r.qdd -= (a * s + b * c) * (kw * kw);
        }
        r
    }

    /// Projects every joint's coefficients orthogonally onto the three
    /// rest conditions (see the module docs). Needs at least three
    /// harmonics for a motion that is not zero.
    pub fn to_rest(&mut self) {
        let h = self.harmonics();
        if h == 0 {
            return;
        }
        let k: Vec<f64> = (1..=h).map(|k| k as f64).collect();
        let kk: f64 = k.iter().map(|v| v * v).sum();
        // The cosine conditions: rows c1 = 1, c2 = k^2; their Gram matrix.
        let (g11, g12, g22) = (
            h as f64,
            k.iter().map(|v| v * v).sum::<f64>(),
            k.iter().map(|v| v.powi(4)).sum::<f64>(),
        );
        let det = g11 * g22 - g12 * g12;
        for j in 0..N {
            let dot: f64 = (0..h).map(|i| k[i] * self.sin[i][j]).sum();
            for i in 0..h {
                self.sin[i][j] -= dot / kk * k[i];
            }
            let (s1, s2) = (
                (0..h).map(|i| self.cos[i][j]).sum::<f64>(),
                (0..h).map(|i| k[i] * k[i] * self.cos[i][j]).sum::<f64>(),
            );
            if det.abs() > 0.0 {
                let l1 = (g22 * s1 - g12 * s2) / det;
                let l2 = (g11 * s2 - g12 * s1) / det;
                for i in 0..h {
                    self.cos[i][j] -= l1 + l2 * k[i] * k[i];
                }
            } else {
                // One harmonic: only b = 0 meets both conditions.
                for i in 0..h {
                    self.cos[i][j] = 0.0;
                }
            }
        }
    }

    /// Multiplies joint `j`'s coefficients by `s[j]`.
    pub fn scale(&mut self, s: &SVector<f64, N>) {
        for k in 0..self.harmonics() {
            self.sin[k].component_mul_assign(s);
            self.cos[k].component_mul_assign(s);
        }
    }

    /// The coefficients as one flat vector: joint-major, then per harmonic
    /// the sine and the cosine coefficient (what the search moves).
    ///
    /// ```
    /// use dynamics_sim2real::excite::Fourier;
    /// let mut f = Fourier::<2>::new(nalgebra::Vector2::zeros(), 5.0, 3);
    /// f.cos[2][1] = 7.0;
    /// let x = f.flat();
    /// assert_eq!(x[2 * 3 + 2 * 2 + 1], 7.0);
    /// let mut g = Fourier::<2>::new(nalgebra::Vector2::zeros(), 5.0, 3);
    /// g.set_flat(&x);
    /// assert_eq!(f, g);
    /// ```
    pub fn flat(&self) -> Vec<f64> {
        let h = self.harmonics();
        let mut x = vec![0.0; N * 2 * h];
        for j in 0..N {
            for k in 0..h {
                x[j * 2 * h + 2 * k] = self.sin[k][j];
                x[j * 2 * h + 2 * k + 1] = self.cos[k][j];
            }
        }
        x
    }

    /// Sets the coefficients from [`Fourier::flat`]'s layout (entries
    /// missing from a short `x` are left as they are).
    pub fn set_flat(&mut self, x: &[f64]) {
        let h = self.harmonics();
        for j in 0..N {
            for k in 0..h {
                if let Some(&v) = x.get(j * 2 * h + 2 * k) {
                    self.sin[k][j] = v;
                }
                if let Some(&v) = x.get(j * 2 * h + 2 * k + 1) {
                    self.cos[k][j] = v;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn derivatives_match_finite_differences() {
        let mut f = Fourier::<2>::new([0.1, -0.2].into(), 3.0, 5);
        let x: Vec<f64> = (0..20)
            .map(|i| ((i * 7 % 11) as f64 - 5.0) * 0.03)
            .collect();
        f.set_flat(&x);
        for t in [0.1, 1.3, 2.9] {
            let h = 1e-5;
            let (a, b, c) = (f.at(t - h), f.at(t), f.at(t + h));
            assert!(((c.q - a.q) / (2.0 * h) - b.qd).norm() < 1e-7);
            assert!(((c.qd - a.qd) / (2.0 * h) - b.qdd).norm() < 1e-6);
        }
    }

    #[test]
    fn rest_projection_is_a_projection() {
        let mut f = Fourier::<1>::new([0.0].into(), 2.0, 4);
        f.set_flat(&[0.3, -0.1, 0.2, 0.5, -0.4, 0.1, 0.05, 0.2]);
        f.to_rest();
        let once = f.clone();
        f.to_rest();
        for (a, b) in once.flat().iter().zip(f.flat()) {
            assert!((a - b).abs() < 1e-14);
        }
        let r = once.at(0.0);
        assert!(r.q[0].abs() < 1e-14 && r.qd[0].abs() < 1e-14 && r.qdd[0].abs() < 1e-13);
    }
}
