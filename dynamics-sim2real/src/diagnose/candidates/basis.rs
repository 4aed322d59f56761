//! Per-sample model quantities that several candidates share: the
//! perturbation Jacobian K = dF/dq (encoder offsets), the tip's Jacobian,
//! velocity and bias acceleration (payload, environment), the joints' own
//! inertia. The fits read the per-sample ones at their rows only, so they
//! are kept at the rows; another sample (a correction applied along the
//! whole record) is recomputed a chunk at a time from the model and the
//! signals: the same operations in the same order as over the whole
//! record (each state's model outputs do not depend on the states beside
//! it in a batch; the smoothing's window sums run tap by tap), so the same
//! values to the bit.

use std::any::Any;
use std::cell::RefCell;
use std::fmt;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;

use nalgebra::{Matrix3, SMatrix, SVector, Vector3};

use super::row_series::RowSeries;
use crate::diagnose::along::{self, CHUNK};
use crate::diagnose::signals::{Motion, Signals};
use crate::effects::nominal_friction;
use crate::effects::Tip;
use crate::smoothing::SavitzkyGolay;
use dynamics_runtime::Robot;

/// Per joint, the nominal model's Coulomb levels and viscous coefficients
/// ([`crate::effects::nominal_friction`]).
pub type Friction<const N: usize> = (SVector<f64, N>, SVector<f64, N>);

/// The tip frame's orientation (world from tip), angular-velocity
/// Jacobian `J_w` and angular acceleration `J_w qdd + Jd_w qd` (smoothed)
/// at one sample.
#[derive(Debug, Clone, Copy)]
pub struct Frame<const N: usize> {
    /// World from tip.
    pub rot: Matrix3<f64>,
    /// Angular-velocity Jacobian.
    pub jac_w: SMatrix<f64, 3, N>,
    /// Angular acceleration, smoothed once more.
    pub alpha: Vector3<f64>,
}

/// The tip's motion at one sample.
#[derive(Debug, Clone, Copy)]
pub struct TipAt<const N: usize> {
    /// Position Jacobian.
    pub jac: SMatrix<f64, 3, N>,
    /// Acceleration `J qdd + Jd qd`, smoothed once more.
    pub acc: Vector3<f64>,
    /// The tip frame's rotation quantities (none for a point tip, which
    /// has no frame).
    pub frame: Option<Frame<N>>,
}

/// The model's per-sample outputs at one row.
#[derive(Debug, Clone, Copy)]
struct AtRow<const N: usize> {
    k: SMatrix<f64, N, N>,
    tip: TipAt<N>,
}

/// The model evaluated along a stretch of states, its type hidden so that
/// a record made ready keeps it without naming it.
trait Model<const N: usize>: Send + Sync {
    /// K = dF/dq at every state of `motion` into `out`.
    fn k(&self, motion: [&[SVector<f64, N>]; 3], out: &mut [SMatrix<f64, N, N>]);
    /// The tip's Jacobians, orientation and (unsmoothed) accelerations at
    /// every state of `motion` into `out`.
    fn tip(&self, tip: &Tip, motion: [&[SVector<f64, N>]; 3], out: &mut [TipAt<N>]);
}

/// A robot as a [`Model`].
struct Held<R>(R);

impl<R: Robot<N> + Send + Sync, const N: usize> Model<N> for Held<R> {
    fn k(&self, motion: [&[SVector<f64, N>]; 3], out: &mut [SMatrix<f64, N, N>]) {
        let n = out.len();
        along::perturbation_k(&self.0, motion, 0..n, n.max(1), out);
    }

    fn tip(&self, tip: &Tip, motion: [&[SVector<f64, N>]; 3], out: &mut [TipAt<N>]) {
        let n = out.len();
        let mut jac = vec![SMatrix::zeros(); n];
        let mut acc = vec![Vector3::zeros(); n];
        let mut frame = None;
        if let Tip::Frame(_) = tip {
            let mut rot = vec![Matrix3::identity(); n];
            let mut jac_w = vec![SMatrix::zeros(); n];
            let mut alpha = vec![Vector3::zeros(); n];
            let rotation = (&mut rot[..], &mut jac_w[..], &mut alpha[..]);
            if along::frame_tip(&self.0, tip, motion, 0..n, &mut jac, &mut acc, rotation) {
                frame = Some((rot, jac_w, alpha));
            }
        }
        if frame.is_none() {
            along::tip_motion(&self.0, tip, motion, 0..n, n.max(1), &mut jac, &mut acc);
        }
        for (i, o) in out.iter_mut().enumerate() {
            *o = TipAt {
                jac: jac[i],
                acc: acc[i],
                frame: frame.as_ref().map(|(r, w, a)| Frame {
                    rot: r[i],
                    jac_w: w[i],
                    alpha: a[i],
                }),
            };
        }
    }
}

/// The quantities a record's model outputs are recomputed from away from
/// the rows: the model, the smoothed motion, where the filter's window
/// fits, and the chunk.
#[derive(Clone)]
struct Along<const N: usize> {
    model: Arc<dyn Model<N>>,
    motion: Motion<N>,
    range: (usize, usize),
    sg: SavitzkyGolay,
    tip: Tip,
    chunk: usize,
}

impl<const N: usize> fmt::Debug for Along<N> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Along")
            .field("range", &self.range)
            .field("tip", &self.tip)
            .field("chunk", &self.chunk)
            .finish_non_exhaustive()
    }
}

/// Entries `entries` of the values `raw` (from sample `lo` on) smoothed at
/// sample `k` over the signals' range `(a, z)`, into `y`: as
/// `SavitzkyGolay::apply` over the range gives them (each window's sum
/// term by term in the same order), zero where the window does not fit
/// in the range or the value is not finite.
fn smooth_into<const R: usize, const C: usize>(
    sg: &SavitzkyGolay,
    raw: &[SMatrix<f64, R, C>],
    lo: usize,
    (a, z): (usize, usize),
    k: usize,
    entries: std::ops::Range<usize>,
    y: &mut [f64],
) {
    let h = sg.half();
    if z - a < 2 * h + 1 || k < a + h || k + h >= z {
        y.fill(0.0);
        return;
    }
    // The value a float sum starts from (`Iterator::sum`).
    let start: f64 = std::iter::empty::<f64>().sum();
    y.fill(start);
    for (i, w) in sg.weights(0).iter().enumerate() {
        let x = &raw[k - h + i - lo].as_slice()[entries.clone()];
        for (s, v) in y.iter_mut().zip(x) {
            *s += w * v;
        }
    }
    for s in y.iter_mut() {
        if !s.is_finite() {
            *s = 0.0;
        }
    }
}

/// Every entry of `raw` smoothed at sample `k` ([`smooth_into`]).
fn smoothed<const R: usize, const C: usize>(
    sg: &SavitzkyGolay,
    raw: &[SMatrix<f64, R, C>],
    lo: usize,
    range: (usize, usize),
    k: usize,
) -> SMatrix<f64, R, C> {
    let mut y = SMatrix::<f64, R, C>::zeros();
    smooth_into(sg, raw, lo, range, k, 0..R * C, y.as_mut_slice());
    y
}

/// The sum over the samples of `range` of the mass matrix's diagonal at
/// `sig`'s positions, the positions made and the batches evaluated
/// `chunk` samples at a time, summed in the samples' order.
fn mass_diagonal_sum<R: Robot<N>, const N: usize>(
    robot: &R,
    sig: &Signals<N>,
    range: std::ops::Range<usize>,
    chunk: usize,
) -> SVector<f64, N> {
    let mut sum = SVector::<f64, N>::zeros();
    for c in along::chunks(range, chunk) {
        let q: Vec<_> = c.map(|k| sig.q(k)).collect();
        along::add_mass_diagonal(robot, &q, &mut sum);
    }
    sum
}

/// K's raw values over a stretch, from its first sample on.
type RawK<const N: usize> = (usize, Vec<SMatrix<f64, N, N>>);

impl<const N: usize> Along<N> {
    /// Chunk `c`'s samples and, when some lie in the signals' range, the
    /// stretch `lo..hi` of raw values their smoothing reads.
    fn stretch(&self, c: usize) -> (usize, usize, Option<(usize, usize)>) {
        let n = self.motion.len();
        let (a, z) = self.range;
        let h = self.sg.half();
        let first = c.saturating_mul(self.chunk).min(n);
        let end = first.saturating_add(self.chunk).min(n);
        let (s, e) = (first.max(a), end.min(z));
        let raw = (s < e).then(|| (s.saturating_sub(h).max(a), e.saturating_add(h).min(z)));
        (first, end, raw)
    }

    fn motion(&self, lo: usize, hi: usize) -> [Vec<SVector<f64, N>>; 3] {
        self.motion.stretch(lo, hi)
    }

    /// K's raw values over the stretch chunk `c`'s smoothing reads, and
    /// its first sample, its end and the stretch's first sample (none when
    /// the chunk lies outside the signals' range).
    fn raw_k(&self, c: usize) -> (usize, usize, Option<RawK<N>>) {
        let (first, end, raw) = self.stretch(c);
        let raw = raw.map(|(lo, hi)| {
            let mut x = vec![SMatrix::zeros(); hi - lo];
            let [q, qd, qdd] = self.motion(lo, hi);
            self.model.k([&q, &qd, &qdd], &mut x);
            (lo, x)
        });
        (first, end, raw)
    }

    /// K over chunk `c`: its first sample and values (zero outside the
    /// signals' range).
    fn k(&self, c: usize) -> (usize, Vec<SMatrix<f64, N, N>>) {
        let (first, end, raw) = self.raw_k(c);
        let mut out = vec![SMatrix::zeros(); end - first];
        if let Some((lo, x)) = raw {
            let (a, z) = self.range;
            for k in first.max(a)..end.min(z) {
                out[k - first] = smoothed(&self.sg, &x, lo, self.range, k);
            }
        }
        (first, out)
    }

    /// Column `j` of K over chunk `c` (only that column smoothed).
    fn k_column(&self, c: usize, j: usize) -> (usize, Vec<SVector<f64, N>>) {
        let (first, end, raw) = self.raw_k(c);
        let mut out = vec![SVector::<f64, N>::zeros(); end - first];
        if let Some((lo, x)) = raw {
            let (a, z) = self.range;
            for k in first.max(a)..end.min(z) {
                let y = out[k - first].as_mut_slice();
                smooth_into(&self.sg, &x, lo, self.range, k, j * N..(j + 1) * N, y);
            }
        }
        (first, out)
    }

    /// The tip's motion over chunk `c`: its first sample and values (zero,
    /// and the identity orientation, outside the signals' range).
    fn tip(&self, c: usize) -> (usize, Vec<TipAt<N>>) {
        let (first, end, raw) = self.stretch(c);
        let rest = TipAt {
            jac: SMatrix::zeros(),
            acc: Vector3::zeros(),
            frame: matches!(self.tip, Tip::Frame(_)).then(|| Frame {
                rot: Matrix3::identity(),
                jac_w: SMatrix::zeros(),
                alpha: Vector3::zeros(),
            }),
        };
        let mut out = vec![rest; end - first];
        if let Some((lo, hi)) = raw {
            let mut x = vec![rest; hi - lo];
            let [q, qd, qdd] = self.motion(lo, hi);
            self.model.tip(&self.tip, [&q, &qd, &qdd], &mut x);
            let acc: Vec<Vector3<f64>> = x.iter().map(|t| t.acc).collect();
            let alpha: Vec<Vector3<f64>> = x
                .iter()
                .map(|t| t.frame.map_or(Vector3::zeros(), |f| f.alpha))
                .collect();
            let (a, z) = self.range;
            for k in first.max(a)..end.min(z) {
                let mut t = x[k - lo];
                t.acc = smoothed(&self.sg, &acc, lo, self.range, k);
                if let Some(f) = t.frame.as_mut() {
                    f.alpha = smoothed(&self.sg, &alpha, lo, self.range, k);
                }
                out[k - first] = t;
            }
        }
        (first, out)
    }
}

/// Where each [`Basis`] is told from another (the thread's chunk cache is
/// keyed by it).
static NEXT_ID: AtomicU64 = AtomicU64::new(0);

/// Chunks of model outputs a thread keeps.
const SLOTS: usize = 4;

/// Which outputs a cached chunk holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Group {
    K,
    /// One column of K.
    KColumn(usize),
    Tip,
}

/// One chunk of one group of outputs, recomputed.
struct Slot {
    id: u64,
    group: Group,
    chunk: usize,
    /// The chunk's first sample.
    first: usize,
    /// `Vec<SMatrix<f64, N, N>>` (K), `Vec<SVector<f64, N>>` (a column of
    /// K) or `Vec<TipAt<N>>` (the tip).
    values: Box<dyn Any>,
}

thread_local! {
    /// The chunks this thread recomputed last (first in, first out).
    static CACHE: RefCell<Vec<Slot>> = const { RefCell::new(Vec::new()) };
}

/// Shared model quantities along one data set (valid inside the signals'
/// range).
#[derive(Debug, Clone)]
pub struct Basis<const N: usize> {
    /// Tells this record's outputs from another's in the chunk cache.
    id: u64,
    /// The rows (sample indices, increasing).
    rows: Vec<usize>,
    /// K and the tip's motion at the rows.
    at_rows: Vec<AtRow<N>>,
    /// What the outputs are recomputed from elsewhere.
    along: Along<N>,
    /// Mean A[j][j] over the data.
    pub inertia: SVector<f64, N>,
    /// Per joint, its acceleration per unit of its own effort: what the
    /// link of a motor-side simulation answers to (`motor_sim/`). One over
    /// its mean own inertia (see `Basis::new` for the per-sample inverse
    /// mass matrix tried instead).
    pub compliance: SVector<f64, N>,
    /// Gravity vector of the model.
    pub gravity: Vector3<f64>,
    /// The tip used.
    pub tip: Tip,
    /// The modelled mass of the body that carries the tip
    /// ([`Tip::body_mass`]): the most a payload relative to the model can
    /// take away.
    pub tip_mass: f64,
    /// The friction laws' columns (every Coulomb width and Stribeck
    /// velocity searched, filtered as the residual shows a force of them)
    /// and the accelerations smoothed once more (the rotor-inertia
    /// column): kept at the fit's rows, recomputed elsewhere
    /// (`row_series.rs`).
    pub series: RowSeries<N>,
    /// Per joint, the nominal model's own Coulomb level and viscous
    /// coefficient (`nominal_friction.rs`): how far a friction correction
    /// may go below zero.
    pub friction: Friction<N>,
}

impl<const N: usize> Basis<N> {
    /// Evaluates the shared quantities along `sig`, the per-sample ones
    /// and the series of [`RowSeries`] kept at `rows` (increasing sample
    /// indices). The model is evaluated `chunk` samples at a time
    /// (`along.rs`; 0: the default), and kept to recompute the per-sample
    /// quantities elsewhere.
    pub fn new<R: Robot<N> + Clone + Send + Sync + 'static>(
        robot: &R,
        sig: &Signals<N>,
        rows: &[usize],
        chunk: usize,
    ) -> Self {
        let n = sig.t.len();
        let tip = Tip::of::<R, N>();
        let chunk = if chunk == 0 { CHUNK } else { chunk };
        let along = Along {
            model: Arc::new(Held(robot.clone())),
            motion: sig.motion.clone(),
            range: sig.range,
            sg: sig.sg.clone(),
            tip,
            chunk,
        };
        let (a, z) = sig.range;
        // The rows' outputs, a chunk at a time.
        let mut at_rows = Vec::with_capacity(rows.len());
        let mut r = 0;
        for c in 0..n.div_ceil(chunk) {
            let end = (c + 1).saturating_mul(chunk).min(n);
            if rows.get(r).is_none_or(|&k| k >= end) {
                continue;
            }
            let ((first, k), (_, t)) = (along.k(c), along.tip(c));
            while let Some(&row) = rows.get(r).filter(|&&k| k < end) {
                at_rows.push(AtRow {
                    k: k[row - first],
                    tip: t[row - first],
                });
                r += 1;
            }
        }
        let mut b = Basis {
            id: NEXT_ID.fetch_add(1, Ordering::Relaxed),
            rows: rows.to_vec(),
            at_rows,
            along,
            inertia: SVector::zeros(),
            compliance: SVector::zeros(),
            gravity: Vector3::from(R::GRAVITY),
            tip,
            tip_mass: Tip::body_mass::<R, N>(robot),
            series: RowSeries::new(sig, rows, chunk),
            friction: (SVector::zeros(), SVector::zeros()),
        };
        if a < n {
            b.friction = nominal_friction(robot, &sig.q(a));
        }
        b.inertia = mass_diagonal_sum(robot, sig, a..z, chunk);
        b.inertia /= (z - a).max(1) as f64;
        // The link's response to its own effort, as one over its mean own
        // inertia. The inverse mass matrix's diagonal at each sample (the
        // joint's response with the other joints' efforts held; the
        // simulation would take it per sample) was tried: right on the MAR's
        // backlash cases, but on the real Panda log it chose elastic joints
        // at joints 1-3 that predicted the held-out half worse (plain
        // shrink 0.429 to 0.409; `scripts/real-logs.sh`): there the other
        // joints' controllers hold them, which neither figure models.
        b.compliance = b.inertia.map(|x| if x > 0.0 { 1.0 / x } else { 0.0 });
        b
    }

    /// Whether the tip is a frame (with an orientation), not a point.
    pub fn framed(&self) -> bool {
        matches!(self.tip, Tip::Frame(_))
    }

    /// K = dF/dq at sample `k`, smoothed like the accelerations it is
    /// made of (zero outside the signals' range and within the filter's
    /// half-width of its ends).
    pub fn k(&self, k: usize) -> SMatrix<f64, N, N> {
        match self.rows.binary_search(&k) {
            Ok(r) => self.at_rows[r].k,
            Err(_) => self.cached(Group::K, k, |c| {
                let (first, v) = self.along.k(c);
                (first, Box::new(v))
            }),
        }
    }

    /// Column `j` of [`Basis::k`] at sample `k`.
    pub fn k_column(&self, k: usize, j: usize) -> SVector<f64, N> {
        match self.rows.binary_search(&k) {
            Ok(r) => self.at_rows[r].k.column(j).into_owned(),
            Err(_) => self.cached(Group::KColumn(j), k, |c| {
                let (first, v) = self.along.k_column(c, j);
                (first, Box::new(v))
            }),
        }
    }

    /// The tip's motion at sample `k` (its accelerations smoothed once
    /// more).
    pub fn tip_at(&self, k: usize) -> TipAt<N> {
        match self.rows.binary_search(&k) {
            Ok(r) => self.at_rows[r].tip,
            Err(_) => self.cached(Group::Tip, k, |c| {
                let (first, v) = self.along.tip(c);
                (first, Box::new(v))
            }),
        }
    }

    /// Sample `k` of `group`, from the thread's cache of recomputed chunks
    /// or `make` (a chunk's first sample and values) of its chunk.
    fn cached<T: Copy + 'static>(
        &self,
        group: Group,
        k: usize,
        make: impl FnOnce(usize) -> (usize, Box<dyn Any>),
    ) -> T {
        let c = k / self.along.chunk;
        let read = |s: &Slot| {
            s.values
                .downcast_ref::<Vec<T>>()
                .and_then(|v| v.get(k - s.first).copied())
        };
        CACHE
            .with(|cache| {
                let mut cache = cache.borrow_mut();
                let hit = cache
                    .iter()
                    .find(|s| s.id == self.id && s.group == group && s.chunk == c)
                    .and_then(read);
                if hit.is_some() {
                    return hit;
                }
                let (first, values) = make(c);
                let slot = Slot {
                    id: self.id,
                    group,
                    chunk: c,
                    first,
                    values,
                };
                let x = read(&slot);
                if cache.len() >= SLOTS {
                    cache.remove(0);
                }
                cache.push(slot);
                x
            })
            .unwrap_or_else(|| unreachable!("a chunk holds each of its samples"))
    }
}

#[cfg(test)]
mod tests;
