//! Stage 4, derive: the model's equations of motion as expression DAGs.
//!
//! Frame poses are products of elementary transfer matrices
//! (`kinematics.rs`); A(q) comes from link Jacobians,
//! `sum m Jv^T Jv + Jw^T R I R^T Jw` (`inertia.rs`); Qqt1, Qqt2 and the
//! Christoffel Coriolis matrix from dA/dq_i (`coriolis.rs`); potential,
//! gravity and Q(0) from `forces.rs`. Everything lives in one hash-consed
//! [`Graph`], so terms shared between outputs are one node.

mod body_jacobian;
mod constraints;
mod coriolis;
mod crba;
mod element_tree;
mod forces;
mod fused;
#[cfg(test)]
mod golden;
mod inertia;
mod kinematics;
mod lower;
mod perturbation;
mod regressor;
mod rnea;
mod rnea_derivatives;
mod spatial;

use dynamics_symbolic::{Graph, Id, Var};

use crate::model::Model;

/// Numbering of the free variables of the graph.
#[derive(Clone, Copy)]
pub struct Vars {
    /// Number of coordinates.
    pub n: usize,
    /// Number of run-time parameters.
    pub n_params: usize,
}

impl Vars {
    /// q_i
    pub fn q(self, i: usize) -> Var {
        Var(i as u32)
    }
    /// qd_i
    pub fn qd(self, i: usize) -> Var {
        Var((self.n + i) as u32)
    }
    /// qdd_i
    pub fn qdd(self, i: usize) -> Var {
        Var((2 * self.n + i) as u32)
    }
    /// Run-time parameter k.
    pub fn param(self, k: usize) -> Var {
        Var((3 * self.n + k) as u32)
    }
    /// Time t (in constraint expressions).
    pub fn time(self) -> Var {
        Var((3 * self.n + self.n_params) as u32)
    }
    /// What a variable is: (kind, index); kind 0..=4 = q, qd, qdd, param, t.
    pub fn classify(self, v: Var) -> (usize, usize) {
        let i = v.0 as usize;
        if i < 3 * self.n {
            (i / self.n, i % self.n)
        } else if i < 3 * self.n + self.n_params {
            (3, i - 3 * self.n)
        } else {
            (4, 0)
        }
    }
}

/// A pose: rotation rows and translation.
#[derive(Clone)]
pub struct Pose {
    /// Rotation matrix, `r[row][col]`.
    pub r: [[Id; 3]; 3],
    /// Translation.
    pub p: [Id; 3],
}

/// Every derived output, as roots in `graph`.
pub struct Derived {
    /// The expression DAG.
    pub graph: Graph,
    /// Variable numbering.
    pub vars: Vars,
    /// A(q), full n x n (symmetric: `a[i][j] == a[j][i]`).
    pub a: Vec<Vec<Id>>,
    /// A as `motion_and_jacobians` computes it beside K and D (the same
    /// matrix, from the composite inertias of the analytic K, D where that
    /// is cheaper together with them).
    pub a_fused: Vec<Vec<Id>>,
    /// Qqt1 + Qqt2 as `motion_and_jacobians` computes it (see `a_fused`).
    pub qqt_fused: Vec<Id>,
    /// Qqt1.
    pub qqt1: Vec<Id>,
    /// Qqt2.
    pub qqt2: Vec<Id>,
    /// Qqt1 + Qqt2, by the cheaper derivation.
    pub qqt: Vec<Id>,
    /// Christoffel Coriolis matrix.
    pub coriolis: Vec<Vec<Id>>,
    /// g = dPi_gravity/dq.
    pub gravity: Vec<Id>,
    /// Q(0).
    pub q0: Vec<Id>,
    /// U = A qdd - Q(0) - Qqt1 - Qqt2.
    pub tau: Vec<Id>,
    /// Perturbation Jacobians K = dU/dq, D = dU/dqd and dU/dparam.
    pub perturbation: perturbation::Perturbation,
    /// Program constraints: residual, Jacobian, acceleration bias.
    pub constraints: Vec<constraints::ConstraintRoots>,
    /// T.
    pub kinetic: Id,
    /// Pi (gravity + springs).
    pub potential: Id,
    /// World pose of each link.
    pub frames: Vec<Pose>,
    /// World position of each named point, in model order.
    pub points: Vec<[Id; 3]>,
    /// Jacobian of each named point: `point_jacobians[k][row][col]`.
    pub point_jacobians: Vec<[Vec<Id>; 3]>,
    /// The inertial regressor and the nominal inertial parameters.
    pub regressor: regressor::Regressor,
}

/// Largest number of monomials an expression may expand to.
const EXPAND_LIMIT: usize = 256;

/// `e` as a canonical trigonometric polynomial (products distributed,
/// `sin^2 = 1 - cos^2`) when that takes fewer operations, else `e`.
fn smaller_expanded(g: &mut Graph, e: Id) -> Id {
    match g.expand(e, EXPAND_LIMIT) {
        Some(x) if g.count_ops(&[x]).total() <= g.count_ops(&[e]).total() => x,
        _ => e,
    }
}

/// Derives every output of the model.
pub fn derive(model: &Model) -> Derived {
    let n = model.joints.iter().filter(|j| j.coord.is_some()).count();
    let vars = Vars {
        n,
        n_params: model.params.len(),
    };
    let mut g = Graph::new();
    let kin = kinematics::frames(model, vars, &mut g);
    let jac = body_jacobian::body_jacobians(model, vars, &mut g);
    let a_jacobian = inertia::mass_matrix(model, &jac, vars, &mut g);
    // The composite-rigid-body form when it is cheaper.
    let a = match crba::mass_matrix(model, vars, &mut g) {
        Some(c) => {
            let flat = |m: &Vec<Vec<Id>>| -> Vec<Id> { m.iter().flatten().copied().collect() };
            if g.count_ops(&flat(&c)).total() < g.count_ops(&flat(&a_jacobian)).total() {
                c
            } else {
                a_jacobian
            }
        }
        None => a_jacobian,
    };
    let dyn_terms = coriolis::terms(&a, vars, &mut g);
    let f = forces::forces(model, &kin, vars, &mut g);

    // The non-gravity part of Q(0) (damping, friction, springs).
    let extras: Vec<Id> = (0..n).map(|i| g.add(f.q0[i], f.gravity[i])).collect();
    // Gravity: from the potential, or by Newton-Euler at rest, whichever is
    // cheaper.
    let only = |velocity, acceleration, gravity| rnea::Terms {
        velocity,
        acceleration,
        gravity,
    };
    let gravity = match rnea::inverse_dynamics(model, vars, only(false, false, true), &mut g) {
        Some(gr) if g.count_ops(&gr).total() < g.count_ops(&f.gravity).total() => gr,
        _ => f.gravity.clone(),
    };
    let q0: Vec<Id> = (0..n).map(|i| g.sub(extras[i], gravity[i])).collect();

    // Inverse dynamics: the matrix form A qdd - Q(0) - Qqt1 - Qqt2, or
    // Newton-Euler for the rigid body minus the extra forces, whichever is
    // cheaper.
    let mut matrix_form = Vec::with_capacity(n);
    for i in 0..n {
        let mut terms = Vec::with_capacity(n + 3);
        for (j, aij) in a[i].iter().enumerate() {
            let qdd = g.var(vars.qdd(j));
            terms.push(g.mul(*aij, qdd));
        }
        let rhs = g.sum(&[q0[i], dyn_terms.qqt1[i], dyn_terms.qqt2[i]]);
        let lhs = g.sum(&terms);
        matrix_form.push(g.sub(lhs, rhs));
    }
    let tau = match rnea::inverse_dynamics(model, vars, only(true, true, true), &mut g) {
        Some(rigid) => {
            let ne: Vec<Id> = (0..n).map(|i| g.sub(rigid[i], extras[i])).collect();
            if g.count_ops(&ne).total() < g.count_ops(&matrix_form).total() {
                ne
            } else {
                matrix_form
            }
        }
        None => matrix_form,
    };
    let constraint_roots = constraints::constraints(model, vars, &mut g);
    // Qqt1 + Qqt2 = -(Newton-Euler with velocities only), when cheaper than
    // the sum of the dA/dq forms.
    let qqt_sum: Vec<Id> = (0..n)
        .map(|i| g.add(dyn_terms.qqt1[i], dyn_terms.qqt2[i]))
        .collect();
    let qqt = match rnea::inverse_dynamics(model, vars, only(true, false, false), &mut g) {
        Some(c) => {
            let ne: Vec<Id> = c.iter().map(|&x| g.neg(x)).collect();
            if g.count_ops(&ne).total() < g.count_ops(&qqt_sum).total() {
                ne
            } else {
                qqt_sum
            }
        }
        None => qqt_sum,
    };
    // The analytic derivatives are tried on a copy of the graph: where they
    // lose, the graph (so the emitted code) is as if never tried.
    let jacobians = |analytic, g: &mut Graph| {
        let coriolis = &dyn_terms.coriolis;
        perturbation::jacobians(
            &tau,
            analytic,
            coriolis,
            &extras,
            model.params.len(),
            vars,
            g,
        )
    };
    let mut trial = g.clone();
    let (perturbation, rigid) = match rnea_derivatives::jacobians(model, vars, &mut trial) {
        Some(rigid) => {
            let terms = (rigid.a.clone(), rigid.bias.clone());
            match jacobians(Some(rigid), &mut trial) {
                (p, true) => {
                    g = trial;
                    (p, Some(terms))
                }
                (_, false) => (jacobians(None, &mut g).0, None),
            }
        }
        None => (jacobians(None, &mut g).0, None),
    };
    let (a_fused, qqt_fused) = fused::terms(
        fused::Shared {
            a: &a,
            qqt: &qqt,
            q0: &q0,
            gravity: &gravity,
        },
        rigid,
        &perturbation,
        &mut g,
    );
    let mut ke_terms = Vec::new();
    for i in 0..n {
        let qdi = g.var(vars.qd(i));
        for j in 0..n {
            let qdj = g.var(vars.qd(j));
            let t = g.product(&[a[i][j], qdi, qdj]);
            ke_terms.push(t);
        }
    }
    let half = g.constant(0.5);
    let ke_sum = g.sum(&ke_terms);
    let kinetic = g.mul(half, ke_sum);

    let mut points = Vec::new();
    let mut point_jacobians = Vec::new();
    for (l, link) in model.links.iter().enumerate() {
        for p in &link.points {
            let pos = kinematics::point_world(&kin[l], &p.at, vars, &mut g);
            let jac = std::array::from_fn(|r| (0..n).map(|j| g.diff(pos[r], vars.q(j))).collect());
            points.push(pos);
            point_jacobians.push(jac);
        }
    }
    let regressor = regressor::regressor(model, &jac, &kin, vars, &mut g);
    Derived {
        vars,
        regressor,
        a,
        a_fused,
        qqt_fused,
        qqt1: dyn_terms.qqt1,
        qqt2: dyn_terms.qqt2,
        qqt,
        coriolis: dyn_terms.coriolis,
        gravity,
        q0,
        tau,
        perturbation,
        constraints: constraint_roots,
        kinetic,
        potential: f.potential,
        frames: kin.into_iter().map(|k| k.pose).collect(),
        points,
        point_jacobians,
        graph: g,
    }
}
