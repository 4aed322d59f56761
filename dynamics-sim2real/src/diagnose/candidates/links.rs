//! Link inertial corrections as terms of the compound explanation: the
//! inertial regressor `d tau / d pi_l` of every link (the ten parameters
//! of `Robot::inertial_regressor`, Pinocchio's order) along the measured
//! motion, smoothed once more like every column built from the
//! acceleration estimate, whitened on the fit's rows; reduced per link to
//! the combinations these data determine (the right singular vectors of
//! the link's columns whose singular value is at least [`IDENTIFIABLE`]
//! of the largest): a link's correction is reported as the minimum-norm
//! parameter change along them.
//!
//! Each link also comes as its mass and centre of mass alone
//! ([`moment_basis`]: the first four parameters, `m` and `m c`, the
//! rotational inertia about the link frame's origin kept as the model's):
//! what the static load of the arm and most of a log's gap depend on, and
//! what a user measures or weighs, where the data seldom determine the
//! six parameters of the rotational inertia as well.

use nalgebra::{DMatrix, SMatrix, SVector};
use rayon::prelude::*;

use crate::diagnose::along;
use crate::diagnose::candidates::Prepared;
use dynamics_runtime::Robot;

/// Relative singular value below which a combination of a link's
/// parameters counts as not determined by the data.
pub const IDENTIFIABLE: f64 = 1e-3;

/// Per link, per inertial parameter (Pinocchio's order), the whitened
/// regressor column over the fit's rows.
pub type LinkColumns = Vec<Vec<Vec<f64>>>;

/// One link's determined combinations.
#[derive(Debug, Clone)]
pub struct LinkBasis {
    /// Link index into `Robot::LINK_NAMES`.
    pub link: usize,
    /// 10 x r: the combinations (orthonormal columns).
    pub v: DMatrix<f64>,
    /// Whether the link carries the tip (the last of `Robot::LINK_NAMES`):
    /// its correction and a payload at the tip are one place
    /// (`Term::family`).
    pub tip: bool,
    /// Whether the correction is of the link's mass and centre of mass
    /// alone (its rotational inertia about the link frame's origin as the
    /// model's): `v` has rows 4.. zero, and the combinations left free are
    /// those of the first four parameters only.
    pub moments: bool,
}

impl LinkBasis {
    /// An orthonormal basis of the combinations of the link's ten
    /// parameters the data do not determine (the complement of `v`).
    /// For a correction of the mass and centre of mass alone, those of the
    /// first four parameters: its rotational inertia is not moved.
    pub fn free_combinations(&self) -> DMatrix<f64> {
        let span = if self.moments { MOMENTS } else { 10 };
        let p = DMatrix::<f64>::from_fn(10, 10, |r, c| if r == c && r < span { 1.0 } else { 0.0 })
            - &self.v * self.v.transpose();
        let eig = p.symmetric_eigen();
        let keep: Vec<usize> = (0..10).filter(|&i| eig.eigenvalues[i] > 0.5).collect();
        eig.eigenvectors.select_columns(&keep)
    }
}

/// Whitened regressor columns of every link on the rows of `p`, each
/// `[link][parameter]` a column of `p.n()` entries (`None` when the robot
/// does not give its regressor). Pieces of [`PIECE`] rows are made on
/// the threads at once, each straight into its part of the columns.
pub fn regressor_columns<R: Robot<N> + Sync, const N: usize>(
    robot: &R,
    p: &Prepared<N>,
) -> Option<LinkColumns> {
    regressor_columns_in(robot, p, PIECE)
}

/// [`regressor_columns`] in pieces of `piece` rows.
fn regressor_columns_in<R: Robot<N> + Sync, const N: usize>(
    robot: &R,
    p: &Prepared<N>,
    piece: usize,
) -> Option<LinkColumns> {
    let piece = piece.max(1);
    let links = R::LINK_NAMES.len();
    if links == 0 {
        return None;
    }
    let mut columns = vec![vec![0.0; p.n()]; links * 10];
    let pieces = p.rows.len().div_ceil(piece);
    let mut parts: Vec<Vec<&mut [f64]>> = (0..pieces).map(|_| Vec::new()).collect();
    for column in &mut columns {
        for (part, piece) in parts.iter_mut().zip(column.chunks_mut(piece * N)) {
            part.push(piece);
        }
    }
    p.rows
        .par_chunks(piece)
        .zip(parts)
        .try_for_each(|(rows, mut part)| regressor_piece(robot, p, rows, &mut part))?;
    let mut columns = columns.into_iter();
    Some(
        (0..links)
            .map(|_| columns.by_ref().take(10).collect())
            .collect(),
    )
}

/// Rows of the link columns made as one piece: some 80 000 samples of a
/// record at 1 kHz, where a piece's window re-evaluates 80 samples.
const PIECE: usize = 4096;

/// The link columns at `rows` (ascending), into `out`: per link and
/// parameter, `rows.len() * N` entries.
fn regressor_piece<R: Robot<N>, const N: usize>(
    robot: &R,
    p: &Prepared<N>,
    rows: &[usize],
    out: &mut [&mut [f64]],
) -> Option<()> {
    let sig = &p.sig;
    let h = sig.sg.half();
    let w = sig.sg.weights(0);
    let n = sig.t.len();
    // The regressor over the window of the current row only (the rows go
    // forward, so a window shares its first samples with the previous
    // one's last): memory bounded by one window whatever the record's
    // length, and every sample evaluated once.
    let mut window = RegressorWindow::<N>::new(out.len() / 10, p.chunk);
    for (r, &k) in rows.iter().enumerate() {
        window.advance(robot, sig, k.saturating_sub(h), (k + h + 1).min(n))?;
        for (l, link) in out.chunks_mut(10).enumerate() {
            let mut s = SMatrix::<f64, N, 10>::zeros();
            for (i, wi) in w.iter().enumerate() {
                let m = k + i;
                if m >= h && m - h < n {
                    s += window.at(m - h, l) * *wi;
                }
            }
            for (c, col) in link.iter_mut().enumerate() {
                for j in 0..N {
                    let x = s[(j, c)] / sig.floor[j];
                    col[r * N + j] = if x.is_finite() { x } else { 0.0 };
                }
            }
        }
    }
    Some(())
}

/// The inertial regressor of every link along a record, held from the
/// first sample the current row's window reaches and evaluated `chunk`
/// samples ahead at a time (`along.rs`): what the link columns hold of the
/// record at once, whatever its length (a chunk of the whole record
/// evaluates it whole).
struct RegressorWindow<const N: usize> {
    /// First sample held.
    from: usize,
    /// Per sample from `from`, per link (zero outside the signals' range).
    y: std::collections::VecDeque<Vec<SMatrix<f64, N, 10>>>,
    links: usize,
    chunk: usize,
}

impl<const N: usize> RegressorWindow<N> {
    fn new(links: usize, chunk: usize) -> Self {
        RegressorWindow {
            from: 0,
            y: Default::default(),
            links,
            chunk: if chunk == 0 { along::CHUNK } else { chunk },
        }
    }

    /// Holds at least the samples `[from, to)`: drops those before `from`,
    /// evaluates a chunk (or up to `to`) when `to` is not held yet (`None`
    /// when the robot does not give its regressor). `from` and `to` never
    /// go back.
    fn advance<R: Robot<N>>(
        &mut self,
        robot: &R,
        sig: &crate::diagnose::signals::Signals<N>,
        from: usize,
        to: usize,
    ) -> Option<()> {
        while self.from < from && !self.y.is_empty() {
            self.y.pop_front();
            self.from += 1;
        }
        if self.y.is_empty() {
            self.from = from;
        }
        let start = self.from + self.y.len();
        if start >= to {
            return Some(());
        }
        let end = start.saturating_add(self.chunk).max(to).min(sig.t.len());
        let (a, z) = sig.range;
        let zero = || vec![SMatrix::<f64, N, 10>::zeros(); self.links];
        // The samples of `[start, end)` inside the range `[a, z)`.
        let lo = start.clamp(a.min(end), end);
        let inside = lo..end.min(z).max(lo);
        for _ in start..inside.start {
            self.y.push_back(zero());
        }
        let [q, qd, qdd] = sig.motion.stretch(inside.start, inside.end);
        let motion = [&q[..], &qd[..], &qdd[..]];
        along::inertial_regressor(robot, motion, 0..inside.len(), self.links, &mut self.y).ok()?;
        for _ in inside.end..end {
            self.y.push_back(zero());
        }
        Some(())
    }

    /// Link `l`'s regressor at sample `k` (held).
    fn at(&self, k: usize, l: usize) -> SMatrix<f64, N, 10> {
        self.y[k - self.from][l]
    }
}

/// The parameters of a link's mass and centre of mass: `m`, `m c`.
pub const MOMENTS: usize = 4;

/// A link's determined combinations from its whitened columns.
pub fn link_basis(link: usize, cols: &[Vec<f64>]) -> Option<LinkBasis> {
    let v = determined(cols, 10)?;
    Some(LinkBasis {
        link,
        v,
        tip: false,
        moments: false,
    })
}

/// The determined combinations of a link's mass and centre of mass alone
/// (its first [`MOMENTS`] parameters; rows 4.. of `v` zero).
pub fn moment_basis(link: usize, cols: &[Vec<f64>]) -> Option<LinkBasis> {
    let sub = determined(cols, MOMENTS)?;
    let v = DMatrix::from_fn(
        10,
        sub.ncols(),
        |r, c| if r < MOMENTS { sub[(r, c)] } else { 0.0 },
    );
    Some(LinkBasis {
        link,
        v,
        tip: false,
        moments: true,
    })
}

/// An orthonormal basis (`width` x r) of the combinations of the first
/// `width` columns whose singular value is at least [`IDENTIFIABLE`] of the
/// largest.
fn determined(cols: &[Vec<f64>], width: usize) -> Option<DMatrix<f64>> {
    let n = cols.first()?.len();
    if cols.len() < width {
        return None;
    }
    let x = DMatrix::from_fn(n, width, |r, c| cols[c][r]);
    let g = x.tr_mul(&x);
    let eig = g.symmetric_eigen();
    let top = eig.eigenvalues.iter().cloned().fold(0.0, f64::max);
    if !(top > 0.0 && top.is_finite()) {
        return None;
    }
    let keep: Vec<usize> = (0..width)
        .filter(|&i| eig.eigenvalues[i] >= IDENTIFIABLE * IDENTIFIABLE * top)
        .collect();
    if keep.is_empty() {
        return None;
    }
    Some(eig.eigenvectors.select_columns(&keep))
}

/// The link's combinations as columns: `X v`.
pub fn combined(cols: &[Vec<f64>], basis: &LinkBasis) -> Vec<Vec<f64>> {
    let n = cols.first().map_or(0, |c| c.len());
    (0..basis.v.ncols())
        .map(|r| {
            (0..n)
                .map(|i| (0..10).map(|c| cols[c][i] * basis.v[(c, r)]).sum())
                .collect()
        })
        .collect()
}

/// The parameter change `v theta` of a link.
pub fn delta(basis: &LinkBasis, theta: &[f64]) -> SVector<f64, 10> {
    let mut d = SVector::<f64, 10>::zeros();
    for (r, th) in theta.iter().enumerate().take(basis.v.ncols()) {
        for c in 0..10 {
            d[c] += basis.v[(c, r)] * th;
        }
    }
    d
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Ten columns of 40 rows: the first four independent, the fifth a
    /// copy of the first (a combination the data do not determine).
    fn columns() -> Vec<Vec<f64>> {
        let mut cols: Vec<Vec<f64>> = (0..10)
            .map(|c| {
                (0..40)
                    .map(|r| ((r * (c + 3) + c * c) as f64 * 0.37).sin())
                    .collect()
            })
            .collect();
        cols[4] = cols[0].clone();
        cols
    }

    /// The link columns made in pieces are those made in one, to the bit,
    /// at every piece boundary.
    #[test]
    fn the_link_columns_in_pieces_are_the_whole_records() {
        use crate::synth::{synthesize, SynthOptions};
        let robot = crate::test_robots::Arm2::default();
        let opts = SynthOptions {
            duration: 3.0,
            seed: 4,
            ..Default::default()
        };
        let m = synthesize(&robot, &[], &opts).expect("a generated record");
        let p = Prepared::new(&robot, &m);
        assert!(p.rows.len() > 50);
        let whole = regressor_columns_in(&robot, &p, usize::MAX).expect("a regressor");
        let bits = |c: &LinkColumns| -> Vec<u64> {
            c.iter().flatten().flatten().map(|x| x.to_bits()).collect()
        };
        assert!(whole.iter().flatten().flatten().any(|x| *x != 0.0));
        for piece in [1, 7, 64] {
            let pieces = regressor_columns_in(&robot, &p, piece).expect("a regressor");
            assert_eq!(bits(&pieces), bits(&whole), "pieces of {piece} rows");
        }
    }

    /// The mass and centre of mass alone: four determined combinations of
    /// the first four parameters, none of the rotational inertia, and no
    /// combination of the inertia left free to move (the model's stays).
    #[test]
    fn a_mass_and_centre_of_mass_correction_leaves_the_rotational_inertia_alone() {
        let cols = columns();
        let b = moment_basis(2, &cols).expect("determined");
        assert!(b.moments && b.link == 2);
        assert_eq!(b.v.shape(), (10, 4));
        assert!((b.v.tr_mul(&b.v) - DMatrix::<f64>::identity(4, 4)).norm() < 1e-12);
        assert!(b.v.rows(MOMENTS, 10 - MOMENTS).iter().all(|x| *x == 0.0));
        assert_eq!(b.free_combinations().ncols(), 0);
        let d = delta(&b, &[1.0, -2.0, 0.5, 0.25]);
        assert!(d.rows(MOMENTS, 10 - MOMENTS).iter().all(|x| *x == 0.0));
        // All ten: the copied column leaves one combination undetermined,
        // free to move.
        let full = link_basis(2, &cols).expect("determined");
        assert!(!full.moments);
        assert_eq!(full.v.ncols(), 9);
        assert_eq!(full.free_combinations().ncols(), 1);
    }
}
