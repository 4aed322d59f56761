//! Potential energy, gravity torques and the generalized forces Q(0).
//!
//! `Pi = -sum_b m_b gravity . c_b + sum_springs 1/2 c (q - l0)^2` over the
//! bodies that move (a body welded to the base adds a constant and is left
//! out, as Pinocchio does). `Q(0)_i = -dPi/dq_i - b_i qd_i
//! - Fc_i tanh(qd_i / eps_i)`, the spring force `c (l0 - q)` being part of
//! `-dPi/dq` (dissertation, sec. 3.1.2). A mimic joint's forces act at its own
//! position `m q_i + o` and speed `m qd_i` and enter Q(0)_i times m.

use dynamics_symbolic::{Graph, Id};

use super::kinematics::{point_world, LinkKin};
use super::lower::lower;
use super::Vars;
use crate::model::{Follow, Model};

/// Default velocity scale of the smooth Coulomb sign, rad/s or m/s.
pub const COULOMB_SMOOTHING: f64 = 1e-3;

/// Potential, gravity torques and Q(0).
pub struct Forces {
    /// Pi (gravity + springs).
    pub potential: Id,
    /// dPi_gravity/dq.
    pub gravity: Vec<Id>,
    /// Q(0).
    pub q0: Vec<Id>,
}

/// Whether some joint between the root and link `l` has a coordinate.
fn moves(model: &Model, mut l: usize) -> bool {
    while let Some(j) = model.links[l].joint {
        if model.joints[j].position().is_some() {
            return true;
        }
        l = model.joints[j].parent;
    }
    false
}

/// Derives the forces.
pub fn forces(model: &Model, kin: &[LinkKin], vars: Vars, g: &mut Graph) -> Forces {
    let n = vars.n;
    let grav = model.gravity.map(|x| g.constant(x));
    let mut pg_terms = Vec::new();
    for (l, link) in model.links.iter().enumerate() {
        let mut bodies = Vec::new();
        if let Some(inert) = &link.inertial {
            bodies.push((&inert.mass, &inert.com));
        }
        for p in &link.points {
            if let Some(m) = &p.mass {
                bodies.push((m, &p.at));
            }
        }
        for (mass, at) in bodies {
            let c = point_world(&kin[l], at, vars, g);
            if !moves(model, l) {
                continue; // welded to the base: constant energy, left out as Pinocchio does
            }
            let m = lower(mass, None, vars, g);
            let t: Vec<Id> = (0..3).map(|r| g.mul(grav[r], c[r])).collect();
            let dot = g.sum(&t);
            let e = g.mul(m, dot);
            pg_terms.push(g.neg(e));
        }
    }
    let pi_sum = g.sum(&pg_terms);
    let pi_gravity = super::smaller_expanded(g, pi_sum);
    let gravity: Vec<Id> = (0..n)
        .map(|i| {
            let d = g.diff(pi_gravity, vars.q(i));
            super::smaller_expanded(g, d)
        })
        .collect();

    let mut spring_terms = Vec::new();
    let mut q0 = Vec::with_capacity(n);
    for i in 0..n {
        q0.push(g.neg(gravity[i]));
    }
    for joint in &model.joints {
        // The joint's own position and speed: `m q_i + o` and `m qd_i` for a
        // mimic joint (m = 1, o = 0 otherwise); its force f acts on
        // coordinate i as `m f` (virtual work).
        let Some(Follow {
            coord: i,
            multiplier,
            offset,
        }) = joint.position()
        else {
            continue;
        };
        let mut q = g.var(vars.q(i));
        let mut qd = g.var(vars.qd(i));
        if multiplier != 1.0 {
            q = g.scale(q, multiplier);
            qd = g.scale(qd, multiplier);
        }
        if offset != 0.0 {
            let o = g.constant(offset);
            q = g.add(q, o);
        }
        let mut extra = Vec::new();
        if let Some((c, l0)) = &joint.forces.spring {
            let c = lower(c, None, vars, g);
            let l0 = lower(l0, None, vars, g);
            let stretch = g.sub(q, l0);
            let sq = g.mul(stretch, stretch);
            let half = g.constant(0.5);
            spring_terms.push(g.product(&[half, c, sq]));
            let rest_minus = g.sub(l0, q);
            extra.push(g.mul(c, rest_minus));
        }
        if let Some(b) = &joint.forces.damping {
            let b = lower(b, None, vars, g);
            let f = g.mul(b, qd);
            extra.push(g.neg(f));
        }
        if let Some(fc) = &joint.forces.coulomb {
            let fc = lower(fc, None, vars, g);
            let eps = match &joint.forces.coulomb_smoothing {
                Some(s) => lower(s, None, vars, g),
                None => g.constant(COULOMB_SMOOTHING),
            };
            let x = g.div(qd, eps);
            let sign = g.tanh(x);
            let f = g.mul(fc, sign);
            extra.push(g.neg(f));
        }
        if !extra.is_empty() {
            if multiplier != 1.0 {
                let f = g.sum(&extra);
                extra = vec![g.scale(f, multiplier)];
            }
            extra.push(q0[i]);
            q0[i] = g.sum(&extra);
        }
    }
    spring_terms.push(pi_gravity);
    let potential = g.sum(&spring_terms);
    Forces {
        potential,
        gravity,
        q0,
    }
}
