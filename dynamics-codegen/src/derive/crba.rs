//! The inertia matrix by a straight-line symbolic composite-rigid-body pass
//! (O(n^2) where the Jacobian form is O(n^3)).
//!
//! Walking the tree from the leaves, each link's composite body (mass m,
//! first moment h and inertia J about the current frame's origin) is carried
//! back through the elements of its joint's transfer chain: a rotation E maps
//! `h -> E h`, `J -> E J E^T`; a translation t maps `h -> h + m t`,
//! `J -> J + 2 (h.t) I - (h t^T + t h^T) + m (|t|^2 I - t t^T)`. Where an
//! element carries coordinate c, the composite's momentum per unit qd_c is
//! recorded (rotation about u: linear `u x h`, angular `J u`; translation
//! along d: linear `m d`, angular `h x d`) and carried upward with it
//! (`L -> L + t x p` across a translation). `A_cc'` is the projection of the
//! momentum of coordinate c' (a descendant, or c itself) on the motion of c:
//! `u . L` for a rotation, `d . p` for a translation. Chains with a general
//! matrix give `None` (the caller keeps the Jacobian form).

use dynamics_symbolic::{Graph, Id};

use super::body_jacobian::cross;
use super::kinematics::{add3 as add, dot, mat_mat, mat_vec, rotation, transpose};
use super::lower::lower;
use super::Vars;
use crate::model::scalar::Scalar;
use crate::model::{Elem, Model};

type V3 = [Id; 3];
type M3 = [[Id; 3]; 3];

#[derive(Clone)]
struct Composite {
    m: Id,
    h: V3,
    j: M3,
}

/// A(q) upper triangle mirrored, or `None` for general matrix elements.
pub fn mass_matrix(model: &Model, vars: Vars, g: &mut Graph) -> Option<Vec<Vec<Id>>> {
    let n = vars.n;
    let zero = g.constant(0.0);
    let empty = Composite {
        m: zero,
        h: [zero; 3],
        j: [[zero; 3]; 3],
    };
    let mut comp: Vec<Composite> = vec![empty.clone(); model.links.len()];
    let mut pending: Vec<Vec<(usize, V3, V3)>> = vec![Vec::new(); model.links.len()];
    let mut terms: Vec<Vec<Vec<Id>>> = vec![vec![Vec::new(); n]; n];

    // Own bodies, in each link's frame.
    for (k, link) in model.links.iter().enumerate() {
        let mut c = empty.clone();
        if let Some(i) = &link.inertial {
            let t = i.inertia.clone().map(|s| lower(&s, None, vars, g));
            let ic = [[t[0], t[3], t[4]], [t[3], t[1], t[5]], [t[4], t[5], t[2]]];
            add_body(g, &mut c, &i.mass, &i.com, Some(ic), vars);
        }
        for p in &link.points {
            if let Some(mass) = &p.mass {
                add_body(g, &mut c, mass, &p.at, None, vars);
            }
        }
        comp[k] = c;
    }

    for k in (0..model.links.len()).rev() {
        let (Some(parent), Some(jn)) = (model.links[k].parent, model.links[k].joint) else {
            continue;
        };
        let joint = &model.joints[jn];
        let mut c = comp[k].clone();
        let mut pend = std::mem::take(&mut pending[k]);
        for e in joint.chain.iter().rev() {
            match e {
                Elem::Rot(u, angle) => {
                    let theta = lower(angle, joint.coord, vars, g);
                    let uc = u.map(|x| g.constant(x));
                    for coord in 0..n {
                        let d = g.diff(theta, vars.q(coord));
                        if g.is_zero(d) {
                            continue;
                        }
                        let w = uc.map(|x| g.mul(x, d));
                        let p = cross(g, w, c.h);
                        let l = mat_vec(g, &c.j, w);
                        pend.push((coord, p, l));
                        for (other, _, lo) in &pend {
                            let proj = dot(g, w, *lo);
                            let (a, b) = if coord <= *other {
                                (coord, *other)
                            } else {
                                (*other, coord)
                            };
                            terms[a][b].push(proj);
                        }
                    }
                    let rot = rotation(g, *u, theta);
                    let rt = transpose(&rot);
                    c.h = mat_vec(g, &rot, c.h);
                    let jr = mat_mat(g, &c.j, &rt);
                    c.j = mat_mat(g, &rot, &jr);
                    for (_, p, l) in pend.iter_mut() {
                        *p = mat_vec(g, &rot, *p);
                        *l = mat_vec(g, &rot, *l);
                    }
                }
                Elem::Trans(t) => {
                    let t = t.clone().map(|s| lower(&s, joint.coord, vars, g));
                    for coord in 0..n {
                        let d = t.map(|x| g.diff(x, vars.q(coord)));
                        if d.iter().all(|x| g.is_zero(*x)) {
                            continue;
                        }
                        let p = d.map(|x| g.mul(c.m, x));
                        let l = cross(g, c.h, d);
                        pend.push((coord, p, l));
                        for (other, po, _) in &pend {
                            let proj = dot(g, d, *po);
                            let (a, b) = if coord <= *other {
                                (coord, *other)
                            } else {
                                (*other, coord)
                            };
                            terms[a][b].push(proj);
                        }
                    }
                    shift(g, &mut c, t);
                    for (_, p, l) in pend.iter_mut() {
                        let txp = cross(g, t, *p);
                        *l = add(g, *l, txp);
                    }
                }
                Elem::Matrix(..) => return None,
            }
        }
        let pc = &mut comp[parent];
        pc.m = g.add(pc.m, c.m);
        pc.h = add(g, pc.h, c.h);
        pc.j = std::array::from_fn(|r| add(g, pc.j[r], c.j[r]));
        pending[parent].extend(pend);
    }
    let mut a = vec![vec![zero; n]; n];
    for i in 0..n {
        for j in i..n {
            let s = g.sum(&terms[i][j]);
            let s = super::smaller_expanded(g, s);
            a[i][j] = s;
            a[j][i] = s;
        }
    }
    Some(a)
}

/// Adds a body (mass, centre, inertia about the centre) given in the
/// composite's frame.
fn add_body(
    g: &mut Graph,
    c: &mut Composite,
    mass: &Scalar,
    at: &[Scalar; 3],
    ic: Option<M3>,
    vars: Vars,
) {
    let m = lower(mass, None, vars, g);
    let r = at.clone().map(|s| lower(&s, None, vars, g));
    let mr = r.map(|x| g.mul(m, x));
    c.m = g.add(c.m, m);
    c.h = add(g, c.h, mr);
    // J_O = I_c + m (|r|^2 I - r r^T)
    let rr: Vec<Id> = (0..3).map(|i| g.mul(r[i], r[i])).collect();
    let r2 = g.sum(&rr);
    for a in 0..3 {
        for b in 0..3 {
            let outer = g.mul(r[a], r[b]);
            let mut parts = vec![];
            if a == b {
                parts.push(r2);
            }
            let no = g.neg(outer);
            parts.push(no);
            let s = g.sum(&parts);
            let ms = g.mul(m, s);
            let base = ic.map(|i| i[a][b]).unwrap_or(g.constant(0.0));
            let e = g.add(base, ms);
            c.j[a][b] = g.add(c.j[a][b], e);
        }
    }
}

/// Moves the composite's reference point: the old origin is at t.
fn shift(g: &mut Graph, c: &mut Composite, t: V3) {
    let ht = dot(g, c.h, t);
    let tt = dot(g, t, t);
    let mut j = c.j;
    for a in 0..3 {
        for b in 0..3 {
            let mut parts = vec![j[a][b]];
            if a == b {
                let two_ht = g.scale(ht, 2.0);
                parts.push(two_ht);
                parts.push(g.mul(c.m, tt));
            }
            let x = g.mul(c.h[a], t[b]);
            let y = g.mul(t[a], c.h[b]);
            let z = g.product(&[c.m, t[a], t[b]]);
            parts.push(g.neg(x));
            parts.push(g.neg(y));
            parts.push(g.neg(z));
            j[a][b] = g.sum(&parts);
        }
    }
    let mt = t.map(|x| g.mul(c.m, x));
    c.h = add(g, c.h, mt);
    c.j = j;
}
