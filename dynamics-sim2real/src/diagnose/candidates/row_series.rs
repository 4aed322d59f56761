//! The column-cache series built from the signals alone: the friction
//! laws filtered as the residual shows a force (the Coulomb widths and the
//! Stribeck velocities searched) and the accelerations smoothed once more
//! (the rotor-inertia column). The fits read them at their rows only, so
//! they are kept at the rows; another sample (a correction applied along
//! the whole record, a figure) is recomputed a chunk at a time from the
//! signals and the running integrals carried to the chunk's start: the
//! same operations in the same order as over the whole record, so the
//! same values to the bit.

use std::cell::RefCell;
use std::sync::atomic::{AtomicU64, Ordering};

use nalgebra::SVector;

use super::force_filter::Carry;
use super::grids::{COULOMB_WIDTHS, STRIBECK_GRID};
use crate::diagnose::along::CHUNK;
use crate::diagnose::signals::Signals;
use crate::effects::{smooth_sign, SIGN_SMOOTHING};

/// How many friction laws are kept: every Coulomb width (the first, the
/// sharp one, is the sign's), then every Stribeck velocity.
pub const LAWS: usize = COULOMB_WIDTHS.len() + STRIBECK_GRID.len();

/// The index of law `Coulomb(w)` (the sharp one for a width not searched).
pub fn coulomb_law(w: f64) -> usize {
    COULOMB_WIDTHS.iter().position(|&g| g == w).unwrap_or(0)
}

/// The index of law `Stribeck(vs)` (the first velocity for one not
/// searched).
pub fn stribeck_law(vs: f64) -> usize {
    COULOMB_WIDTHS.len() + STRIBECK_GRID.iter().position(|&g| g == vs).unwrap_or(0)
}

/// Law `i` at velocity `v`.
fn law(i: usize, v: f64) -> f64 {
    match i.checked_sub(COULOMB_WIDTHS.len()) {
        None if i == 0 => smooth_sign(v),
        None => (v / COULOMB_WIDTHS[i]).tanh(),
        Some(s) => (-(v / STRIBECK_GRID[s]).powi(2)).exp() * smooth_sign(v),
    }
}

/// Velocity step of the quadrature in [`interval_mean`], rad/s or m/s: an
/// eighth of the narrowest velocity scale a friction column has (the
/// smooth sign's, and the smallest Stribeck velocity searched).
const VELOCITY_STEP: f64 = SIGN_SMOOTHING / 8.0;

/// The mean of `f` over sample `k`'s own interval, from half-way to the
/// previous sample to half-way to the next, the velocity going linearly
/// through `prev`, `v` and `next` (midpoint rule, steps of at most
/// [`VELOCITY_STEP`]). A friction law is sharp in the velocity: where the
/// velocity crosses a Stribeck velocity within one sample interval (0.03
/// rad/s crossed at 5 rad/s^2 in 6 ms, under one interval at 100 Hz),
/// `f` at the sample alone catches the breakaway or misses it, and the
/// impulse it gives the motion, which the accelerations carry, is lost.
/// The mean keeps it.
fn interval_mean(f: &impl Fn(f64) -> f64, prev: f64, v: f64, next: f64) -> f64 {
    let half = |a: f64, b: f64| {
        let m = ((b - a).abs() / VELOCITY_STEP).ceil().clamp(1.0, 256.0) as usize;
        (0..m)
            .map(|i| f(a + (b - a) * (i as f64 + 0.5) / m as f64))
            .sum::<f64>()
            / m as f64
    };
    0.5 * (half(0.5 * (prev + v), v) + half(v, 0.5 * (v + next)))
}

/// Joint `j`'s lightly smoothed velocity ([`Signals::qd_light_at`]) over
/// samples `from..to` and the sample either side of them that the record
/// has: the first sample's index and the values.
fn light<const N: usize>(sig: &Signals<N>, j: usize, from: usize, to: usize) -> Light {
    let first = from.saturating_sub(1);
    let end = to.saturating_add(1).min(sig.t.len());
    Light {
        first,
        v: (first..end).map(|k| sig.qd_light_at(k, j)).collect(),
    }
}

/// A stretch of one joint's lightly smoothed velocity ([`light`]).
struct Light {
    first: usize,
    v: Vec<f64>,
}

/// Law `i` of the lightly smoothed velocity `v` (a stretch holding samples
/// `k - 1..=k + 1`, those the record has), averaged over sample `k`'s
/// interval ([`interval_mean`]); zero where the velocity is not finite, a
/// neighbour that is not (or is past the record's end) standing in for
/// itself.
fn raw(v: &Light, i: usize, k: usize) -> f64 {
    let x = v.v[k - v.first];
    if !x.is_finite() {
        return 0.0;
    }
    let near = |i: Option<usize>| {
        i.and_then(|i| v.v.get(i - v.first))
            .copied()
            .filter(|y| y.is_finite())
            .unwrap_or(x)
    };
    interval_mean(&|u| law(i, u), near(k.checked_sub(1)), x, near(Some(k + 1)))
}

/// The derivative of the filter that makes a force of its running
/// integrals what the residual shows (`force_filter.rs`).
fn order<const N: usize>(sig: &Signals<N>) -> usize {
    if sig.qd_measured {
        1
    } else {
        2
    }
}

/// Where each [`RowSeries`] is told from another (the thread's chunk
/// cache is keyed by it).
static NEXT_ID: AtomicU64 = AtomicU64::new(0);

/// Chunks of law values a thread keeps (a correction of a Stribeck
/// friction reads two laws at every sample).
const SLOTS: usize = 4;

/// One chunk of one law at one joint, recomputed.
struct Slot {
    id: u64,
    law: usize,
    joint: usize,
    chunk: usize,
    /// The chunk's first sample.
    first: usize,
    values: Vec<f64>,
}

thread_local! {
    /// The chunks this thread recomputed last (first in, first out).
    static CACHE: RefCell<Vec<Slot>> = const { RefCell::new(Vec::new()) };
}

/// The friction laws' columns and the once-more smoothed accelerations of
/// one record: kept at the fit's rows, recomputed elsewhere (see the
/// module's docs). Read with the [`Signals`] they were made from.
#[derive(Debug, Clone)]
pub struct RowSeries<const N: usize> {
    /// Tells this record's series from another's in the chunk cache.
    id: u64,
    /// The rows (sample indices, increasing).
    rows: Vec<usize>,
    /// Per row: the smoothed accelerations, then every law.
    at_rows: Vec<[SVector<f64, N>; LAWS + 1]>,
    /// Per chunk, law and joint: the running integrals at the first
    /// sample the chunk's filter reads.
    carries: Vec<[[Carry; N]; LAWS]>,
    /// Samples a chunk.
    chunk: usize,
}

impl<const N: usize> RowSeries<N> {
    /// The series of `sig`, kept at `rows` (increasing sample indices),
    /// recomputed `chunk` samples at a time elsewhere (0: the default).
    pub fn new(sig: &Signals<N>, rows: &[usize], chunk: usize) -> Self {
        let n = sig.t.len();
        let chunk = if chunk == 0 { CHUNK } else { chunk };
        let h = sig.sg.half();
        let count = n.div_ceil(chunk);
        let starts: Vec<usize> = (0..count).map(|c| (c * chunk).saturating_sub(h)).collect();
        let mut carries = vec![[[Carry::default(); N]; LAWS]; count];
        let mut at_rows = vec![[SVector::<f64, N>::zeros(); LAWS + 1]; rows.len()];
        for (r, &k) in rows.iter().enumerate() {
            for j in 0..N {
                at_rows[r][0][j] = smoothed_qdd(sig, k, j);
            }
        }
        for j in 0..N {
            let v = light(sig, j, 0, n);
            for i in 0..LAWS {
                let mut carry = Carry::default();
                let mut next = 0;
                let mut running = Vec::with_capacity(n);
                for k in 0..n {
                    while next < count && starts[next] == k {
                        carries[next][i][j] = carry;
                        next += 1;
                    }
                    running.push(carry.step(raw(&v, i, k), sig.dt, sig.qd_measured));
                }
                let col = sig.sg.apply(&running, order(sig));
                for (r, &k) in rows.iter().enumerate() {
                    at_rows[r][1 + i][j] = col[k];
                }
            }
        }
        RowSeries {
            id: NEXT_ID.fetch_add(1, Ordering::Relaxed),
            rows: rows.to_vec(),
            at_rows,
            carries,
            chunk,
        }
    }

    /// Law `i` ([`coulomb_law`], [`stribeck_law`]) of joint `j` at sample
    /// `k`, filtered as the residual shows a force of it; NaN within the
    /// filter's half-width of the record's ends.
    pub fn law(&self, sig: &Signals<N>, i: usize, k: usize, j: usize) -> f64 {
        if let Ok(r) = self.rows.binary_search(&k) {
            return self.at_rows[r][1 + i][j];
        }
        self.cached(sig, i, k, j)
    }

    /// Series `i` (a law below [`LAWS`], the smoothed accelerations at
    /// [`LAWS`]) of joint `j` at sample `k` from this thread's chunk
    /// cache, its chunk recomputed when not there.
    fn cached(&self, sig: &Signals<N>, i: usize, k: usize, j: usize) -> f64 {
        let c = k / self.chunk;
        CACHE.with(|cache| {
            let mut cache = cache.borrow_mut();
            let hit = cache
                .iter()
                .find(|s| s.id == self.id && s.law == i && s.joint == j && s.chunk == c);
            if let Some(s) = hit {
                return s.values[k - s.first];
            }
            let (first, values) = if i < LAWS {
                self.recompute(sig, i, j, c)
            } else {
                self.recompute_qdd(sig, j, c)
            };
            let x = values[k - first];
            if cache.len() >= SLOTS {
                cache.remove(0);
            }
            cache.push(Slot {
                id: self.id,
                law: i,
                joint: j,
                chunk: c,
                first,
                values,
            });
            x
        })
    }

    /// Joint `j`'s acceleration at sample `k` smoothed once more (zero
    /// within the filter's half-width of the signals' range, the
    /// acceleration itself outside it).
    pub fn qdd(&self, sig: &Signals<N>, k: usize, j: usize) -> f64 {
        match self.rows.binary_search(&k) {
            Ok(r) => self.at_rows[r][0][j],
            Err(_) => self.cached(sig, LAWS, k, j),
        }
    }

    /// Joint `j`'s accelerations smoothed once more over chunk `c`: its
    /// first sample and values, from the accelerations over the stretch
    /// the chunk's windows read.
    fn recompute_qdd(&self, sig: &Signals<N>, j: usize, c: usize) -> (usize, Vec<f64>) {
        let n = sig.t.len();
        let h = sig.sg.half();
        let first = c * self.chunk;
        let end = first.saturating_add(self.chunk).min(n);
        let (from, to) = (first.saturating_sub(h), end.saturating_add(h).min(n));
        let qdd: Vec<f64> = (from..to).map(|k| sig.motion.qdd_at(k, j)).collect();
        let values = (first..end)
            .map(|k| smoothed_qdd_in(sig, &qdd, from, k))
            .collect();
        (first, values)
    }

    /// Law `i` of joint `j` over chunk `c`: its first sample and values.
    fn recompute(&self, sig: &Signals<N>, i: usize, j: usize, c: usize) -> (usize, Vec<f64>) {
        let n = sig.t.len();
        let h = sig.sg.half();
        let first = c * self.chunk;
        let end = first.saturating_add(self.chunk).min(n);
        let (from, to) = (first.saturating_sub(h), end.saturating_add(h).min(n));
        let mut carry = self.carries[c][i][j];
        let v = light(sig, j, from, to);
        let running: Vec<f64> = (from..to)
            .map(|k| carry.step(raw(&v, i, k), sig.dt, sig.qd_measured))
            .collect();
        let col = sig.sg.apply(&running, order(sig));
        (first, col[first - from..end - from].to_vec())
    }
}

/// Joint `j`'s acceleration at sample `k` smoothed once more over the
/// signals' range: as the filter over the range gives it, zero where its
/// window does not fit in the range (or it is not finite), the
/// acceleration itself outside the range.
fn smoothed_qdd<const N: usize>(sig: &Signals<N>, k: usize, j: usize) -> f64 {
    let h = sig.sg.half();
    let lo = k.saturating_sub(h);
    let hi = k.saturating_add(h + 1).min(sig.t.len()).max(k + 1);
    let qdd: Vec<f64> = (lo..hi).map(|i| sig.motion.qdd_at(i, j)).collect();
    smoothed_qdd_in(sig, &qdd, lo, k)
}

/// [`smoothed_qdd`] from the joint's accelerations `qdd` of samples `lo`
/// on (covering `k` and, inside the range, its window).
fn smoothed_qdd_in<const N: usize>(sig: &Signals<N>, qdd: &[f64], lo: usize, k: usize) -> f64 {
    let (a, z) = sig.range;
    let h = sig.sg.half();
    if k < a || k >= z {
        return qdd[k - lo];
    }
    if k < a + h || k + h >= z {
        return 0.0;
    }
    let y: f64 = sig
        .sg
        .weights(0)
        .iter()
        .zip(&qdd[k - h - lo..=k + h - lo])
        .map(|(w, x)| w * x)
        .sum();
    if y.is_finite() {
        y
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests;
