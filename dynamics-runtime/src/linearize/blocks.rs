//! Matrices of `R x C` fixed-size `N x N` blocks, on the stack.
//!
//! The state-space matrices of an `N`-joint robot are `2N x 2N` (and the
//! augmented matrix of the zero-order hold `3N x 3N`), which stable Rust
//! cannot write as `SMatrix<f64, {2 * N}, {2 * N}>`. nalgebra's `DimSum`
//! machinery can, but only with `DimAdd` and allocator bounds on every
//! generic function that touches one. A matrix of `N x N` blocks needs no
//! bounds, no heap, and keeps the structure visible: the state-space
//! matrices are naturally blocks (`[[0, I], [ddq_dq, ddq_dv]]`).

use core::ops::{Add, Index, IndexMut, Mul, Sub};

use nalgebra::SMatrix;

/// A `(R N) x (C N)` matrix held as `R x C` blocks of `N x N`:
/// `blocks[r][c]` is rows `r N .. (r + 1) N`, columns `c N .. (c + 1) N`.
/// `m[(i, j)]` indexes the whole matrix.
///
/// ```
/// use dynamics_runtime::linearize::BlockMatrix;
/// use nalgebra::Matrix2;
/// let mut m = BlockMatrix::<2, 2, 2>::zeros();
/// m.blocks[0][1] = Matrix2::identity();
/// assert_eq!(m[(1, 3)], 1.0);
/// assert_eq!((m.nrows(), m.ncols()), (4, 4));
/// assert_eq!((m * m)[(1, 3)], 0.0); // [[0, I], [0, 0]] is nilpotent
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BlockMatrix<const N: usize, const R: usize, const C: usize> {
    /// The blocks, row of blocks by row of blocks.
    pub blocks: [[SMatrix<f64, N, N>; C]; R],
}

impl<const N: usize, const R: usize, const C: usize> BlockMatrix<N, R, C> {
    /// All zeros.
    pub fn zeros() -> Self {
        Self {
            blocks: [[SMatrix::zeros(); C]; R],
        }
    }

    /// Number of rows, `R N`.
    pub const fn nrows(&self) -> usize {
        R * N
    }

    /// Number of columns, `C N`.
    pub const fn ncols(&self) -> usize {
        C * N
    }

    /// Every entry times `s`.
    pub fn scale(&self, s: f64) -> Self {
        let mut out = *self;
        out.blocks.iter_mut().flatten().for_each(|b| *b *= s);
        out
    }

    /// The largest absolute row sum (the norm induced by the max norm).
    pub fn norm_inf(&self) -> f64 {
        (0..R * N)
            .map(|i| (0..C * N).map(|j| self[(i, j)].abs()).sum::<f64>())
            .fold(0.0, f64::max)
    }

    /// Position `(row, column)` of the first entry that is NaN or infinite.
    pub fn first_non_finite(&self) -> Option<(usize, usize)> {
        (0..R * N)
            .flat_map(|i| (0..C * N).map(move |j| (i, j)))
            .find(|&ij| !self[ij].is_finite())
    }
}

impl<const N: usize, const B: usize> BlockMatrix<N, B, B> {
    /// The identity.
    pub fn identity() -> Self {
        let mut m = Self::zeros();
        for i in 0..B {
            m.blocks[i][i] = SMatrix::identity();
        }
        m
    }
}

impl<const N: usize, const R: usize, const C: usize> Index<(usize, usize)>
    for BlockMatrix<N, R, C>
{
    type Output = f64;
    fn index(&self, (i, j): (usize, usize)) -> &f64 {
        &self.blocks[i / N][j / N][(i % N, j % N)]
    }
}

impl<const N: usize, const R: usize, const C: usize> IndexMut<(usize, usize)>
    for BlockMatrix<N, R, C>
{
    fn index_mut(&mut self, (i, j): (usize, usize)) -> &mut f64 {
        &mut self.blocks[i / N][j / N][(i % N, j % N)]
    }
}

impl<const N: usize, const R: usize, const C: usize> Add for BlockMatrix<N, R, C> {
    type Output = Self;
    fn add(mut self, rhs: Self) -> Self {
        for (a, b) in self
            .blocks
            .iter_mut()
            .flatten()
            .zip(rhs.blocks.iter().flatten())
        {
            *a += b;
        }
        self
    }
}

impl<const N: usize, const R: usize, const C: usize> Sub for BlockMatrix<N, R, C> {
    type Output = Self;
    fn sub(mut self, rhs: Self) -> Self {
        for (a, b) in self
            .blocks
            .iter_mut()
            .flatten()
            .zip(rhs.blocks.iter().flatten())
        {
            *a -= b;
        }
        self
    }
}

impl<const N: usize, const R: usize, const K: usize, const C: usize> Mul<BlockMatrix<N, K, C>>
    for BlockMatrix<N, R, K>
{
    type Output = BlockMatrix<N, R, C>;
    fn mul(self, rhs: BlockMatrix<N, K, C>) -> BlockMatrix<N, R, C> {
        let mut out = BlockMatrix::<N, R, C>::zeros();
        for r in 0..R {
            for c in 0..C {
                let acc = &mut out.blocks[r][c];
                for k in 0..K {
                    acc.gemm(1.0, &self.blocks[r][k], &rhs.blocks[k][c], 1.0);
                }
            }
        }
        out
    }
}

/// Solves `a x = b` by Gaussian elimination with partial pivoting, in place
/// of copies (no heap). `None` when a pivot is zero or not finite.
pub(crate) fn solve<const N: usize, const B: usize, const C: usize>(
    mut a: BlockMatrix<N, B, B>,
    mut b: BlockMatrix<N, B, C>,
) -> Option<BlockMatrix<N, B, C>> {
    let n = B * N;
    let m = C * N;
    for k in 0..n {
        let p = (k..n)
            .max_by(|&x, &y| a[(x, k)].abs().total_cmp(&a[(y, k)].abs()))
            .unwrap_or(k);
        let pivot = a[(p, k)];
        if pivot == 0.0 || !pivot.is_finite() {
            return None;
        }
        if p != k {
            for j in 0..n {
                let t = a[(k, j)];
                a[(k, j)] = a[(p, j)];
                a[(p, j)] = t;
            }
            for j in 0..m {
                let t = b[(k, j)];
                b[(k, j)] = b[(p, j)];
                b[(p, j)] = t;
            }
        }
        for i in k + 1..n {
            let f = a[(i, k)] / pivot;
            if f == 0.0 {
                continue;
            }
            for j in k + 1..n {
                a[(i, j)] -= f * a[(k, j)];
            }
            for j in 0..m {
                b[(i, j)] -= f * b[(k, j)];
            }
        }
    }
    for k in (0..n).rev() {
        for j in 0..m {
            let mut s = b[(k, j)];
            for i in k + 1..n {
                s -= a[(k, i)] * b[(i, j)];
            }
            b[(k, j)] = s / a[(k, k)];
        }
    }
    Some(b)
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{DMatrix, Matrix2};

    fn dense<const N: usize, const R: usize, const C: usize>(
        m: &BlockMatrix<N, R, C>,
    ) -> DMatrix<f64> {
        DMatrix::from_fn(R * N, C * N, |i, j| m[(i, j)])
    }

    fn sample<const R: usize, const C: usize>(seed: f64) -> BlockMatrix<2, R, C> {
        let mut m = BlockMatrix::<2, R, C>::zeros();
        for i in 0..2 * R {
            for j in 0..2 * C {
                m[(i, j)] = ((i * 7 + j * 3) as f64 + seed).sin();
            }
        }
        m
    }

    #[test]
    fn products_and_solves_agree_with_dense_matrices() {
        let a = sample::<3, 3>(0.3) + BlockMatrix::identity().scale(3.0);
        let b = sample::<3, 2>(1.1);
        let ab = dense(&(a * b));
        assert!((ab - dense(&a) * dense(&b)).abs().max() < 1e-14);
        let x = solve(a, b).expect("regular");
        let truth = dense(&a).lu().solve(&dense(&b)).expect("regular");
        assert!((dense(&x) - truth).abs().max() < 1e-13);
        assert!((dense(&(a * x)) - dense(&b)).abs().max() < 1e-13);
    }

    #[test]
    fn a_singular_matrix_is_refused() {
        let mut a = BlockMatrix::<2, 2, 2>::zeros();
        a.blocks[0][0] = Matrix2::identity();
        assert!(solve(a, BlockMatrix::<2, 2, 1>::zeros()).is_none());
    }

    #[test]
    fn norm_is_the_largest_row_sum() {
        let mut m = BlockMatrix::<2, 1, 2>::zeros();
        m[(1, 0)] = -2.0;
        m[(1, 3)] = 0.5;
        m[(0, 2)] = 2.4;
        assert_eq!(m.norm_inf(), 2.5);
        assert_eq!(m.first_non_finite(), None);
        m[(1, 2)] = f64::NAN;
        assert_eq!(m.first_non_finite(), Some((1, 2)));
    }
}
