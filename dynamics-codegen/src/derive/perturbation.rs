//! Perturbation Jacobians of the residual (seed 000, eqs. 4-6):
//! `F(q, qd, qdd) = A qdd - Q(0) - Qqt1 - Qqt2 - U`. Linearised about a
//! nominal motion, `A dxdd + D dxd + K dx = dU` with `K = dF/dq` and
//! `D = dF/dqd`; with U held fixed these are the derivatives of the inverse
//! dynamics U(q, qd, qdd). Also `dF/dp` for the run-time parameters (the
//! regressor column of a parameter that enters linearly).

use dynamics_symbolic::{Graph, Id};

use super::Vars;

/// K, D and the parameter sensitivities, as roots in the graph.
pub struct Perturbation {
    /// `k[i][j] = dU_i/dq_j`.
    pub k: Vec<Vec<Id>>,
    /// `d[i][j] = dU_i/dqd_j`.
    pub d: Vec<Vec<Id>>,
    /// `dp[p][i] = dU_i/dparam_p`.
    pub dp: Vec<Vec<Id>>,
}

/// Differentiates the inverse dynamics `tau` (one entry per coordinate).
pub fn jacobians(tau: &[Id], n_params: usize, vars: Vars, g: &mut Graph) -> Perturbation {
    let n = vars.n;
    let k = tau
        .iter()
        .map(|&t| (0..n).map(|j| g.diff(t, vars.q(j))).collect())
        .collect();
    let d = tau
        .iter()
        .map(|&t| (0..n).map(|j| g.diff(t, vars.qd(j))).collect())
        .collect();
    let dp = (0..n_params)
        .map(|p| tau.iter().map(|&t| g.diff(t, vars.param(p))).collect())
        .collect();
    Perturbation { k, d, dp }
}
