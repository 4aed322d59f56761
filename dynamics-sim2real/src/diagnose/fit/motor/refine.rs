//! Refining a motor-side fit (elasticity, backlash) from its best grid
//! point: a compass search on the logarithms of the parameters, each step
//! tried both ways, halved when no direction improves.

use crate::diagnose::candidates::MotorGuess;

/// Largest number of evaluations a refinement spends.
pub const BUDGET: usize = 120;

/// Minimises `cost` from `start` (cost `start_cost`) over motor inertia,
/// stiffness, damping and, for backlash, the half-width; returns the best
/// guess and its cost.
///
/// The search is the plain compass search: each parameter in turn tried
/// up, then down, by the step, the first improvement taken before the next
/// parameter is tried; the step halved after a sweep without one. Its
/// trials are priced ahead, to keep `costs`' lanes full: the trials of
/// every parameter still to come in the sweep are priced together from the
/// current best, and those after an improvement are priced again from the
/// improved guess. A guess's price does not depend on its companions, so
/// the path, the result and the count of trials charged to the budget
/// (those the one-at-a-time search would have looked at) are those of the
/// search that prices two trials at a time.
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
        let mut d = 0;
        while d < dims {
            // Both trials of parameters d.., from the current best.
            let trials: Vec<MotorGuess> = (d..dims)
                .flat_map(|e| [1.0, -1.0].map(|sign: f64| scaled(&best, e, (sign * step).exp())))
                .collect();
            let priced = costs(&trials);
            let mut next = dims;
            for (i, trial) in trials.iter().enumerate() {
                spent += 1;
                let c = priced.get(i).copied().unwrap_or(f64::INFINITY);
                if c.is_finite() && c < best_cost {
                    (best, best_cost) = (*trial, c);
                    improved = true;
                    // The parameter after this one, priced afresh.
                    next = d + i / 2 + 1;
                    break;
                }
            }
            d = next;
        }
        if !improved {
            step *= 0.5;
        }
    }
    (best, best_cost)
}

/// Minimises `cost` over one positive parameter from `start` (cost
/// `start_cost`): a compass search on its logarithm, from a step of 0.35
/// down to 0.01, each step tried up, then down, the first improvement
/// taken and the step halved when neither improves. Priced ahead like
/// [`refine`]: the trials of the step and of up to three halvings to come
/// are priced together from the current value (a search that stops
/// improving halves its step several times running), with the same path
/// and result as a search pricing two trials at a time.
pub fn refine_one(start: f64, start_cost: f64, costs: impl Fn(&[f64]) -> Vec<f64>) -> (f64, f64) {
    let (mut x, mut best) = (start, start_cost);
    let mut step = 0.35f64;
    while step > 0.01 {
        let levels: Vec<f64> = std::iter::successors(Some(step), |s| Some(s * 0.5))
            .take_while(|&s| s > 0.01)
            .take(4)
            .collect();
        let trials: Vec<f64> = levels
            .iter()
            .flat_map(|s| [s.exp(), (-s).exp()].map(|f| x * f))
            .collect();
        let priced = costs(&trials);
        let moved = trials.iter().zip(&priced).position(|(_, &c)| c < best);
        match moved {
            Some(i) => {
                (x, best) = (trials[i], priced[i]);
                step = levels[i / 2];
            }
            None => step = levels.last().map_or(0.0, |s| s * 0.5),
        }
    }
    (x, best)
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

    /// The one-parameter search priced ahead walks the path of the plain
    /// one (two trials at a time), on a cost with ripples.
    #[test]
    fn one_parameter_priced_ahead_walks_the_plain_path() {
        let cost = |x: f64| (x / 0.02).ln().powi(2) + 0.05 * (40.0 * x.ln()).sin();
        for start in [0.001, 0.015, 0.02, 0.3] {
            let (mut x, mut best, mut step) = (start, cost(start), 0.35f64);
            while step > 0.01 {
                let mut moved = false;
                for f in [step.exp(), (-step).exp()] {
                    if cost(x * f) < best {
                        (x, best, moved) = (x * f, cost(x * f), true);
                        break;
                    }
                }
                if !moved {
                    step *= 0.5;
                }
            }
            let ahead = refine_one(start, cost(start), |xs| {
                xs.iter().map(|&x| cost(x)).collect()
            });
            assert_eq!(ahead, (x, best), "from {start}");
        }
    }

    /// The compass search two trials at a time, as written plainly.
    fn two_at_a_time(
        start: MotorGuess,
        start_cost: f64,
        dims: usize,
        cost: impl Fn(&MotorGuess) -> f64,
    ) -> (MotorGuess, f64, usize) {
        let (mut best, mut best_cost) = (start, start_cost);
        let (mut step, mut spent) = (0.35f64, 0);
        while step > 0.005 && spent < BUDGET {
            let mut improved = false;
            for d in 0..dims {
                for sign in [1.0, -1.0] {
                    let trial = scaled(&best, d, (sign * step).exp());
                    spent += 1;
                    let c = cost(&trial);
                    if c.is_finite() && c < best_cost {
                        (best, best_cost) = (trial, c);
                        improved = true;
                        break;
                    }
                }
            }
            if !improved {
                step *= 0.5;
            }
        }
        (best, best_cost, spent)
    }

    /// Pricing ahead changes nothing: on a bumpy cost with a region
    /// priced infinite, the same path to the same guess and cost, and the
    /// same number of evaluations charged (here under the budget, so the
    /// budget's stop is reached at the same sweep).
    #[test]
    fn pricing_ahead_walks_the_path_of_two_at_a_time() {
        let cost = |g: &MotorGuess| {
            let (a, b) = ((g.jm / 0.3).ln(), (g.stiffness / 2000.0).ln());
            let (c, d) = ((g.damping / 1.5).ln(), (g.half_width / 0.004).ln());
            if g.damping > 4.0 {
                return f64::INFINITY;
            }
            a * a + 2.0 * b * b + c * c + d * d + 0.3 * (7.0 * a).sin() * (5.0 * c).cos()
        };
        for (backlash, dims) in [(false, 3), (true, 4)] {
            for scale in [0.5, 1.0, 2.5] {
                let start = MotorGuess {
                    jm: 0.4 * scale,
                    stiffness: 1500.0 / scale,
                    damping: 2.0 * scale,
                    half_width: 0.005 * scale,
                };
                let calls = std::cell::Cell::new(0);
                let (g, c) = refine(start, cost(&start), backlash, |gs| {
                    calls.set(calls.get() + 1);
                    gs.iter().map(cost).collect()
                });
                let (g0, c0, spent) = two_at_a_time(start, cost(&start), dims, cost);
                assert_eq!((g, c), (g0, c0), "backlash {backlash}, scale {scale}");
                // Fewer calls than the two-at-a-time search's one a parameter.
                assert!(
                    calls.get() * 2 < spent,
                    "{} calls, {spent} trials",
                    calls.get()
                );
            }
        }
    }
}
