//! Inertial forces of the matrix Lagrange form (dissertation, eq. 2.41) and the
//! Christoffel Coriolis matrix, all from dA/dq_i.
//!
//! ```text
//! Qqt1_i = 1/2 qd^T (dA/dq_i) qd
//! Qqt2   = -sum_i (dA/dq_i) qd qd_i
//! C_ij   = sum_k 1/2 (dA_ij/dq_k + dA_ik/dq_j - dA_jk/dq_i) qd_k
//!        = 1/2 (dA/dt + W - W^T)_ij,   W_ij = sum_k dA_ik/dq_j qd_k
//! ```
//! (whichever of the two groupings of C takes fewer operations).
//! so that `C qd = -(Qqt1 + Qqt2)` and `dA/dt - 2C` is skew-symmetric.

use dynamics_symbolic::{Graph, Id};

use super::Vars;

/// Qqt1, Qqt2 and C.
pub struct Terms {
    /// Qqt1.
    pub qqt1: Vec<Id>,
    /// Qqt2.
    pub qqt2: Vec<Id>,
    /// Christoffel C.
    pub coriolis: Vec<Vec<Id>>,
}

/// Derives the terms from A.
pub fn terms(a: &[Vec<Id>], vars: Vars, g: &mut Graph) -> Terms {
    let n = vars.n;
    // da[k][i][j] = dA_ij / dq_k (symmetric in i, j).
    let mut da = vec![vec![vec![g.constant(0.0); n]; n]; n];
    for (k, dak) in da.iter_mut().enumerate() {
        for i in 0..n {
            for j in i..n {
                let d = g.diff(a[i][j], vars.q(k));
                dak[i][j] = d;
                dak[j][i] = d;
            }
        }
    }
    let qd: Vec<Id> = (0..n).map(|i| g.var(vars.qd(i))).collect();
    let half = g.constant(0.5);

    let mut qqt1 = Vec::with_capacity(n);
    for dak in &da {
        let mut t = Vec::new();
        for i in 0..n {
            let sq = g.mul(qd[i], qd[i]);
            t.push(g.product(&[half, dak[i][i], sq]));
            for j in i + 1..n {
                t.push(g.product(&[dak[i][j], qd[i], qd[j]]));
            }
        }
        qqt1.push(g.sum(&t));
    }

    let mut qqt2 = Vec::with_capacity(n);
    for j in 0..n {
        let mut t = Vec::new();
        for (i, dai) in da.iter().enumerate() {
            for k in 0..n {
                t.push(g.product(&[dai[j][k], qd[k], qd[i]]));
            }
        }
        let s = g.sum(&t);
        qqt2.push(g.neg(s));
    }

    let direct = christoffel(&da, &qd, g);
    let regrouped = regrouped(&da, &qd, g);
    let count = |g: &Graph, c: &[Vec<Id>]| g.count_ops(&c.concat()).total();
    let coriolis = if count(g, &regrouped) < count(g, &direct) {
        regrouped
    } else {
        direct
    };
    Terms {
        qqt1,
        qqt2,
        coriolis,
    }
}

/// `C_ij = sum_k 1/2 (dA_ij/dq_k + dA_ik/dq_j - dA_jk/dq_i) qd_k`, term by term.
fn christoffel(da: &[Vec<Vec<Id>>], qd: &[Id], g: &mut Graph) -> Vec<Vec<Id>> {
    let n = qd.len();
    let half = g.constant(0.5);
    (0..n)
        .map(|i| {
            (0..n)
                .map(|j| {
                    let t: Vec<Id> = (0..n)
                        .map(|k| {
                            let s = g.sum(&[da[k][i][j], da[j][i][k]]);
                            let gamma = g.sub(s, da[i][j][k]);
                            g.product(&[half, gamma, qd[k]])
                        })
                        .collect();
                    g.sum(&t)
                })
                .collect()
        })
        .collect()
}

/// The same sum regrouped, `C = 1/2 (dA/dt + W - W^T)` with
/// `W_ij = sum_k dA_ik/dq_j qd_k` (the Jacobian of the momentum A qd), so
/// that dA/dt (symmetric) and W are each formed once: cheaper for 6-7
/// coordinates, dearer for 3.
fn regrouped(da: &[Vec<Vec<Id>>], qd: &[Id], g: &mut Graph) -> Vec<Vec<Id>> {
    let n = qd.len();
    let half = g.constant(0.5);
    let mut adot = vec![vec![g.constant(0.0); n]; n];
    for i in 0..n {
        for j in i..n {
            let t: Vec<Id> = (0..n).map(|k| g.mul(da[k][i][j], qd[k])).collect();
            let s = g.sum(&t);
            adot[i][j] = s;
            adot[j][i] = s;
        }
    }
    let w: Vec<Vec<Id>> = (0..n)
        .map(|i| {
            (0..n)
                .map(|j| {
                    let t: Vec<Id> = (0..n).map(|k| g.mul(da[j][i][k], qd[k])).collect();
                    g.sum(&t)
                })
                .collect()
        })
        .collect();
    (0..n)
        .map(|i| {
            (0..n)
                .map(|j| {
                    let s = g.sum(&[adot[i][j], w[i][j]]);
                    let twice = g.sub(s, w[j][i]);
                    g.mul(half, twice)
                })
                .collect()
        })
        .collect()
}
