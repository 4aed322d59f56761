//! Inertial forces of the matrix Lagrange form (seed 001, eq. 2.41) and the
//! Christoffel Coriolis matrix, all from dA/dq_i.
//!
//! ```text
//! Qqt1_i = 1/2 qd^T (dA/dq_i) qd
//! Qqt2   = -sum_i (dA/dq_i) qd qd_i
//! C_ij   = sum_k 1/2 (dA_ij/dq_k + dA_ik/dq_j - dA_jk/dq_i) qd_k
//! ```
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

    let mut coriolis = vec![vec![g.constant(0.0); n]; n];
    for (i, row) in coriolis.iter_mut().enumerate() {
        for (j, cij) in row.iter_mut().enumerate() {
            let mut t = Vec::new();
            for k in 0..n {
                let s = g.sum(&[da[k][i][j], da[j][i][k]]);
                let gamma = g.sub(s, da[i][j][k]);
                t.push(g.product(&[half, gamma, qd[k]]));
            }
            *cij = g.sum(&t);
        }
    }
    Terms {
        qqt1,
        qqt2,
        coriolis,
    }
}
