//! `A = L D L^T` over lanes: the operations of the scalar factorisation
//! (`linearize/ldlt.rs`) in the same order, so each lane's result is the
//! scalar one; a lane whose pivot is not positive is reported, not
//! stopped at (the other lanes go on).

use crate::lanes::{mul_add, Lanes};

/// The factors of `WIDTH` matrices, and whether each was positive definite.
pub(crate) struct Ldlt<L, const N: usize> {
    /// Strictly lower part of `L` (`l[i][j]`, `j < i`).
    l: [[L; N]; N],
    /// `1 / D`.
    inv_d: [L; N],
}

impl<L: Lanes, const N: usize> Ldlt<L, N> {
    /// Factors `a` (column-major, `a[column][row]`, its lower triangle
    /// read) lane by lane; the
    /// lanes whose every pivot is positive and finite are marked in the
    /// returned mask (bit `i` for lane `i`).
    #[inline(always)]
    pub(crate) fn new(a: &[[L; N]; N]) -> (Self, u32) {
        let zero = L::splat(0.0);
        // `s[k][i]` holds entry (i, k): column k, as `a` is laid out.
        let mut s: [[L; N]; N] = *a;
        let mut l = [[zero; N]; N];
        let mut inv_d = [zero; N];
        let mut ok = u32::MAX;
        for j in 0..N {
            let dj = s[j][j];
            for lane in 0..L::WIDTH {
                let d = dj.lane(lane);
                if !(d > 0.0 && d < f64::INFINITY) {
                    ok &= !(1 << lane);
                }
            }
            inv_d[j] = L::splat(1.0) / dj;
            let col = s[j];
            for i in j + 1..N {
                l[i][j] = col[i] * inv_d[j];
            }
            for k in j + 1..N {
                let f = l[k][j];
                for i in k..N {
                    s[k][i] = mul_add(-f, col[i], s[k][i]);
                }
            }
        }
        (Self { l, inv_d }, ok)
    }

    /// `s A^-1 x` in place of `x`: the scalar solve's operations on each
    /// entry in its order (there a right-hand side matrix's columns go
    /// together, row by row; each column is this).
    #[inline(always)]
    pub(crate) fn solve_in_place(&self, x: &mut [L; N], s: f64) {
        for i in 0..N {
            for k in 0..i {
                x[i] = mul_add(-self.l[i][k], x[k], x[i]);
            }
        }
        for i in 0..N {
            x[i] = x[i] * (self.inv_d[i] * L::splat(s));
        }
        for i in (0..N).rev() {
            for k in i + 1..N {
                x[i] = mul_add(-self.l[k][i], x[k], x[i]);
            }
        }
    }

    /// `A^-1 b`.
    #[inline(always)]
    pub(crate) fn solve(&self, b: &[L; N]) -> [L; N] {
        let mut x = *b;
        self.solve_in_place(&mut x, 1.0);
        x
    }
}
