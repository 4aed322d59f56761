//! Link Jacobians expressed in each link's own frame (body Jacobians).
//!
//! Column j of link k's Jacobian is the velocity of link k (angular `w`,
//! and linear `v` of its frame origin) per unit `qd_j`, in link k's
//! coordinates. Walking from link k towards the root, each element of a
//! joint's transfer chain is met with the pose `M` of link k relative to the
//! frame just after that element already known; a rotation element about
//! the unit axis u adds `w = R^T u dtheta/dq`, `v = R^T (u x p) dtheta/dq`
//! (with `M = (R, p)`), a translation adds `v = R^T dt/dq`. Only the joints
//! between j and k enter, so `A(q)` built from these does not depend on
//! the coordinates of joints that move the whole subtree rigidly (the first
//! joint of a chain drops out), and the expressions stay small. `A` itself
//! is frame-independent: `Jv^T Jv` and `Jw^T I Jw` are invariant under a
//! change of coordinates.

use dynamics_symbolic::{Graph, Id};

use super::kinematics::{mat_mat, mat_vec, transpose};
use super::lower::lower;
use super::Vars;
use crate::model::{Elem, Model};

/// One column of a body Jacobian.
#[derive(Clone, Copy)]
pub struct Column {
    /// Angular velocity per unit qd_j, link frame.
    pub w: [Id; 3],
    /// Velocity of the link frame's origin per unit qd_j, link frame.
    pub v: [Id; 3],
}

/// Body Jacobian columns of every link (`None` where the coordinate does
/// not move the link).
pub fn body_jacobians(model: &Model, vars: Vars, g: &mut Graph) -> Vec<Vec<Option<Column>>> {
    model
        .links
        .iter()
        .enumerate()
        .map(|(k, _)| link_columns(model, k, vars, g))
        .collect()
}

fn link_columns(model: &Model, k: usize, vars: Vars, g: &mut Graph) -> Vec<Option<Column>> {
    let zero = g.constant(0.0);
    let one = g.constant(1.0);
    let mut cols: Vec<Option<Column>> = vec![None; vars.n];
    // M = pose of link k in the frame after the current element.
    let mut r = [[one, zero, zero], [zero, one, zero], [zero, zero, one]];
    let mut p = [zero; 3];
    let mut link = k;
    while let Some(j) = model.links[link].joint {
        let joint = &model.joints[j];
        for e in joint.chain.iter().rev() {
            match e {
                Elem::Rot(u, angle) => {
                    let theta = lower(angle, joint.coord, vars, g);
                    let uc = u.map(|x| g.constant(x));
                    let rt = transpose(&r);
                    for c in 0..vars.n {
                        let d = g.diff(theta, vars.q(c));
                        if g.is_zero(d) {
                            continue;
                        }
                        let w = mat_vec(g, &rt, uc).map(|x| g.mul(x, d));
                        let uxp = cross(g, uc, p);
                        let v = mat_vec(g, &rt, uxp).map(|x| g.mul(x, d));
                        accumulate(g, &mut cols[c], w, v);
                    }
                    let e = super::kinematics::rotation(g, *u, theta);
                    r = mat_mat(g, &e, &r);
                    p = mat_vec(g, &e, p);
                }
                Elem::Trans(t) => {
                    let t = t.clone().map(|s| lower(&s, joint.coord, vars, g));
                    let rt = transpose(&r);
                    for c in 0..vars.n {
                        let dt = t.map(|x| g.diff(x, vars.q(c)));
                        if dt.iter().all(|x| g.is_zero(*x)) {
                            continue;
                        }
                        let v = mat_vec(g, &rt, dt);
                        accumulate(g, &mut cols[c], [zero; 3], v);
                    }
                    p = std::array::from_fn(|i| g.add(p[i], t[i]));
                }
                Elem::Matrix(rm, tm) => {
                    let re: [[Id; 3]; 3] = std::array::from_fn(|i| {
                        std::array::from_fn(|c| lower(&rm[i][c], joint.coord, vars, g))
                    });
                    let te = tm.clone().map(|s| lower(&s, joint.coord, vars, g));
                    // Pose of link k in the frame before this element.
                    let r_before = mat_mat(g, &re, &r);
                    let rp = mat_vec(g, &re, p);
                    let p_before: [Id; 3] = std::array::from_fn(|i| g.add(rp[i], te[i]));
                    let rt = transpose(&r_before);
                    for c in 0..vars.n {
                        let dr: [[Id; 3]; 3] = std::array::from_fn(|i| {
                            std::array::from_fn(|cc| g.diff(re[i][cc], vars.q(c)))
                        });
                        let dt = te.map(|x| g.diff(x, vars.q(c)));
                        if dr.iter().flatten().chain(dt.iter()).all(|x| g.is_zero(*x)) {
                            continue;
                        }
                        let s = mat_mat(g, &dr, &transpose(&re));
                        let w_before = [s[2][1], s[0][2], s[1][0]];
                        let drp = mat_vec(g, &dr, p);
                        let v_before: [Id; 3] = std::array::from_fn(|i| g.add(drp[i], dt[i]));
                        let w = mat_vec(g, &rt, w_before);
                        let v = mat_vec(g, &rt, v_before);
                        accumulate(g, &mut cols[c], w, v);
                    }
                    r = r_before;
                    p = p_before;
                }
            }
        }
        link = joint.parent;
    }
    cols
}

fn accumulate(g: &mut Graph, col: &mut Option<Column>, w: [Id; 3], v: [Id; 3]) {
    *col = Some(match col.take() {
        None => Column { w, v },
        Some(c) => Column {
            w: std::array::from_fn(|i| g.add(c.w[i], w[i])),
            v: std::array::from_fn(|i| g.add(c.v[i], v[i])),
        },
    });
}

/// a x b
pub fn cross(g: &mut Graph, a: [Id; 3], b: [Id; 3]) -> [Id; 3] {
    let term = |g: &mut Graph, i: usize, j: usize| {
        let x = g.mul(a[i], b[j]);
        let y = g.mul(a[j], b[i]);
        g.sub(x, y)
    };
    [term(g, 1, 2), term(g, 2, 0), term(g, 0, 1)]
}
