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

/// Rows of a right-hand side (`rows[i]` = row `i` of the matrix), plain
/// arrays so that a row update is one vector loop.
type Rows<const N: usize, const M: usize> = [[f64; M]; N];

/// `rows[i] -= f(k) * rows[k]` for every `k` in `ks` (`k < i` forward,
/// `k > i` backward).
#[inline(always)]
fn eliminate<const N: usize, const M: usize>(
    rows: &mut Rows<N, M>,
    i: usize,
    ks: core::ops::Range<usize>,
    f: impl Fn(usize) -> f64,
) {
    for k in ks {
        let (fk, rk) = (f(k), rows[k]);
        for (x, y) in rows[i].iter_mut().zip(rk) {
            *x = mul_add(-fk, y, *x);
        }
    }
}

impl<const N: usize> Ldlt<N> {
    /// Factors `a` (reading its lower triangle); `None` unless every pivot
    /// is positive (`a` positive definite) and finite.
    pub(crate) fn new(a: &SMatrix<f64, N, N>) -> Option<Self> {
        // Right-looking: once column j's pivot is known, every later column
        // is updated by independent multiply-adds, so the chain from one
        // pivot to the next is one division, one product and one update.
        // `s[k][i]` holds entry (i, k) of the partly reduced matrix.
        let mut s: [[f64; N]; N] = core::array::from_fn(|k| core::array::from_fn(|i| a[(i, k)]));
        let mut l = SMatrix::<f64, N, N>::zeros();
        let mut inv_d = [0.0; N];
        for j in 0..N {
            let dj = s[j][j];
            // Two float compares (NaN fails both); `is_finite` would move
            // the pivot to an integer register on the critical path.
            if !(dj > 0.0 && dj < f64::INFINITY) {
                return None;
            }
            inv_d[j] = 1.0 / dj;
            let col = s[j];
            for i in j + 1..N {
                l[(i, j)] = col[i] * inv_d[j];
            }
            for k in j + 1..N {
                let f = l[(k, j)];
                for i in k..N {
                    s[k][i] = mul_add(-f, col[i], s[k][i]);
                }
            }
        }
        Some(Self { l, inv_d })
    }

    /// `s A^-1 B` in place of `B`'s rows (`s` rides on the scaling by
    /// `1 / D`).
    fn solve_rows<const M: usize>(&self, rows: &mut Rows<N, M>, s: f64) {
        for i in 0..N {
            eliminate(rows, i, 0..i, |k| self.l[(i, k)]);
        }
        for (row, inv_d) in rows.iter_mut().zip(self.inv_d) {
            let f = inv_d * s;
            row.iter_mut().for_each(|x| *x *= f);
        }
        for i in (0..N).rev() {
            eliminate(rows, i, i + 1..N, |k| self.l[(k, i)]);
        }
    }

    /// `A^-1 b`.
    pub(crate) fn solve(&self, b: &SVector<f64, N>) -> SVector<f64, N> {
        let mut rows: Rows<N, 1> = core::array::from_fn(|i| [b[i]]);
        self.solve_rows(&mut rows, 1.0);
        SVector::from_fn(|i, _| rows[i][0])
    }

    /// `s A^-1 B` for a square `B`.
    pub(crate) fn solve_matrix(&self, b: &SMatrix<f64, N, N>, s: f64) -> SMatrix<f64, N, N> {
        let mut rows: Rows<N, N> = core::array::from_fn(|i| core::array::from_fn(|j| b[(i, j)]));
        self.solve_rows(&mut rows, s);
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
