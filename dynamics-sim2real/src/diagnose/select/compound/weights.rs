//! Feasible weighting of the compound explanation's rows. The rows are
//! whitened by the sensors' noise floor, which is the error left only once
//! the model is complete. On a real robot the chosen set leaves model
//! error that no candidate explains, joint by joint far above the floor
//! (a 200 Hz log of smooth efforts: 1e3-1e4 times), and whitening by the
//! floor then weighs the joints by how quiet their sensors are rather
//! than by how well the model can be fitted there: one joint's leftover
//! rules the fit and the criterion, the others' effects never earn their
//! margin. Where the set leaves a joint above its floor, that joint's
//! error variance is the residual's: its rows are weighed by `1 / rms`
//! (in floor units, the floor kept as the least), and the selection
//! resumes under these weights until they settle. A set that leaves every
//! joint within its floor (a complete model) is not touched.

use crate::diagnose::select::pool::{Pool, Solution};

/// Reweighting rounds at most.
pub const REWEIGHTS: usize = 3;

/// Relative change of every joint's weight under which the weights are
/// settled.
pub const SETTLED: f64 = 0.1;

/// The joints' weights that `set` calls for, `None` when they are
/// settled (within [`SETTLED`] of the pool's).
pub fn weights(pool: &Pool, set: &[usize]) -> Option<Vec<f64>> {
    let sol = pool.solve(set);
    let rms = pool.floor_rms(&pool.residual(set, &sol));
    let w: Vec<f64> = rms.iter().map(|r| 1.0 / r.max(1.0)).collect();
    let settled = w
        .iter()
        .zip(pool.weights())
        .all(|(a, b)| (a / b - 1.0).abs() < SETTLED);
    (!settled).then_some(w)
}

/// Whether the residual of `set` is within `ratio` times the noise floor
/// on every joint.
pub fn within_noise(pool: &Pool, set: &[usize], sol: &Solution, ratio: f64) -> bool {
    pool.floor_rms(&pool.residual(set, sol))
        .iter()
        .all(|&r| r <= ratio)
}

/// Joints whose residual under `set` is above `ratio` times the floor.
pub fn loud_joints(pool: &Pool, set: &[usize], sol: &Solution, ratio: f64) -> Vec<usize> {
    let rms = pool.floor_rms(&pool.residual(set, sol));
    (0..rms.len()).filter(|&j| rms[j] > ratio).collect()
}
