//! Effort scales that act on part of the effort are not candidates: the
//! selection resumes without them.
//!
//! A torque sensor's gain scales the gravity effort and the effort beside
//! it (inertia, Coriolis, the drive) alike; a mass the model places wrong
//! scales the gravity effort alone. An effort scale the selection chose is
//! split into those two parts ([`Pool::split_off`]) and must help each part
//! the data determine ([`whole_scale`]). Left out only in the confirmation
//! (`evaluate/confirm.rs`, rule 2), its place would stay empty: the other
//! effects of the set were chosen beside it, and a friction fitted beside
//! a stand-in scale need not hold without it. So such a scale leaves the
//! candidates here, as a link that leaves no body does (`bodies.rs`), and
//! the selection resumes without it.

use nalgebra::SVector;

use super::left_out::{LeftOut, Why};
use crate::diagnose::candidates::{whitened, Candidate, Prepared};
use crate::diagnose::numeric::correlation_time;
use crate::diagnose::select::pool::{model_lag, whole_scale, Pool, Solution};
use dynamics_runtime::Robot;

/// The model's effort beside gravity at the rows of a pool, whitened like
/// its columns: what an effort scale's column is split by.
#[derive(Debug, Clone)]
pub struct BesideGravity {
    /// Rows `row * joints + joint`, before the pool's weights.
    efforts: Vec<f64>,
    /// Joints.
    joints: usize,
    /// Factor on the split's standard deviations: the rows counted as the
    /// noise through the smoothing leaves them independent.
    inflate: f64,
}

impl BesideGravity {
    /// The nominal model's effort minus `robot`'s gravity effort at the
    /// rows of the training record `p`.
    pub fn of<R: Robot<N>, const N: usize>(robot: &R, p: &Prepared<N>) -> Self {
        let efforts = whitened(p, |k| {
            let e: SVector<f64, N> = p.sig.model[k] - robot.gravity(&p.sig.q(k));
            e
        });
        let spacing = p.rows.windows(2).map(|w| w[1] - w[0]).min().unwrap_or(1);
        BesideGravity {
            efforts,
            joints: N,
            inflate: correlation_time(p.sig.sg.weights(0), spacing).sqrt(),
        }
    }

    /// Whitened efforts given row by row (`row * joints + joint`).
    #[cfg(test)]
    pub fn given(efforts: Vec<f64>, joints: usize, inflate: f64) -> Self {
        BesideGravity {
            efforts,
            joints,
            inflate,
        }
    }

    /// The factor on a split's standard deviations at the pool's rows:
    /// the rows counted as the noise through the smoothing leaves them
    /// independent.
    pub fn inflate(&self) -> f64 {
        self.inflate
    }

    /// Joint `j`'s part alone, the other joints' rows zero.
    fn at(&self, j: usize) -> Vec<f64> {
        let n = self.joints.max(1);
        self.efforts
            .iter()
            .enumerate()
            .map(|(r, &v)| if r % n == j { v } else { 0.0 })
            .collect()
    }
}

/// The effort scales of `set` (fitted `sol`) that do not act on the whole
/// effort, their columns split by `beside` and the set refitted by
/// `solve`.
pub fn partial_scales(
    pool: &Pool,
    set: &[usize],
    sol: &Solution,
    beside: &BesideGravity,
    solve: impl Fn(&Pool, &[usize]) -> Solution + Copy,
) -> Vec<LeftOut> {
    (0..set.len())
        .filter_map(|i| partial_scale(pool, set, i, sol, beside, solve))
        .collect()
}

/// [`partial_scales`] of the term at position `at` of `set` alone: `None`
/// when it is no effort scale, or one of the whole effort.
pub fn partial_scale(
    pool: &Pool,
    set: &[usize],
    at: usize,
    sol: &Solution,
    beside: &BesideGravity,
    solve: impl Fn(&Pool, &[usize]) -> Solution,
) -> Option<LeftOut> {
    let t = *set.get(at)?;
    let Candidate::EffortScale(j) = pool.terms[t].fit.candidate else {
        return None;
    };
    let common = *sol.theta.get(at)?.first()?;
    let scales = model_lag(pool, set, at, &beside.at(j), beside.inflate, solve)?;
    (!whole_scale(common, &scales)).then(|| LeftOut {
        term: t,
        theta: sol.theta[at].clone(),
        std: sol.std[at].clone(),
        why: Why::PartOfTheEffort { common, scales },
    })
}
