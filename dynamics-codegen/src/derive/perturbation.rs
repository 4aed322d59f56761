//! Perturbation Jacobians of the residual (vibration paper, eqs. 4-6):
//! `F(q, qd, qdd) = A qdd - Q(0) - Qqt1 - Qqt2 - U`. Linearised about a
//! nominal motion, `A dxdd + D dxd + K dx = dU` with `K = dF/dq` and
//! `D = dF/dqd`; with U held fixed these are the derivatives of the inverse
//! dynamics U(q, qd, qdd). Also `dF/dp` for the run-time parameters (the
//! regressor column of a parameter that enters linearly).

use dynamics_symbolic::{Graph, Id, Var};

use super::rnea_derivatives::Rigid;
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
///
/// D has a second form: the velocity terms `-(Qqt1 + Qqt2) = C qd` are a
/// quadratic form `c_i = sum_jk Gamma_ijk qd_j qd_k` with Christoffel
/// symbols symmetric in j, k, so `dc_i/dqd_j = 2 sum_k Gamma_ijk qd_k =
/// 2 C_ij`: `D = 2 C - d(extras)/dqd`, `extras` being the damping, friction
/// and spring forces of Q(0) (diagonal in qd).
///
/// `analytic` is (K, D) of the rigid body by the analytic Newton-Euler
/// derivatives (`rnea_derivatives.rs`), when the model allows them; minus
/// the derivatives of `extras` they are another form of each. Of all the
/// pairs (K, D), the one with the fewest operations together is kept (on a
/// tie, the exact derivatives); the flag says whether it is the analytic
/// one, in either matrix.
pub fn jacobians(
    tau: &[Id],
    analytic: Option<Rigid>,
    coriolis: &[Vec<Id>],
    extras: &[Id],
    n_params: usize,
    vars: Vars,
    g: &mut Graph,
) -> (Perturbation, bool) {
    let n = vars.n;
    let k: Vec<Vec<Id>> = tau
        .iter()
        .map(|&t| (0..n).map(|j| g.diff(t, vars.q(j))).collect())
        .collect();
    let by_diff: Vec<Vec<Id>> = tau
        .iter()
        .map(|&t| (0..n).map(|j| g.diff(t, vars.qd(j))).collect())
        .collect();
    let by_coriolis: Vec<Vec<Id>> = (0..n)
        .map(|i| {
            (0..n)
                .map(|j| {
                    let twice = g.scale(coriolis[i][j], 2.0);
                    let de = g.diff(extras[i], vars.qd(j));
                    g.sub(twice, de)
                })
                .collect()
        })
        .collect();
    let mut ks = vec![k];
    let mut ds = vec![by_diff, by_coriolis];
    if let Some(Rigid { k: ka, d: da, .. }) = analytic {
        let minus_extras = |g: &mut Graph, m: Vec<Vec<Id>>, var: &dyn Fn(usize) -> Var| {
            m.into_iter()
                .enumerate()
                .map(|(i, row)| {
                    row.into_iter()
                        .enumerate()
                        .map(|(j, x)| {
                            let de = g.diff(extras[i], var(j));
                            g.sub(x, de)
                        })
                        .collect()
                })
                .collect()
        };
        ks.push(minus_extras(g, ka, &|j| vars.q(j)));
        ds.push(minus_extras(g, da, &|j| vars.qd(j)));
    }
    // The cheapest pair (K and D share nodes).
    let mut best = (usize::MAX, 0, 0);
    for (a, k) in ks.iter().enumerate() {
        for (b, d) in ds.iter().enumerate() {
            let roots: Vec<Id> = k.iter().chain(d).flatten().copied().collect();
            let ops = g.count_ops(&roots).total();
            if ops < best.0 {
                best = (ops, a, b);
            }
        }
    }
    let analytic = best.1 == 1 || best.2 == 2;
    let k = ks.swap_remove(best.1);
    let d = ds.swap_remove(best.2);
    let dp = (0..n_params)
        .map(|p| tau.iter().map(|&t| g.diff(t, vars.param(p))).collect())
        .collect();
    (Perturbation { k, d, dp }, analytic)
}
