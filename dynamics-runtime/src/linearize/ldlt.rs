//! `A = L D L^T` of the inertia matrix (unit lower `L`, no square root, so
//! no float function beyond `core`), and solves for many right-hand sides at
//! once: a right-hand side matrix is held row by row, so every step of the
//! substitutions is one fused multiply-add over a whole row (vector lanes
//! across the right-hand sides).

use nalgebra::{SMatrix, SVector};

use crate::fma::mul_add;

/// The factors of a symmetric positive definite matrix.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Ldlt<const N: usize> {
    /// Strictly lower part: `L` (unit diagonal implied).
    l: SMatrix<f64, N, N>,
    /// `1 / D`.
    inv_d: [f64; N],
}

/// Rows of a right-hand side (`rows[i]` = row `i` of the matrix).
type Rows<const N: usize, const M: usize> = [SVector<f64, M>; N];

impl<const N: usize> Ldlt<N> {
    /// Factors `a` (reading its lower triangle); `None` unless every pivot
    /// is positive (`a` positive definite) and finite.
    pub(crate) fn new(a: &SMatrix<f64, N, N>) -> Option<Self> {
        let mut l = SMatrix::<f64, N, N>::zeros();
        let mut d = [0.0; N];
        let mut inv_d = [0.0; N];
        for j in 0..N {
            // w_k = L_jk D_k for k < j.
            let mut w = [0.0; N];
            let mut dj = a[(j, j)];
            for k in 0..j {
                w[k] = l[(j, k)] * d[k];
                dj = mul_add(-w[k], l[(j, k)], dj);
            }
            if !(dj > 0.0 && dj.is_finite()) {
                return None;
            }
            d[j] = dj;
            inv_d[j] = 1.0 / dj;
            for i in j + 1..N {
                let mut s = a[(i, j)];
                for k in 0..j {
                    s = mul_add(-l[(i, k)], w[k], s);
                }
                l[(i, j)] = s * inv_d[j];
            }
        }
        Some(Self { l, inv_d })
    }

    /// `A^-1 B` in place of `B`'s rows.
    pub(crate) fn solve_rows<const M: usize>(&self, rows: &mut Rows<N, M>) {
        for i in 0..N {
            for k in 0..i {
                let (lik, rk) = (self.l[(i, k)], rows[k]);
                rows[i].zip_apply(&rk, |x, y| *x = mul_add(-lik, y, *x));
            }
        }
        for i in 0..N {
            rows[i] *= self.inv_d[i];
        }
        for i in (0..N).rev() {
            for k in i + 1..N {
                let (lki, rk) = (self.l[(k, i)], rows[k]);
                rows[i].zip_apply(&rk, |x, y| *x = mul_add(-lki, y, *x));
            }
        }
    }

    /// `A^-1 b`.
    pub(crate) fn solve(&self, b: &SVector<f64, N>) -> SVector<f64, N> {
        let mut rows: Rows<N, 1> = core::array::from_fn(|i| SVector::<f64, 1>::new(b[i]));
        self.solve_rows(&mut rows);
        SVector::from_fn(|i, _| rows[i][0])
    }

    /// `s A^-1 B` for a square `B`.
    pub(crate) fn solve_matrix(&self, b: &SMatrix<f64, N, N>, s: f64) -> SMatrix<f64, N, N> {
        let mut rows: Rows<N, N> = core::array::from_fn(|i| b.row(i).transpose() * s);
        self.solve_rows(&mut rows);
        SMatrix::from_fn(|i, j| rows[i][j])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Matrix3, Vector3};

    #[test]
    fn solves_agree_with_nalgebra_cholesky() {
        let m = Matrix3::new(2.0, 0.3, -0.4, 0.1, 1.0, 0.2, 0.5, -0.2, 3.0);
        let a = m * m.transpose() + Matrix3::identity();
        let f = Ldlt::new(&a).expect("positive definite");
        let chol = a.cholesky().expect("positive definite");
        let b = Vector3::new(1.0, -2.0, 0.5);
        assert!((f.solve(&b) - chol.solve(&b)).abs().max() < 1e-14);
        assert!(
            (f.solve_matrix(&m, -2.0) - chol.solve(&m) * -2.0)
                .abs()
                .max()
                < 1e-14
        );
    }

    #[test]
    fn indefinite_and_non_finite_matrices_are_refused() {
        assert!(Ldlt::new(&Matrix3::new(1.0, 2.0, 0.0, 2.0, 1.0, 0.0, 0.0, 0.0, 1.0)).is_none());
        assert!(Ldlt::new(&Matrix3::from_diagonal_element(f64::NAN)).is_none());
        assert!(Ldlt::new(&Matrix3::from_diagonal(&Vector3::new(1.0, 0.0, 1.0))).is_none());
    }
}
