//! The motor-side simulation behind elasticity, backlash and the stiff
//! rotor (`transmitted.rs` says what it models), run for several guesses at
//! once: the guesses of a grid, of a compass step or of a finite
//! difference share the measured signals and differ only in their
//! parameters, and one integration step is a chain of dependent
//! operations, so lanes integrated side by side keep the processor's
//! units busy where one lane waits on its own chain. Every lane does
//! exactly the operations, in the same order, of a simulation on its own:
//! its result does not depend on its companions.
//!
//! - here: the lanes' integration (two Runge-Kutta steps a sample);
//! - `transmitted.rs`: one guess's transmitted effort;
//! - `derivative.rs`: the coupling's force (spring or dead zone) and the
//!   lanes' state derivative, the link pulled back to the measured motion;
//! - `tests.rs`: the one-at-a-time simulation each lane must reproduce.

mod derivative;
pub mod stretches;
#[cfg(test)]
mod tests;
pub mod transmitted;

use std::cell::RefCell;
use std::f64::consts::PI;
use std::rc::Rc;

use crate::diagnose::candidates::MotorGuess;
use crate::diagnose::signals::Signals;
use crate::smoothing::SavitzkyGolay;
use derivative::{add, force, Lanes};
use nalgebra::SVector;
pub use stretches::Stretches;

/// Bandwidth with which the simulated link is pulled back to the measured
/// motion, Hz.
pub const OBSERVER_HZ: f64 = 3.0;

/// Lanes integrated side by side.
pub const LANES: usize = 8;

/// What a motor side at a joint is simulated on: a record's signals and
/// the nominal model's effort at the joint that the link answers to, the
/// signals' own ([`Signals::model`]) or with other effects' efforts added
/// to it (`fit::Against`, what the compound explanation searches a motor
/// side against).
pub trait Load<const N: usize>: Sync {
    /// The record's signals.
    fn signals(&self) -> &Signals<N>;

    /// What tells this model's efforts from another's on the same motion
    /// (0: the signals' own): a key for values kept made from them.
    fn model_key(&self) -> u64;

    /// The model's effort at joint `j` over samples `a..z` of the record.
    fn model_along(&self, j: usize, a: usize, z: usize) -> Vec<f64>;
}

impl<const N: usize> Load<N> for Signals<N> {
    fn signals(&self) -> &Signals<N> {
        self
    }

    fn model_key(&self) -> u64 {
        0
    }

    fn model_along(&self, j: usize, a: usize, z: usize) -> Vec<f64> {
        (a..z).map(|k| self.model[k][j]).collect()
    }
}

/// The raw transmitted effort (see `transmitted::motor_transmitted_raw`) of
/// every guess of `gs` at joint `j`, in their order, over the record's
/// range (NaN outside it); `compliance` per joint is the link's
/// acceleration per unit of its own effort (`Basis::compliance`).
pub fn transmitted_raw_many<const N: usize, L: Load<N> + ?Sized>(
    on: &L,
    j: usize,
    gs: &[MotorGuess],
    backlash: bool,
    compliance: &SVector<f64, N>,
) -> Vec<Vec<f64>> {
    let sig = on.signals();
    let n = sig.t.len();
    let (a, _) = sig.range;
    let track = Track::of(on, j, sig.range);
    in_lanes(sig, &track, j, gs, backlash, compliance, sig.range)
        .into_iter()
        .map(|span| {
            let mut whole = vec![f64::NAN; n];
            let m = span.len().min(n.saturating_sub(a));
            if let (Some(to), Some(from)) = (whole.get_mut(a..a + m), span.get(..m)) {
                to.copy_from_slice(from);
            }
            whole
        })
        .collect()
}

/// One guess's simulation over the stretches of a search: the raw
/// transmitted effort of each stretch (indexed from the stretch's first
/// sample; NaN everywhere when the simulation diverged), and the joint's
/// track over each.
pub struct Simulated<'a> {
    stretches: &'a Stretches,
    efforts: Vec<Vec<f64>>,
    tracks: &'a [Rc<Track>],
}

impl Simulated<'_> {
    /// The smoothed transmitted effort and the model's effort at the
    /// joint at each scored row, in the rows' order: `(effort, model)`.
    pub fn at_rows<'s>(&'s self, sg: &'s SavitzkyGolay) -> impl Iterator<Item = (f64, f64)> + 's {
        self.stretches
            .spans()
            .zip(self.efforts.iter().zip(self.tracks))
            .flat_map(move |((first, _, rows), (effort, track))| {
                rows.iter()
                    .map(move |&k| (sg.at(effort, 0, k - first), track.model[k - first]))
            })
    }
}

/// The simulation of every guess of `gs` over the `stretches`, each
/// handed to `reduce` as soon as its lanes are integrated and then
/// dropped: at most [`LANES`] guesses' worth of simulation held at once,
/// however many guesses (a grid holds dozens).
pub fn transmitted_each<const N: usize, T, L: Load<N> + ?Sized>(
    on: &L,
    j: usize,
    gs: &[MotorGuess],
    backlash: bool,
    compliance: &SVector<f64, N>,
    stretches: &Stretches,
    mut reduce: impl FnMut(&Simulated) -> T,
) -> Vec<T> {
    let sig = on.signals();
    let mut out = Vec::with_capacity(gs.len());
    for now in gs.chunks(LANES) {
        let mut each: Vec<Vec<Vec<f64>>> = vec![Vec::new(); now.len()];
        let mut tracks = Vec::new();
        for (first, end, _) in stretches.spans() {
            let track = Track::of(on, j, (first, end));
            let spans = in_lanes(sig, &track, j, now, backlash, compliance, (first, end));
            for (e, span) in each.iter_mut().zip(spans) {
                e.push(span);
            }
            tracks.push(track);
        }
        let tracks = &tracks[..];
        out.extend(each.into_iter().map(|efforts| {
            reduce(&Simulated {
                stretches,
                efforts,
                tracks,
            })
        }));
    }
    out
}

/// The guesses of `gs` integrated [`LANES`] at a time over samples
/// `span.0..span.1`, each result indexed from `span.0`; `track` is joint
/// `j`'s over the span.
fn in_lanes<const N: usize>(
    sig: &Signals<N>,
    track: &Track,
    j: usize,
    gs: &[MotorGuess],
    backlash: bool,
    compliance: &SVector<f64, N>,
    span: (usize, usize),
) -> Vec<Vec<f64>> {
    let mut out = Vec::with_capacity(gs.len());
    let mut rest = gs;
    let tr = track;
    while !rest.is_empty() {
        let take = rest.len().min(LANES);
        let (now, later) = rest.split_at(take);
        let c = compliance;
        match (take, backlash) {
            (1, false) => out.extend(lanes::<N, 1, false>(sig, tr, j, now, c, span)),
            (1, true) => out.extend(lanes::<N, 1, true>(sig, tr, j, now, c, span)),
            (2, false) => out.extend(lanes::<N, 2, false>(sig, tr, j, now, c, span)),
            (2, true) => out.extend(lanes::<N, 2, true>(sig, tr, j, now, c, span)),
            (_, false) => out.extend(lanes::<N, LANES, false>(sig, tr, j, now, c, span)),
            (_, true) => out.extend(lanes::<N, LANES, true>(sig, tr, j, now, c, span)),
        }
        rest = later;
    }
    out
}

/// Joint `j`'s smoothed position, velocity and acceleration and the
/// model's effort there over the samples of a span that lie in the
/// record, indexed from the span's first sample: made once for all the
/// lanes integrated over the span, and kept by the thread for the next
/// guesses simulated over it.
struct Track {
    q: Vec<f64>,
    qd: Vec<f64>,
    qdd: Vec<f64>,
    model: Vec<f64>,
}

/// Samples of tracks a thread keeps, in seconds of the record: what one
/// search simulates ([`stretches::SEARCH_SECONDS`], whole or in
/// stretches) and a quarter more; an optimum's simulation over a longer
/// record makes its track and drops it.
const KEPT_SECONDS: f64 = 1.25 * stretches::SEARCH_SECONDS;

/// Samples from which a track's series are made on the threads at once
/// (a search's stretches are shorter and many at a time already).
pub const ALONG_APART: usize = 1 << 16;

/// A kept track: the motion's id and the model's key, the joint, the
/// span.
type Kept = ((u64, u64), usize, (usize, usize), Rc<Track>);

thread_local! {
    /// The tracks this thread made last (first in, first out).
    static KEPT: RefCell<Vec<Kept>> = const { RefCell::new(Vec::new()) };
}

impl Track {
    /// Joint `j`'s track over `span` of the motion and model of `on`,
    /// kept or made.
    fn of<const N: usize, L: Load<N> + ?Sized>(
        on: &L,
        j: usize,
        span: (usize, usize),
    ) -> Rc<Track> {
        let sig = on.signals();
        let id = (sig.motion.id(), on.model_key());
        let most = (KEPT_SECONDS / sig.dt) as usize;
        let len = |s: (usize, usize)| s.1.saturating_sub(s.0);
        if len(span) > most {
            return Rc::new(Self::made(on, j, span));
        }
        let key = (id, j, span);
        let hit = KEPT.with(|kept| {
            let kept = kept.borrow();
            kept.iter()
                .find(|(i, jj, s, _)| (*i, *jj, *s) == key)
                .map(|(.., t)| Rc::clone(t))
        });
        if let Some(t) = hit {
            return t;
        }
        // (Made with the thread's tracks not borrowed: the making may wait
        // on other threads, and this one meanwhile run a simulation that
        // reads them.)
        let t = Rc::new(Self::made(on, j, span));
        KEPT.with(|kept| {
            let mut kept = kept.borrow_mut();
            while !kept.is_empty()
                && kept.iter().map(|x| len(x.2)).sum::<usize>() + len(span) > most
            {
                kept.remove(0);
            }
            kept.push((id, j, span, Rc::clone(&t)));
        });
        t
    }

    fn made<const N: usize, L: Load<N> + ?Sized>(on: &L, j: usize, (a, z): (usize, usize)) -> Self {
        let sig = on.signals();
        let z = z.min(sig.t.len());
        let m = &sig.motion;
        let z = z.max(a);
        let stretch = |d: usize| m.joint_stretch(d, j, a, z);
        if z - a < ALONG_APART {
            return Track {
                q: stretch(0),
                qd: stretch(1),
                qdd: stretch(2),
                model: on.model_along(j, a, z),
            };
        }
        // A long span (a whole record): the four made on the threads.
        let ((q, qd), (qdd, model)) = rayon::join(
            || rayon::join(|| stretch(0), || stretch(1)),
            || rayon::join(|| stretch(2), || on.model_along(j, a, z)),
        );
        Track { q, qd, qdd, model }
    }
}

/// `L` lanes side by side, `B` backlash, over samples `a..z`, each result
/// indexed from `a`; `gs` has 1 to `L` guesses (the last repeated to fill
/// the lanes, its copies dropped); `track` is joint `j`'s motion over
/// them.
fn lanes<const N: usize, const L: usize, const B: bool>(
    sig: &Signals<N>,
    track: &Track,
    j: usize,
    gs: &[MotorGuess],
    compliance: &SVector<f64, N>,
    (a, z): (usize, usize),
) -> Vec<Vec<f64>> {
    let n = z.saturating_sub(a);
    let used = gs.len().min(L);
    let nan = || vec![vec![f64::NAN; n]; used];
    if z <= a + 1 || used == 0 || sig.t.len() < z {
        return nan();
    }
    let g: [MotorGuess; L] = std::array::from_fn(|l| gs[l.min(used - 1)]);
    let (k_, c_, w_) = (
        g.map(|g| g.stiffness),
        g.map(|g| g.damping),
        g.map(|g| g.half_width),
    );
    // One buffer per guess (the copies filling the lanes store nothing).
    let mut out = nan();
    let (q, qd, qdd, model) = (&track.q, &track.qd, &track.qdd, &track.model);
    let load = model[0];
    // State per lane: motor angle, motor rate, link angle, link rate.
    let mut x = [[0.0f64; L]; 4];
    for l in 0..L {
        x[0][l] = if B {
            q[0] + load.signum() * (g[l].half_width + load.abs() / g[l].stiffness)
        } else {
            q[0] + load / g[l].stiffness
        };
        x[1][l] = qd[0];
        x[2][l] = q[0];
        x[3][l] = qd[0];
    }
    let mut dead = [false; L];
    let wo = 2.0 * PI * OBSERVER_HZ;
    let (wo2, two_wo) = (wo * wo, 2.0 * wo);
    // Two RK4 steps a sample: omega h <= 0.8 up to the 250 Hz stiff rotor,
    // well inside RK4's stability (|R(z)| < 1 for |z| < 2.78 on the
    // imaginary axis).
    const SUB: usize = 2;
    // A multiply, not a divide, on the integration's dependent chain.
    let inv_jm = g.map(|g| 1.0 / g.jm);
    let (t, tau_raw) = (&sig.t[..], sig.tau_raw());
    for k in a..z {
        for (l, o) in out.iter_mut().enumerate() {
            o[k - a] = force::<L, B>(k_[l], c_[l], w_[l], x[0][l] - x[2][l], x[1][l] - x[3][l]);
        }
        if k + 1 >= z {
            break;
        }
        let r = k - a;
        let (q0, v0, a0, m0) = (q[r], qd[r], qdd[r], model[r]);
        let (q1, v1, a1, m1) = (q[r + 1], qd[r + 1], qdd[r + 1], model[r + 1]);
        let h = (t[k + 1] - t[k]) / SUB as f64;
        let tau = tau_raw[k][j];
        // The link's response to its own effort.
        let inv_i = compliance[j];
        // The measured motion and the model's effort at fraction s of the
        // interval.
        let at = |s: f64| -> [f64; 4] {
            [
                q0 + (q1 - q0) * s,
                v0 + (v1 - v0) * s,
                a0 + (a1 - a0) * s,
                m0 + (m1 - m0) * s,
            ]
        };
        let lane = Lanes {
            k: &k_,
            c: &c_,
            w: &w_,
            inv_jm: &inv_jm,
            inv_i,
            wo2,
            two_wo,
            tau,
        };
        for i in 0..SUB {
            let s0 = i as f64 / SUB as f64;
            let sm = (i as f64 + 0.5) / SUB as f64;
            let s1 = (i + 1) as f64 / SUB as f64;
            let (m0s, mms, m1s) = (at(s0), at(sm), at(s1));
            let k1 = lane.derivative::<B>(&x, &m0s);
            let k2 = lane.derivative::<B>(&add(&x, &k1, 0.5 * h), &mms);
            let k3 = lane.derivative::<B>(&add(&x, &k2, 0.5 * h), &mms);
            let k4 = lane.derivative::<B>(&add(&x, &k3, h), &m1s);
            for c in 0..4 {
                for l in 0..L {
                    x[c][l] += h / 6.0 * (k1[c][l] + 2.0 * k2[c][l] + 2.0 * k3[c][l] + k4[c][l]);
                }
            }
        }
        let mut all_dead = true;
        for l in 0..L {
            if !x[0][l].is_finite() || !x[1][l].is_finite() || !x[2][l].is_finite() {
                dead[l] = true;
                // (A diverged lane goes on from rest, its result dropped.)
                for row in x.iter_mut() {
                    row[l] = 0.0;
                }
            }
            all_dead &= dead[l];
        }
        if all_dead {
            break;
        }
    }
    for (l, o) in out.iter_mut().enumerate() {
        if dead[l] {
            o.fill(f64::NAN);
        }
    }
    out
}
