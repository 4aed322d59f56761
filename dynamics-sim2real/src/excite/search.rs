//! The optimiser: a (1+lambda) evolution strategy with a success-driven
//! step size, from the best of a few random starts, with a fixed seed.
//!
//! Why this and not a library: the constraints are met by construction
//! (every candidate is projected onto the rest conditions, each joint
//! scaled to fill the room its position, velocity and acceleration limits
//! leave, and all joints scaled down together until the efforts keep their
//! limits), so what is left is an unconstrained, non-smooth (a condition
//! number), moderately sized problem (`2 H N` coefficients, 70 for the
//! Panda) whose evaluations are independent and cheap enough to run in
//! parallel. A derivative-free strategy of forty lines fits it, keeps the
//! result the same for a seed on any number of threads (offspring are drawn
//! in order, evaluated in parallel, compared in order), and adds no
//! dependency; argmin's Nelder-Mead and particle swarm need the same
//! projection and do not evaluate in parallel.

use nalgebra::SVector;
use rayon::prelude::*;

use super::{
    check, room, separation_angles, BaseColumns, Clearances, Criterion, ExciteError, Figures,
    Fourier, Limits, Rival,
};
use crate::rng::Rng;
use dynamics_runtime::control::Reference;
use dynamics_runtime::Robot;

/// What the search needs to turn coefficients into a feasible motion and
/// its cost.
pub(crate) struct Problem<'a, R, const N: usize> {
    pub robot: &'a R,
    pub columns: &'a BaseColumns<N>,
    /// The limits with their margin.
    pub limits: Limits<N>,
    pub q0: SVector<f64, N>,
    pub period: f64,
    pub harmonics: usize,
    /// Times over one period where limits and the criterion are evaluated.
    pub grid: Vec<f64>,
    pub criterion: Criterion,
    /// Rival pairs to separate: when given, the cost is minus the
    /// smallest of their separation angles instead of the criterion.
    pub pairs: &'a [(Rival, Rival)],
    /// The clearance of the link frames to keep, if any.
    pub clearances: Option<&'a Clearances>,
}

/// Fraction of the room used, for peaks between grid points.
const SAFETY: f64 = 0.995;

impl<R: Robot<N> + Sync, const N: usize> Problem<'_, R, N> {
    /// The feasible motion of coefficients `x` (`None` when nothing moves).
    pub fn realise(&self, x: &[f64]) -> Option<Fourier<N>> {
        let mut f = Fourier::new(self.q0, self.period, self.harmonics);
        f.set_flat(x);
        f.to_rest();
        let s = room(&f, &self.grid, &self.limits) * SAFETY;
        if s.iter().all(|v| *v == 0.0) {
            return None;
        }
        f.scale(&s);
        // Efforts and clearances: not met by a per-joint scaling.
        let effort_ok = |g: f64| {
            let mut h = f.clone();
            h.scale(&SVector::repeat(g));
            let states: Vec<Reference<N>> = self.grid.iter().map(|&t| h.at(t)).collect();
            check(self.robot, &states, &self.limits).effort
                && self.clearances.is_none_or(|c| c.keeps(self.robot, &states))
        };
        if !effort_ok(1.0) {
            // The largest common factor that keeps the efforts and the
            // clearances (bisection; the start pose itself keeps them,
            // checked before the search, and its clearances are the
            // thresholds where it is closer than the clearance asked).
            let (mut lo, mut hi) = (0.0, 1.0);
            for _ in 0..12 {
                let mid = 0.5 * (lo + hi);
                if effort_ok(mid) {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            if lo == 0.0 {
                return None;
            }
            f.scale(&SVector::repeat(lo * SAFETY));
        }
        Some(f)
    }

    /// The criterion's figures of a motion over the grid.
    pub fn figures(&self, f: &Fourier<N>) -> Result<Figures, ExciteError> {
        let states: Vec<Reference<N>> = self.grid.iter().map(|&t| f.at(t)).collect();
        Figures::of(&self.columns.stack(self.robot, &states)?)
    }

    /// The separation angles of the pairs over the grid.
    pub fn angles(&self, f: &Fourier<N>) -> Result<Vec<f64>, ExciteError> {
        let states: Vec<Reference<N>> = self.grid.iter().map(|&t| f.at(t)).collect();
        separation_angles(self.robot, self.columns, self.pairs, &states)
    }

    /// The cost of coefficients `x` (infinite when nothing moves).
    fn cost(&self, x: &[f64]) -> f64 {
        let Some(f) = self.realise(x) else {
            return f64::INFINITY;
        };
        let c = if self.pairs.is_empty() {
            self.figures(&f).map(|fig| fig.cost(self.criterion))
        } else {
            self.angles(&f)
                .map(|a| -a.iter().fold(f64::INFINITY, |m, &v| m.min(v)))
        };
        c.ok().filter(|c| c.is_finite()).unwrap_or(f64::INFINITY)
    }
}

/// Random coefficients, harmonic `k` of standard deviation `1 / k`.
fn draw(rng: &mut Rng, n: usize, h: usize) -> Vec<f64> {
    (0..n * 2 * h)
        .map(|i| rng.normal() / (1 + (i % (2 * h)) / 2) as f64)
        .collect()
}

/// The outcome of the search.
pub(crate) struct Found {
    pub x: Vec<f64>,
    pub evaluations: usize,
}

/// Minimises the problem's cost within `budget` evaluations from `seed`.
pub(crate) fn search<R: Robot<N> + Sync, const N: usize>(
    p: &Problem<'_, R, N>,
    budget: usize,
    seed: u64,
) -> Found {
    const STARTS: usize = 16;
    const LAMBDA: usize = 8;
    let mut rng = Rng::new(seed);
    let h = p.harmonics;
    let dim = N * 2 * h;
    let starts: Vec<Vec<f64>> = (0..STARTS).map(|_| draw(&mut rng, N, h)).collect();
    let costs: Vec<f64> = starts.par_iter().map(|x| p.cost(x)).collect();
    let mut evaluations = STARTS;
    let (mut best, mut cost) = (starts[0].clone(), costs[0]);
    for (x, c) in starts.into_iter().zip(costs) {
        if c < cost {
            (best, cost) = (x, c);
        }
    }
    let norm = |x: &[f64]| x.iter().map(|v| v * v).sum::<f64>().sqrt().max(1e-300);
    let mut sigma = 0.3;
    while evaluations + LAMBDA <= budget && sigma > 1e-4 {
        let scale = sigma * norm(&best) / (dim as f64).sqrt();
        let offspring: Vec<Vec<f64>> = (0..LAMBDA)
            .map(|_| best.iter().map(|v| v + scale * rng.normal()).collect())
            .collect();
        let costs: Vec<f64> = offspring.par_iter().map(|x| p.cost(x)).collect();
        evaluations += LAMBDA;
        let (i, c) =
            costs.iter().enumerate().fold(
                (0, f64::INFINITY),
                |m, (i, &c)| if c < m.1 { (i, c) } else { m },
            );
        if c < cost {
            best = offspring[i].clone();
            cost = c;
            sigma = (sigma * 1.5).min(1.0);
        } else {
            sigma *= 0.8;
        }
    }
    Found {
        x: best,
        evaluations,
    }
}
