//! Block matrices as heap-allocated dense matrices (needs an allocator: the
//! one part of [`linearize`](super) that does not build without `alloc`).

use nalgebra::DMatrix;

use super::BlockMatrix;

impl<const N: usize, const R: usize, const C: usize> BlockMatrix<N, R, C> {
    /// The whole `(R N) x (C N)` matrix as one dense matrix.
    ///
    /// ```
    /// use dynamics_runtime::linearize::BlockMatrix;
    /// let m = BlockMatrix::<3, 2, 2>::identity().to_dmatrix();
    /// assert_eq!(m, nalgebra::DMatrix::<f64>::identity(6, 6));
    /// ```
    pub fn to_dmatrix(&self) -> DMatrix<f64> {
        DMatrix::from_fn(R * N, C * N, |i, j| self[(i, j)])
    }
}
