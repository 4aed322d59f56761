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

    /// `s A^-1 B` in place of the rows of `B` (`rows[i]` = row `i`).
    #[inline(always)]
    pub(crate) fn solve_rows<const M: usize>(&self, rows: &mut [[L; M]; N], s: f64) {
        for i in 0..N {
            for k in 0..i {
                let (fk, rk) = (self.l[i][k], rows[k]);
                for (x, y) in rows[i].iter_mut().zip(rk) {
                    *x = mul_add(-fk, y, *x);
                }
            }
        }
        for (row, inv_d) in rows.iter_mut().zip(self.inv_d) {
            let f = inv_d * L::splat(s);
            row.iter_mut().for_each(|x| *x = *x * f);
        }
        for i in (0..N).rev() {
            for k in i + 1..N {
                let (fk, rk) = (self.l[k][i], rows[k]);
                for (x, y) in rows[i].iter_mut().zip(rk) {
                    *x = mul_add(-fk, y, *x);
                }
            }
        }
    }

    /// `A^-1 b`.
    #[inline(always)]
    pub(crate) fn solve(&self, b: &[L; N]) -> [L; N] {
        let mut rows: [[L; 1]; N] = core::array::from_fn(|i| [b[i]]);
        self.solve_rows(&mut rows, 1.0);
        core::array::from_fn(|i| rows[i][0])
    }
}
