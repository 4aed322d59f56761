//! Refining a motor-side fit (elasticity, backlash) from its best grid
//! point: a compass search on the logarithms of the parameters, each step
//! tried both ways, halved when no direction improves.

use crate::diagnose::candidates::MotorGuess;

/// Largest number of evaluations a refinement spends.
pub const BUDGET: usize = 120;

/// Minimises `cost` from `start` (cost `start_cost`) over motor inertia,
/// stiffness, damping and, for backlash, the half-width; returns the best
/// guess and its cost. `costs` prices several guesses at once (the two
/// directions of a step are priced together; the second is used, and
/// counted, only where the first does not improve, as when they are
/// tried one after the other).
pub fn refine(
    start: MotorGuess,
    start_cost: f64,
    backlash: bool,
    costs: impl Fn(&[MotorGuess]) -> Vec<f64>,
) -> (MotorGuess, f64) {
    let dims = if backlash { 4 } else { 3 };
    let (mut best, mut best_cost) = (start, start_cost);
    let mut step = 0.35f64; // ln(1.42): about the grid's spacing
    let mut spent = 0;
    while step > 0.005 && spent < BUDGET {
        let mut improved = false;
        for d in 0..dims {
            let trials = [1.0, -1.0].map(|sign: f64| scaled(&best, d, (sign * step).exp()));
            let c = costs(&trials);
            for (trial, c) in trials.iter().zip(c) {
                spent += 1;
                if c.is_finite() && c < best_cost {
                    (best, best_cost) = (*trial, c);
                    improved = true;
                    break;
                }
            }
        }
        if !improved {
            step *= 0.5;
        }
    }
    (best, best_cost)
}

/// `g` with parameter `d` (0 inertia, 1 stiffness, 2 damping, 3
/// half-width) multiplied by `f`.
pub(super) fn scaled(g: &MotorGuess, d: usize, f: f64) -> MotorGuess {
    let mut out = *g;
    match d {
        0 => out.jm *= f,
        1 => out.stiffness *= f,
        2 => out.damping *= f,
        _ => out.half_width *= f,
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_the_minimum_of_a_smooth_bowl() {
        let truth = MotorGuess {
            jm: 0.3,
            stiffness: 2000.0,
            damping: 1.5,
            half_width: 0.004,
        };
        let cost = |g: &MotorGuess| {
            (g.jm / truth.jm).ln().powi(2)
                + (g.stiffness / truth.stiffness).ln().powi(2)
                + (g.damping / truth.damping).ln().powi(2)
                + (g.half_width / truth.half_width).ln().powi(2)
        };
        let start = MotorGuess {
            jm: 0.4,
            stiffness: 1500.0,
            damping: 2.0,
            half_width: 0.005,
        };
        let (g, c) = refine(start, cost(&start), true, |gs| {
            gs.iter().map(cost).collect()
        });
        assert!(c < 0.02 * cost(&start), "cost {c}");
        assert!((g.stiffness / truth.stiffness - 1.0).abs() < 0.1);
    }
}
