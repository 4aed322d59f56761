//! Fitting: every candidate fitted on its own to the training record's
//! torque residual.
//!
//! - `one.rs`: a fit ([`Fit`]) and the residual it leaves;
//! - `against.rs`: what a fit is made against (a record's residual, or
//!   what other effects leave of it, made where read);
//! - here: the fit of one candidate (linear ones by sign-constrained least
//!   squares on their columns) and of every candidate on all cores;
//! - `motor/`: the candidates that simulate a motor side (elasticity,
//!   backlash, the stiff rotor): grid search, refinement, spreads;
//! - `motor_sim/`: the motor-side simulation itself, several guesses in
//!   lanes;
//! - `window/`: effects that start and stop, fitted on the window the
//!   residual shows.

mod against;
mod motor;
mod motor_sim;
mod one;
mod window;

use std::sync::atomic::{AtomicUsize, Ordering};

use nalgebra::{DMatrix, DVector};
use rayon::prelude::*;

use crate::diagnose::candidates::{Candidate, Prepared, EFFORT_SCALE_LIMIT};
use crate::diagnose::numeric::constrained_least_squares;
use crate::diagnose::Options;
use dynamics_runtime::Robot;

pub use against::Against;
/// The motor-side simulation, for a baseline to undo a known motor side
/// on data (`crate::baseline::undo`).
pub(crate) use motor_sim::transmitted::motor_transmitted_raw;
#[cfg(test)]
pub(crate) use motor_sim::Load;
pub use one::{fixed_column, fixed_column_against, Fit};
pub use window::{
    corrected, corrected_in, corrected_rows, fit_windowed, holdout_window_in, inside, window_of,
    windowed, Windows,
};

/// Fits `c` to the residual of `p`.
pub fn fit<R: Robot<N>, const N: usize>(c: Candidate, p: &Prepared<N>) -> Fit {
    fit_against::<R, N>(c, &Against::record(p))
}

/// Fits `c` to the residual of `on` (a motor side simulated against its
/// model; a linear candidate's columns are those of its record).
pub fn fit_against<R: Robot<N>, const N: usize>(c: Candidate, on: &Against<N>) -> Fit {
    let p = on.p;
    let params = c.linear_parameters();
    if params.is_empty() {
        return motor::fit_motor::<R, N>(c, on);
    }
    let m = params.len();
    let n = p.n();
    let mut x = DMatrix::zeros(n, m);
    let mut y = DVector::zeros(n);
    for (r, &k) in p.rows.iter().enumerate() {
        let cols = c.columns(&p.sig, &p.basis, k);
        let res = on.residual_row(r);
        for j in 0..N {
            let w = 1.0 / p.sig.floor[j];
            y[r * N + j] = res[j] * w;
            for i in 0..m {
                x[(r * N + j, i)] = cols[i][j] * w;
            }
        }
    }
    let nonneg: Vec<bool> = params.iter().map(|p| p.1).collect();
    let mut f = constrained_least_squares(&x, &y, &nonneg);
    // An effort scale beyond its limit is held there, as in the compound
    // explanation (`prior::EFFORT_SCALE_LIMIT`).
    if let (Candidate::EffortScale(_), [s]) = (c, f.theta.as_slice()) {
        if s.abs() > EFFORT_SCALE_LIMIT {
            let held = EFFORT_SCALE_LIMIT.copysign(*s);
            f.sse = (&y - x.column(0) * held).norm_squared();
            f.theta = vec![held];
            f.std = vec![0.0];
        }
    }
    // A payload that takes away more than the tip body's mass is held
    // there (`columns::lower_bounds`), its centre of mass refitted.
    let held = -p.basis.tip_mass;
    if matches!(c, Candidate::Payload | Candidate::PayloadCom(_)) && f.theta[0] < held {
        let rest = y.clone() - x.column(0) * held;
        let g = constrained_least_squares(&x.columns(1, m - 1).into_owned(), &rest, &nonneg[1..]);
        f.sse = if m > 1 { g.sse } else { rest.norm_squared() };
        f.theta = std::iter::once(held).chain(g.theta).collect();
        f.std = std::iter::once(0.0).chain(g.std).collect();
    }
    let linear = Fit {
        candidate: c,
        theta: f.theta,
        std: f.std,
        motor: None,
        motor_std: None,
        sse: f.sse,
        k: m,
    };
    match c {
        Candidate::Armature(j) => motor::stiff_rotor(linear, j, on),
        _ => linear,
    }
}

/// Fits `candidates` to `p` on the current rayon pool, calling
/// `progress(done, total)` after each fit; the fits in the order of
/// `candidates`.
pub fn fit_all<R: Robot<N> + Clone + Sync, const N: usize>(
    candidates: &[Candidate],
    p: &Prepared<N>,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Vec<Fit> {
    let total = candidates.len();
    let done = AtomicUsize::new(0);
    candidates
        .par_iter()
        .with_max_len(1)
        .map(|&c| {
            let f = fit::<R, N>(c, p);
            progress(done.fetch_add(1, Ordering::Relaxed) + 1, total);
            f
        })
        .collect()
}

/// Every candidate fitted on its own, and the windows of those that start
/// and stop.
#[derive(Debug, Clone)]
pub struct Fitted {
    /// One fit per candidate, in the candidates' order (a windowed effect
    /// limited to its window).
    pub fits: Vec<Fit>,
    /// The candidates found limited in time, with their training windows.
    pub windows: Windows,
}

/// Fits every candidate to `p` (`progress(done, total)` after each), then
/// limits to its window each that starts and stops (`window/`).
pub fn fit_candidates<R: Robot<N> + Clone + Sync, const N: usize>(
    candidates: &[Candidate],
    p: &Prepared<N>,
    options: &Options,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Fitted {
    let fits = fit_all::<R, N>(candidates, p, progress);
    let (fits, windows) = windowed(fits, p, options);
    Fitted { fits, windows }
}
