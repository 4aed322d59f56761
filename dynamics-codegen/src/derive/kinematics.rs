//! Link poses as products of elementary transfer matrices, and the angular
//! velocity Jacobian of each link.
//!
//! A rotation element about the unit axis u by angle theta(q) adds
//! `R_before u dtheta/dq_j` to column j of the world angular Jacobian; a
//! general matrix element adds `R_before vee(dR_e/dq_j R_e^T)`. Translations
//! add nothing. Multiplying by the zeros and ones of elementary matrices is
//! folded away by the graph's builders.

use dynamics_symbolic::{Graph, Id};

use super::lower::lower;
use super::{Pose, Vars};
use crate::model::scalar::Scalar;
use crate::model::{Elem, Model};

/// A link's pose and world angular-velocity Jacobian (n columns).
#[derive(Clone)]
pub struct LinkKin {
    /// World pose.
    pub pose: Pose,
    /// Column j: world angular velocity per unit qd_j.
    pub w: Vec<[Id; 3]>,
}

/// Poses of all links, in model (depth-first) order.
pub fn frames(model: &Model, vars: Vars, g: &mut Graph) -> Vec<LinkKin> {
    let zero = g.constant(0.0);
    let one = g.constant(1.0);
    let root = LinkKin {
        pose: Pose {
            r: [[one, zero, zero], [zero, one, zero], [zero, zero, one]],
            p: [zero; 3],
        },
        w: vec![[zero; 3]; vars.n],
    };
    let mut out: Vec<LinkKin> = Vec::with_capacity(model.links.len());
    for link in &model.links {
        let kin = match (link.parent, link.joint) {
            (Some(p), Some(j)) => {
                let joint = &model.joints[j];
                let mut k = out[p].clone();
                for e in &joint.chain {
                    apply(&mut k, e, joint.coord, vars, g);
                }
                k
            }
            _ => root.clone(),
        };
        out.push(kin);
    }
    out
}

/// Right-multiplies the link's pose by one element.
fn apply(k: &mut LinkKin, e: &Elem, coord: Option<usize>, vars: Vars, g: &mut Graph) {
    match e {
        Elem::Trans(t) => {
            let t = t.clone().map(|s| lower(&s, coord, vars, g));
            let moved = mat_vec(g, &k.pose.r, t);
            k.pose.p = add3(g, k.pose.p, moved);
        }
        Elem::Rot(u, angle) => {
            let theta = lower(angle, coord, vars, g);
            let re = rotation(g, *u, theta);
            let uc = u.map(|c| g.constant(c));
            let axis_world = mat_vec(g, &k.pose.r, uc);
            for j in 0..vars.n {
                let d = g.diff(theta, vars.q(j));
                if !g.is_zero(d) {
                    let contrib = axis_world.map(|a| g.mul(a, d));
                    k.w[j] = add3(g, k.w[j], contrib);
                }
            }
            k.pose.r = mat_mat(g, &k.pose.r, &re);
        }
        Elem::Matrix(r, t) => {
            let re: [[Id; 3]; 3] =
                std::array::from_fn(|i| std::array::from_fn(|c| lower(&r[i][c], coord, vars, g)));
            let te = t.clone().map(|s: Scalar| lower(&s, coord, vars, g));
            for j in 0..vars.n {
                let dr: [[Id; 3]; 3] =
                    std::array::from_fn(|i| std::array::from_fn(|c| g.diff(re[i][c], vars.q(j))));
                if dr.iter().flatten().all(|x| g.is_zero(*x)) {
                    continue;
                }
                // skew = dR R^T; omega = vee(skew).
                let rt = transpose(&re);
                let s = mat_mat(g, &dr, &rt);
                let local = [s[2][1], s[0][2], s[1][0]];
                let world = mat_vec(g, &k.pose.r, local);
                k.w[j] = add3(g, k.w[j], world);
            }
            let moved = mat_vec(g, &k.pose.r, te);
            k.pose.p = add3(g, k.pose.p, moved);
            k.pose.r = mat_mat(g, &k.pose.r, &re);
        }
    }
}

/// Rotation about the unit axis u by theta (Rodrigues); exact zeros and ones
/// for the coordinate axes.
pub fn rotation(g: &mut Graph, u: [f64; 3], theta: Id) -> [[Id; 3]; 3] {
    let c = g.cos(theta);
    let s = g.sin(theta);
    let one = g.constant(1.0);
    let omc = g.sub(one, c);
    let uc = u.map(|x| g.constant(x));
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            // c delta_ij + s [u]x_ij + (1 - c) u_i u_j
            let delta = if i == j { c } else { g.constant(0.0) };
            let cross = match (i, j) {
                (0, 1) => g.neg(uc[2]),
                (0, 2) => uc[1],
                (1, 0) => uc[2],
                (1, 2) => g.neg(uc[0]),
                (2, 0) => g.neg(uc[1]),
                (2, 1) => uc[0],
                _ => g.constant(0.0),
            };
            let sc = g.mul(s, cross);
            let uu = g.constant(u[i] * u[j]);
            let outer = g.mul(omc, uu);
            let e = g.sum(&[delta, sc, outer]);
            snap(g, e)
        })
    })
}

/// A constant rotation entry within rounding of 0 or +-1 is made exact:
/// `cos(pi/2)` evaluates to 6e-17, and keeping it would cost the
/// sparsity that rotations by right angles (common in URDFs) give.
fn snap(g: &mut Graph, e: Id) -> Id {
    match g.as_constant(e) {
        Some(v) if v.abs() < 1e-15 => g.constant(0.0),
        Some(v) if (v.abs() - 1.0).abs() < 1e-15 => g.constant(v.signum()),
        _ => e,
    }
}

/// World position of a point given in a link's frame.
pub fn point_world(k: &LinkKin, at: &[Scalar; 3], vars: Vars, g: &mut Graph) -> [Id; 3] {
    let local = at.clone().map(|s| lower(&s, None, vars, g));
    let rotated = mat_vec(g, &k.pose.r, local);
    add3(g, k.pose.p, rotated)
}

/// a . b
pub fn dot(g: &mut Graph, a: [Id; 3], b: [Id; 3]) -> Id {
    let t: Vec<Id> = (0..3).map(|i| g.mul(a[i], b[i])).collect();
    g.sum(&t)
}

/// a + b
pub fn add3(g: &mut Graph, a: [Id; 3], b: [Id; 3]) -> [Id; 3] {
    std::array::from_fn(|i| g.add(a[i], b[i]))
}

pub fn mat_vec(g: &mut Graph, m: &[[Id; 3]; 3], v: [Id; 3]) -> [Id; 3] {
    std::array::from_fn(|i| {
        let t: Vec<Id> = (0..3).map(|k| g.mul(m[i][k], v[k])).collect();
        g.sum(&t)
    })
}

pub fn mat_mat(g: &mut Graph, a: &[[Id; 3]; 3], b: &[[Id; 3]; 3]) -> [[Id; 3]; 3] {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let t: Vec<Id> = (0..3).map(|k| g.mul(a[i][k], b[k][j])).collect();
            g.sum(&t)
        })
    })
}

pub fn transpose(m: &[[Id; 3]; 3]) -> [[Id; 3]; 3] {
    std::array::from_fn(|i| std::array::from_fn(|j| m[j][i]))
}
