//! The inertial regressor: `Y_l = d tau / d pi_l` for every link that
//! carries inertial parameters, with Pinocchio's dynamic parameters
//! `pi = [m, m c_x, m c_y, m c_z, I_xx, I_xy, I_yy, I_xz, I_yz, I_zz]`
//! about the link frame's origin, in the link frame's axes (`I` = inertia
//! about the origin, `I_c + m (|c|^2 1 - c c^T)`).
//!
//! The rigid-body efforts are `tau = sum_l J_l^T f_l`, with `J_l` the
//! body Jacobian of link l (angular `u_j`, linear `s_j` per unit `qd_j`,
//! link frame) and `f_l = [n; f]` the moment about the origin and force
//! the link needs, which are linear in `pi_l`: with the link frame's
//! angular velocity w, angular acceleration dw and origin acceleration a
//! (gravity as `-gravity`), `f = m a + dw x h + w x (w x h)` and
//! `n = I dw + w x I w + h x a` (h = m c). Row j of `Y_l` is therefore
//! - mass: `s . a`;
//! - first moments: `a x u + s x dw + (s . w) w - |w|^2 s`;
//! - inertia: the coefficients of `u^T I dw + (u x w)^T I w`.
//!
//! The motion of each link frame comes from the Newton-Euler forward pass
//! (`rnea.rs`), or, for chains with moving general matrices, from the body
//! Jacobians and their derivatives. The regressor does not depend on any
//! inertial value, only on kinematics.

use dynamics_symbolic::{Graph, Id};

use super::body_jacobian::{cross, Column};
use super::kinematics::{dot, mat_vec, transpose, LinkKin};
use super::lower::lower;
use super::spatial::{Inertia, M3};
use super::{rnea, Vars};
use crate::model::{JointKind, Model};

type V3 = [Id; 3];

/// The regressor of every link that carries inertial parameters.
pub struct Regressor {
    /// Model indices of those links, in order.
    pub links: Vec<usize>,
    /// Per link, row-major n x 10.
    pub y: Vec<Vec<Id>>,
    /// Per link, the nominal parameters (body and point masses together).
    pub pi: Vec<[Id; 10]>,
}

/// Links that carry inertial parameters: moved by some coordinate, and
/// either on a moving joint or holding mass (a massless link welded on a
/// fixed joint adds only columns its parent already has).
pub fn links(model: &Model, jac: &[Vec<Option<Column>>]) -> Vec<usize> {
    (0..model.links.len())
        .filter(|&l| {
            let link = &model.links[l];
            let moved = jac[l].iter().any(Option::is_some);
            let moving_joint = link
                .joint
                .is_some_and(|j| model.joints[j].kind != JointKind::Fixed);
            let massive = link.inertial.is_some() || link.points.iter().any(|p| p.mass.is_some());
            moved && (moving_joint || massive)
        })
        .collect()
}

/// The regressor of `model` (body Jacobians `jac`, frames `kin`).
pub fn regressor(
    model: &Model,
    jac: &[Vec<Option<Column>>],
    kin: &[LinkKin],
    vars: Vars,
    g: &mut Graph,
) -> Regressor {
    let all = rnea::Terms {
        velocity: true,
        acceleration: true,
        gravity: true,
    };
    let motion: Vec<rnea::Motion> = match rnea::forward(model, vars, all, g) {
        Some((m, _)) => m,
        None => (0..model.links.len())
            .map(|l| from_jacobian(model, &jac[l], kin[l].pose.r, vars, g))
            .collect(),
    };
    let links = links(model, jac);
    let zero = g.constant(0.0);
    let mut y = Vec::with_capacity(links.len());
    let mut pi = Vec::with_capacity(links.len());
    for &l in &links {
        let m = motion[l];
        let ww = dot(g, m.w, m.w);
        let mut rows = vec![zero; vars.n * 10];
        for (j, col) in jac[l].iter().enumerate() {
            let Some(col) = col else { continue };
            rows[j * 10..j * 10 + 10].copy_from_slice(&row(g, m, ww, *col));
        }
        y.push(rows);
        pi.push(nominal(model, l, vars, g));
    }
    Regressor { links, y, pi }
}

/// One row `J_j^T d f / d pi` of a link's regressor.
fn row(g: &mut Graph, m: rnea::Motion, ww: Id, col: Column) -> [Id; 10] {
    let (u, s) = (col.w, col.v);
    let mass = dot(g, s, m.a);
    let axu = cross(g, m.a, u);
    let sxdw = cross(g, s, m.dw);
    let sw = dot(g, s, m.w);
    let h: V3 = std::array::from_fn(|i| {
        let a = g.mul(sw, m.w[i]);
        let b = g.mul(ww, s[i]);
        let p = g.sum(&[axu[i], sxdw[i], a]);
        g.sub(p, b)
    });
    // u^T I dw + k^T I w with k = u x w: the coefficient of I_ab is
    // u_a dw_b + k_a w_b (+ the same with a, b swapped off the diagonal).
    let k = cross(g, u, m.w);
    let mut coef = |a: usize, b: usize| -> Id {
        let mut t = vec![g.mul(u[a], m.dw[b]), g.mul(k[a], m.w[b])];
        if a != b {
            t.push(g.mul(u[b], m.dw[a]));
            t.push(g.mul(k[b], m.w[a]));
        }
        g.sum(&t)
    };
    [
        mass,
        h[0],
        h[1],
        h[2],
        coef(0, 0),
        coef(0, 1),
        coef(1, 1),
        coef(0, 2),
        coef(1, 2),
        coef(2, 2),
    ]
}

/// The motion of a link frame from its body Jacobian: `w = Jw qd`,
/// `v = Jv qd`, `dw = Jw qdd + (dJw/dt) qd`,
/// `a = Jv qdd + (dJv/dt) qd + w x v - R^T gravity`.
fn from_jacobian(
    model: &Model,
    cols: &[Option<Column>],
    r: M3,
    vars: Vars,
    g: &mut Graph,
) -> rnea::Motion {
    let zero = g.constant(0.0);
    let (mut w, mut v, mut dw, mut dv) = ([zero; 3], [zero; 3], [zero; 3], [zero; 3]);
    let add = |g: &mut Graph, acc: &mut V3, x: V3, k: Id| {
        for i in 0..3 {
            let t = g.mul(x[i], k);
            acc[i] = g.add(acc[i], t);
        }
    };
    for (j, col) in cols.iter().enumerate() {
        let Some(col) = col else { continue };
        let qd = g.var(vars.qd(j));
        let qdd = g.var(vars.qdd(j));
        add(g, &mut w, col.w, qd);
        add(g, &mut v, col.v, qd);
        add(g, &mut dw, col.w, qdd);
        add(g, &mut dv, col.v, qdd);
    }
    for i in 0..vars.n {
        let qd = g.var(vars.qd(i));
        let dwi = w.map(|x| g.diff(x, vars.q(i)));
        let dvi = v.map(|x| g.diff(x, vars.q(i)));
        add(g, &mut dw, dwi, qd);
        add(g, &mut dv, dvi, qd);
    }
    let wxv = cross(g, w, v);
    let neg_gravity = model.gravity.map(|x| g.constant(-x));
    let grav = mat_vec(g, &transpose(&r), neg_gravity);
    let a = std::array::from_fn(|i| g.sum(&[dv[i], wxv[i], grav[i]]));
    rnea::Motion { w, dw, a }
}

/// The nominal parameters of link `l`: its body and point masses about the
/// link frame's origin.
fn nominal(model: &Model, l: usize, vars: Vars, g: &mut Graph) -> [Id; 10] {
    let link = &model.links[l];
    let zero = g.constant(0.0);
    let mut total = Inertia::zero(g);
    if let Some(inert) = &link.inertial {
        let m = lower(&inert.mass, None, vars, g);
        let c = inert.com.clone().map(|s| lower(&s, None, vars, g));
        let [xx, yy, zz, xy, xz, yz] = inert.inertia.clone().map(|s| lower(&s, None, vars, g));
        let ic = [[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]];
        let body = Inertia::body(g, m, c, ic);
        total = total.add(g, body);
    }
    for p in &link.points {
        if let Some(mass) = &p.mass {
            let m = lower(mass, None, vars, g);
            let c = p.at.clone().map(|s| lower(&s, None, vars, g));
            let body = Inertia::body(g, m, c, [[zero; 3]; 3]);
            total = total.add(g, body);
        }
    }
    let i = total.i;
    [
        total.m, total.h[0], total.h[1], total.h[2], i[0][0], i[0][1], i[1][1], i[0][2], i[1][2],
        i[2][2],
    ]
}
