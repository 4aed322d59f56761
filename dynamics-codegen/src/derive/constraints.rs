//! Program constraints f(t, q) = 0 (dissertation, eqs. 2.39, 2.43-2.46): the
//! residual, its Jacobian J = df/dq, and the bias of its second time
//! derivative, `d2f/dt2 = J qdd + bias` with
//! `bias = qd^T (d2f/dq2) qd + 2 (d2f/dq dt) qd + d2f/dt2`, so that the
//! runtime can solve for the constraint forces that keep the motion on the
//! program.

use dynamics_symbolic::{Graph, Id};

use super::lower::lower;
use super::Vars;
use crate::model::Model;

/// One constraint's outputs, as roots.
pub struct ConstraintRoots {
    /// f(t, q).
    pub f: Id,
    /// df/dq_j.
    pub jacobian: Vec<Id>,
    /// The part of d2f/dt2 that does not multiply qdd.
    pub bias: Id,
}

/// Derives every constraint of the model.
pub fn constraints(model: &Model, vars: Vars, g: &mut Graph) -> Vec<ConstraintRoots> {
    let n = vars.n;
    let qd: Vec<Id> = (0..n).map(|i| g.var(vars.qd(i))).collect();
    model
        .constraints
        .iter()
        .map(|c| {
            let f = lower(&c.f, None, vars, g);
            let jacobian: Vec<Id> = (0..n).map(|j| g.diff(f, vars.q(j))).collect();
            let mut terms = Vec::new();
            for j in 0..n {
                for k in 0..n {
                    let d2 = g.diff(jacobian[j], vars.q(k));
                    terms.push(g.product(&[d2, qd[j], qd[k]]));
                }
                let djt = g.diff(jacobian[j], vars.time());
                let two = g.constant(2.0);
                terms.push(g.product(&[two, djt, qd[j]]));
            }
            let ft = g.diff(f, vars.time());
            terms.push(g.diff(ft, vars.time()));
            let bias = g.sum(&terms);
            ConstraintRoots { f, jacobian, bias }
        })
        .collect()
}
