//! The pool's whitened columns over the fit's scalar rows (`row * joints +
//! joint`). A column that is `+0.0` at every joint but one (a joint's own
//! friction, rotor, motor side, effort scale or offset, spring: some 130
//! of a 7-joint arm's 220 columns) is kept at that joint's rows alone, a
//! seventh of its length; the others whole.
//!
//! Every product the pool forms of them (the Gram matrix of all rows or
//! of a block, `X^T y`, one column against the others, a residual) is
//! nalgebra's on the whole columns to the bit: a dot product sums the
//! products of every eighth scalar row in eight partial sums, adds them as
//! `dot` adds them and then the rows left over in order; a kept column's
//! products land in the partial sum of their scalar row, and the products
//! it leaves out are zeros times finite values, which change no partial
//! sum (a sum starting at `+0.0` is never `-0.0`: adding `±0.0` leaves it
//! as it is). Columns are kept at one joint's rows only while every
//! column of the pool and the residual are finite (whitened columns are:
//! `candidates/columns.rs`); otherwise all are kept whole.

use nalgebra::{DMatrix, DVector};
use rayon::prelude::*;

/// One column: whole (`joint: None`, one value per scalar row) or at the
/// rows of `joint` alone (one value per row).
#[derive(Debug, Clone)]
struct Col {
    joint: Option<usize>,
    v: Vec<f64>,
}

/// The pool's columns.
#[derive(Debug, Clone)]
pub(super) struct Cols {
    /// Scalar rows (rows x joints).
    n: usize,
    /// Joints a row.
    joints: usize,
    cols: Vec<Col>,
    /// Every column kept whole (a value that is not finite was given).
    whole: bool,
}

/// Columns a tile of [`tiled`].
const TILE: usize = 8;

impl Cols {
    /// No columns over `n` scalar rows of `joints` joints each.
    pub fn new(n: usize, joints: usize) -> Cols {
        Cols {
            n,
            joints,
            cols: Vec::new(),
            // One joint: a column at its joint's rows is the whole column.
            whole: joints < 2 || !n.is_multiple_of(joints),
        }
    }

    /// The columns of `x`, over rows of `joints` joints.
    #[cfg(test)]
    pub fn from_matrix(x: &DMatrix<f64>, joints: usize) -> Cols {
        let mut cols = Cols::new(x.nrows(), joints);
        for c in x.column_iter() {
            cols.push(c.iter().copied().collect());
        }
        cols
    }

    /// The whole columns as a matrix.
    #[cfg(test)]
    pub fn to_matrix(&self) -> DMatrix<f64> {
        DMatrix::from_fn(self.n, self.cols.len(), |i, c| self.get(c, i))
    }

    /// Every column kept whole from now on (`from_matrix` of a pool whose
    /// columns stay whole, for the tests).
    pub fn keep_whole(&mut self) {
        if self.whole {
            return;
        }
        for c in 0..self.cols.len() {
            if self.cols[c].joint.is_some() {
                let v = self.column(c);
                self.cols[c] = Col { joint: None, v };
            }
        }
        self.whole = true;
    }

    /// How many values are kept (the memory the columns take, in `f64`s).
    #[cfg(test)]
    pub fn kept(&self) -> usize {
        self.cols.iter().map(|c| c.v.len()).sum()
    }

    /// Scalar rows.
    pub fn nrows(&self) -> usize {
        self.n
    }

    /// Columns.
    pub fn ncols(&self) -> usize {
        self.cols.len()
    }

    /// How `v` (one value per scalar row) is kept.
    fn keep(&mut self, v: Vec<f64>) -> Col {
        debug_assert_eq!(v.len(), self.n);
        if !v.iter().all(|x| x.is_finite()) {
            self.keep_whole();
        }
        if self.whole {
            return Col { joint: None, v };
        }
        let nz = self.joints;
        let j = v
            .iter()
            .position(|x| x.to_bits() != 0)
            .map_or(0, |i| i % nz);
        let local = v
            .iter()
            .enumerate()
            .all(|(i, x)| i % nz == j || x.to_bits() == 0);
        if !local {
            return Col { joint: None, v };
        }
        let v: Vec<f64> = v.iter().skip(j).step_by(nz).copied().collect();
        Col { joint: Some(j), v }
    }

    /// Appends column `v` (one value per scalar row).
    pub fn push(&mut self, v: Vec<f64>) {
        let c = self.keep(v);
        self.cols.push(c);
    }

    /// Replaces column `c` by `v` (one value per scalar row).
    pub fn set(&mut self, c: usize, v: Vec<f64>) {
        self.cols[c] = self.keep(v);
    }

    /// The columns `which`, in that order, over the same rows.
    pub fn subset(&self, which: &[usize]) -> Cols {
        Cols {
            n: self.n,
            joints: self.joints,
            cols: which.iter().map(|&c| self.cols[c].clone()).collect(),
            whole: self.whole,
        }
    }

    /// Column `c` at scalar row `i`.
    pub fn get(&self, c: usize, i: usize) -> f64 {
        let col = &self.cols[c];
        match col.joint {
            None => col.v[i],
            Some(j) if i % self.joints == j => col.v[i / self.joints],
            Some(_) => 0.0,
        }
    }

    /// Column `c`, one value per scalar row.
    pub fn column(&self, c: usize) -> Vec<f64> {
        (0..self.n).map(|i| self.get(c, i)).collect()
    }

    /// Multiplies the rows of joint `j` by `s[j]`, every column, as the
    /// whole columns multiplied would be.
    pub fn scale(&mut self, s: &[f64]) {
        if s.len() != self.joints {
            return;
        }
        // A zero times a weight that is not a positive finite value is not
        // `+0.0`.
        if !s.iter().all(|w| w.is_finite() && w.is_sign_positive()) {
            self.keep_whole();
        }
        let nz = self.joints;
        for col in &mut self.cols {
            match col.joint {
                None => {
                    for (i, x) in col.v.iter_mut().enumerate() {
                        *x *= s[i % nz];
                    }
                }
                Some(j) => {
                    for x in col.v.iter_mut() {
                        *x *= s[j];
                    }
                }
            }
        }
        if !self.cols.iter().all(|c| c.v.iter().all(|x| x.is_finite())) {
            self.keep_whole();
        }
    }

    /// nalgebra's `dot` of columns `p` and `q` over scalar rows `a..z`.
    fn dot(&self, p: usize, q: usize, a: usize, z: usize) -> f64 {
        let (cp, cq) = (&self.cols[p], &self.cols[q]);
        match (cp.joint, cq.joint) {
            (None, None) => dense_dot(&cp.v[a..z], &cq.v[a..z]),
            (Some(j), None) => self.local_dot(j, &cp.v, |_, i| cq.v[i], a, z),
            (None, Some(j)) => self.local_dot(j, &cq.v, |_, i| cp.v[i], a, z),
            (Some(j), Some(k)) if j == k => self.local_dot(j, &cp.v, |r, _| cq.v[r], a, z),
            // Zero at every row.
            (Some(_), Some(_)) => 0.0,
        }
    }

    /// nalgebra's `dot` of column `c` and `v` (one value per scalar row)
    /// over scalar rows `a..z`.
    pub fn dot_with(&self, c: usize, v: &[f64], a: usize, z: usize) -> f64 {
        let col = &self.cols[c];
        match col.joint {
            None => dense_dot(&col.v[a..z], &v[a..z]),
            Some(j) => self.local_dot(j, &col.v, |_, i| v[i], a, z),
        }
    }

    /// nalgebra's `dot` over scalar rows `a..z` of the column whole that is
    /// `c[r]` at the rows `r * joints + j` and zero elsewhere, and the
    /// values `w(r, i)` at scalar rows `i = r * joints + j`: the products
    /// of those rows alone, each in the partial sum of its scalar row.
    fn local_dot(
        &self,
        j: usize,
        c: &[f64],
        w: impl Fn(usize, usize) -> f64,
        a: usize,
        z: usize,
    ) -> f64 {
        let nz = self.joints;
        let len = z - a;
        let bulk = a + (len - len % 8);
        let mut r = if a <= j { 0 } else { (a - j).div_ceil(nz) };
        let mut acc = [0.0f64; 8];
        while r * nz + j < bulk {
            let i = r * nz + j;
            acc[(i - a) % 8] += c[r] * w(r, i);
            r += 1;
        }
        let mut d = 0.0;
        d += acc[0] + acc[4];
        d += acc[1] + acc[5];
        d += acc[2] + acc[6];
        d += acc[3] + acc[7];
        while r * nz + j < z {
            let i = r * nz + j;
            d += c[r] * w(r, i);
            r += 1;
        }
        d
    }

    /// `X_b^T v_b` over scalar rows `a..z` (`v` one value per scalar row):
    /// nalgebra's `tr_mul` of the rows to the bit.
    pub fn tr_mul(&self, v: &[f64], a: usize, z: usize) -> DVector<f64> {
        let d: Vec<f64> = (0..self.cols.len())
            .into_par_iter()
            .map(|c| self.dot_with(c, v, a, z))
            .collect();
        DVector::from_vec(d)
    }

    /// Every column's dot product with column `c` (all rows): nalgebra's
    /// `x.tr_mul(&x.column(c))` to the bit.
    pub fn against(&self, c: usize) -> DVector<f64> {
        let d: Vec<f64> = (0..self.cols.len())
            .into_par_iter()
            .map(|k| self.dot(k, c, 0, self.n))
            .collect();
        DVector::from_vec(d)
    }

    /// `r += alpha * x_c` as nalgebra's `r.axpy(alpha, &x.column(c), 1.0)`
    /// (a zero's product added too: it turns a `-0.0` of `r` into `+0.0`
    /// as the whole column's would).
    pub fn axpy(&self, c: usize, alpha: f64, r: &mut DVector<f64>) {
        let col = &self.cols[c];
        match col.joint {
            None => {
                for (y, x) in r.iter_mut().zip(&col.v) {
                    *y = alpha * *x * 1.0 + 1.0 * *y;
                }
            }
            Some(j) => {
                for (row, x) in r.as_mut_slice().chunks_exact_mut(self.joints).zip(&col.v) {
                    for (k, y) in row.iter_mut().enumerate() {
                        let x = if k == j { *x } else { 0.0 };
                        *y = alpha * x * 1.0 + 1.0 * *y;
                    }
                }
            }
        }
    }

    /// `r -= x_c` (`y - +0.0` is `y`: the rows off a column's joint are
    /// left as they are).
    pub fn sub_from(&self, c: usize, r: &mut DVector<f64>) {
        let col = &self.cols[c];
        match col.joint {
            None => {
                for (y, x) in r.iter_mut().zip(&col.v) {
                    *y -= *x;
                }
            }
            Some(j) => {
                for (row, x) in r.as_mut_slice().chunks_exact_mut(self.joints).zip(&col.v) {
                    row[j] -= *x;
                }
            }
        }
    }

    /// `X_b^T X_b` of scalar rows `a..z`, each entry nalgebra's dot product
    /// of its two columns to the bit: the whole columns' products tile by
    /// tile ([`tiled`]), those of a column kept at one joint's rows with
    /// each of the others at those rows.
    pub fn gram(&self, a: usize, z: usize) -> DMatrix<f64> {
        let m = self.cols.len();
        let (a, z) = (a.min(self.n), z.min(self.n).max(a.min(self.n)));
        let whole: Vec<usize> = (0..m).filter(|&c| self.cols[c].joint.is_none()).collect();
        let slices: Vec<&[f64]> = whole.iter().map(|&c| &self.cols[c].v[a..z]).collect();
        let mut g = DMatrix::zeros(m, m);
        for (u, v, d) in tiled(&slices) {
            let (i, k) = (whole[u], whole[v]);
            g[(i, k)] = d;
            g[(k, i)] = d;
        }
        let local: Vec<usize> = (0..m).filter(|&c| self.cols[c].joint.is_some()).collect();
        let pairs: Vec<(usize, Vec<(usize, f64)>)> = local
            .par_iter()
            .map(|&p| {
                let jp = self.cols[p].joint;
                let others = (0..m)
                    .filter(|&q| match self.cols[q].joint {
                        None => true,
                        Some(_) if q < p => false,
                        jq => jq == jp,
                    })
                    .map(|q| (q, self.dot(p, q, a, z)))
                    .collect();
                (p, others)
            })
            .collect();
        for (p, others) in pairs {
            for (q, d) in others {
                g[(p, q)] = d;
                g[(q, p)] = d;
            }
        }
        g
    }
}

/// nalgebra's `dot` of two slices of the same length: eight partial sums
/// of every eighth element, added as `dot` adds them, then the elements
/// left over in order.
fn dense_dot(x: &[f64], y: &[f64]) -> f64 {
    let n = x.len();
    let bulk = n - n % 8;
    let mut acc = [0.0f64; 8];
    for off in (0..bulk).step_by(8) {
        for r in 0..8 {
            acc[r] += x[off + r] * y[off + r];
        }
    }
    let mut d = 0.0;
    d += acc[0] + acc[4];
    d += acc[1] + acc[5];
    d += acc[2] + acc[6];
    d += acc[3] + acc[7];
    for k in bulk..n {
        d += x[k] * y[k];
    }
    d
}

/// The dot products `(u, v, d)`, `u <= v`, of columns `cols` (slices of
/// the same length), each [`dense_dot`] to the bit, formed tile by tile:
/// the products of eight columns with eight others row after row, so that
/// each column is read once a tile of others instead of once for every
/// other column (a long record's columns do not stay in the cache between
/// two of their dot products).
fn tiled(cols: &[&[f64]]) -> Vec<(usize, usize, f64)> {
    let c = cols.len();
    let n = cols.first().map_or(0, |x| x.len());
    let bulk = n - n % 8;
    // Each tile of columns against itself and those after it, the tiles
    // side by side on the threads.
    let tiles: Vec<Vec<(usize, usize, f64)>> = (0..c)
        .step_by(TILE)
        .collect::<Vec<_>>()
        .into_par_iter()
        .map(|ti| {
            let mut out = Vec::new();
            let ci = &cols[ti..(ti + TILE).min(c)];
            for tj in (ti..c).step_by(TILE) {
                let cj = &cols[tj..(tj + TILE).min(c)];
                let mut acc = [[[0.0f64; 8]; TILE]; TILE];
                for off in (0..bulk).step_by(8) {
                    for (u, xu) in ci.iter().enumerate() {
                        let xu = &xu[off..off + 8];
                        for (v, xv) in cj.iter().enumerate() {
                            let xv = &xv[off..off + 8];
                            let s = &mut acc[u][v];
                            for r in 0..8 {
                                s[r] += xu[r] * xv[r];
                            }
                        }
                    }
                }
                for (u, xu) in ci.iter().enumerate() {
                    for (v, xv) in cj.iter().enumerate() {
                        let (i, j) = (ti + u, tj + v);
                        if j < i {
                            continue;
                        }
                        let s = &acc[u][v];
                        let mut d = 0.0;
                        d += s[0] + s[4];
                        d += s[1] + s[5];
                        d += s[2] + s[6];
                        d += s[3] + s[7];
                        for k in bulk..n {
                            d += xu[k] * xv[k];
                        }
                        out.push((i, j, d));
                    }
                }
            }
            out
        })
        .collect();
    tiles.into_iter().flatten().collect()
}

#[cfg(test)]
mod tests;
