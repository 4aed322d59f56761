//! Inverse dynamics by a straight-line symbolic recursive Newton-Euler
//! pass (as RobCoGen, ROBOTRAN and OpenSYMORO emit it): O(n) where the
//! matrix form `A qdd - Qqt1 - Qqt2` is O(n^2) and more.
//!
//! Forward, element by element of each joint's transfer chain, in the frame
//! after the element: angular velocity w, angular acceleration dw and the
//! linear acceleration a of the frame origin, with gravity as a base
//! acceleration `-gravity`. A rotation `E = Rot(u, theta)` maps
//! `w' = E^T w + u dtheta`, `dw' = E^T dw + u ddtheta + (E^T w) x u dtheta`,
//! `a' = E^T a`; a translation t(q) maps
//! `a' = a + dw x t + w x (w x t) + 2 w x dt + ddt`. Backward, each body's
//! force `m (a + dw x c + w x (w x c))` and moment about the frame origin
//! `I dw + w x I w + c x F` (I about the centre of mass) are carried back
//! through the same elements; the effort of coordinate j collects
//! `u . n dtheta/dq_j` at its rotations and `dt/dq_j . f` at its
//! translations. Chains whose general matrices move with q are not handled
//! here (`None`): the caller then keeps the matrix form.

use dynamics_symbolic::{Graph, Id};

use super::body_jacobian::cross;
use super::kinematics::{add3 as add, dot, mat_vec, transpose};
use super::lower::lower;
use super::Vars;
use crate::model::scalar::Scalar;
use crate::model::{Elem, Model};

type V3 = [Id; 3];

/// Motion of a frame: angular velocity, angular acceleration, linear
/// acceleration of the origin (gravity included), all in the frame's axes.
#[derive(Clone, Copy)]
pub struct Motion {
    /// Angular velocity.
    pub w: V3,
    /// Angular acceleration.
    pub dw: V3,
    /// Linear acceleration of the frame origin, `-gravity` included.
    pub a: V3,
}

/// What the forward pass did at one element, for the backward pass.
pub enum Step {
    /// A rotation E (rows), and the coordinates' rates of its angle.
    Rot {
        e: [[Id; 3]; 3],
        u: V3,
        dtheta_dq: Vec<(usize, Id)>,
    },
    /// A translation t and its partials.
    Trans { t: V3, dt_dq: Vec<(usize, V3)> },
}

/// Which terms a Newton-Euler pass includes.
#[derive(Clone, Copy)]
pub struct Terms {
    /// Velocities qd (else zero).
    pub velocity: bool,
    /// Accelerations qdd (else zero).
    pub acceleration: bool,
    /// Gravity (else none).
    pub gravity: bool,
}

/// The efforts `U` of the rigid body (no damping, friction, springs) that
/// produce `qdd` at (q, qd) with the chosen terms, or `None` when a chain has
/// a general matrix that moves with q. Velocities only give
/// `-(Qqt1 + Qqt2)`; gravity only gives `g`.
pub fn inverse_dynamics(model: &Model, vars: Vars, terms: Terms, g: &mut Graph) -> Option<Vec<Id>> {
    let (motion, steps) = forward(model, vars, terms, g)?;
    Some(backward(model, vars, &motion, &steps, g))
}

/// The forward pass: the motion of every link frame (in model order) and
/// the elements met on the way, or `None` when a chain has a general matrix
/// that moves with q.
pub fn forward(
    model: &Model,
    vars: Vars,
    terms: Terms,
    g: &mut Graph,
) -> Option<(Vec<Motion>, Vec<Vec<Step>>)> {
    let n = vars.n;
    let zero = g.constant(0.0);
    let z3 = [zero; 3];
    let neg_gravity = if terms.gravity {
        model.gravity.map(|x| g.constant(-x))
    } else {
        z3
    };
    let rate = |g: &mut Graph, c: usize, second: bool| -> Id {
        match (second, terms.velocity, terms.acceleration) {
            (false, true, _) => g.var(vars.qd(c)),
            (true, _, true) => g.var(vars.qdd(c)),
            _ => g.constant(0.0),
        }
    };

    let mut motion: Vec<Motion> = Vec::with_capacity(model.links.len());
    let mut steps: Vec<Vec<Step>> = Vec::with_capacity(model.links.len());
    for link in &model.links {
        let (Some(p), Some(j)) = (link.parent, link.joint) else {
            motion.push(Motion {
                w: z3,
                dw: z3,
                a: neg_gravity,
            });
            steps.push(Vec::new());
            continue;
        };
        let joint = &model.joints[j];
        let mut m = motion[p];
        let mut link_steps = Vec::new();
        for e in &joint.chain {
            match e {
                Elem::Rot(u, angle) => {
                    let theta = lower(angle, joint.coord, vars, g);
                    let uc = u.map(|x| g.constant(x));
                    let rot = super::kinematics::rotation(g, *u, theta);
                    let et = transpose(&rot);
                    let mut dtheta_dq = Vec::new();
                    let (mut rate1, mut rate2) = (Vec::new(), Vec::new());
                    for c in 0..n {
                        let d = g.diff(theta, vars.q(c));
                        if g.is_zero(d) {
                            continue;
                        }
                        dtheta_dq.push((c, d));
                        let qd = rate(g, c, false);
                        let qdd = rate(g, c, true);
                        rate1.push(g.mul(d, qd));
                        rate2.push(g.mul(d, qdd));
                        for c2 in 0..n {
                            let dd = g.diff(d, vars.q(c2));
                            if !g.is_zero(dd) {
                                let qd2 = rate(g, c2, false);
                                rate2.push(g.product(&[dd, qd, qd2]));
                            }
                        }
                    }
                    let td = g.sum(&rate1);
                    let tdd = g.sum(&rate2);
                    let w_rot = mat_vec(g, &et, m.w);
                    let dw_rot = mat_vec(g, &et, m.dw);
                    let a_rot = mat_vec(g, &et, m.a);
                    let u_td = uc.map(|x| g.mul(x, td));
                    let u_tdd = uc.map(|x| g.mul(x, tdd));
                    let wxu = cross(g, w_rot, u_td);
                    m = Motion {
                        w: add(g, w_rot, u_td),
                        dw: add3(g, dw_rot, u_tdd, wxu),
                        a: a_rot,
                    };
                    link_steps.push(Step::Rot {
                        e: rot,
                        u: uc,
                        dtheta_dq,
                    });
                }
                Elem::Trans(t) => {
                    let t = t.clone().map(|s| lower(&s, joint.coord, vars, g));
                    let mut dt_dq = Vec::new();
                    let (mut td, mut tdd) = (Vec::new(), Vec::new());
                    for c in 0..n {
                        let d = t.map(|x| g.diff(x, vars.q(c)));
                        if d.iter().all(|x| g.is_zero(*x)) {
                            continue;
                        }
                        dt_dq.push((c, d));
                        let qd = rate(g, c, false);
                        let qdd = rate(g, c, true);
                        td.push(d.map(|x| g.mul(x, qd)));
                        tdd.push(d.map(|x| g.mul(x, qdd)));
                        for c2 in 0..n {
                            let dd = d.map(|x| g.diff(x, vars.q(c2)));
                            if dd.iter().any(|x| !g.is_zero(*x)) {
                                let qd2 = rate(g, c2, false);
                                tdd.push(dd.map(|x| g.product(&[x, qd, qd2])));
                            }
                        }
                    }
                    let tdot: V3 = std::array::from_fn(|i| {
                        let parts: Vec<Id> = td.iter().map(|v| v[i]).collect();
                        g.sum(&parts)
                    });
                    let tddot: V3 = std::array::from_fn(|i| {
                        let parts: Vec<Id> = tdd.iter().map(|v| v[i]).collect();
                        g.sum(&parts)
                    });
                    let dwxt = cross(g, m.dw, t);
                    let wxt = cross(g, m.w, t);
                    let wxwxt = cross(g, m.w, wxt);
                    let wxtd = cross(g, m.w, tdot);
                    let two_wxtd = wxtd.map(|x| g.scale(x, 2.0));
                    let a: V3 = std::array::from_fn(|i| {
                        g.sum(&[m.a[i], dwxt[i], wxwxt[i], two_wxtd[i], tddot[i]])
                    });
                    m.a = a;
                    link_steps.push(Step::Trans { t, dt_dq });
                }
                Elem::Matrix(r, t) => {
                    let moving = r.iter().flatten().chain(t.iter()).any(Scalar::moves);
                    if moving {
                        return None;
                    }
                    // A constant rotation followed by... (E = [R | t]): the
                    // new origin is at t in the old frame, axes rotated by R.
                    let t = t.clone().map(|s| lower(&s, joint.coord, vars, g));
                    let dwxt = cross(g, m.dw, t);
                    let wxt = cross(g, m.w, t);
                    let wxwxt = cross(g, m.w, wxt);
                    let a_old = add3(g, m.a, dwxt, wxwxt);
                    link_steps.push(Step::Trans {
                        t,
                        dt_dq: Vec::new(),
                    });
                    let rot: [[Id; 3]; 3] = std::array::from_fn(|i| {
                        std::array::from_fn(|c| lower(&r[i][c], joint.coord, vars, g))
                    });
                    let et = transpose(&rot);
                    m = Motion {
                        w: mat_vec(g, &et, m.w),
                        dw: mat_vec(g, &et, m.dw),
                        a: mat_vec(g, &et, a_old),
                    };
                    link_steps.push(Step::Rot {
                        e: rot,
                        u: z3,
                        dtheta_dq: Vec::new(),
                    });
                }
            }
        }
        motion.push(m);
        steps.push(link_steps);
    }

    Some((motion, steps))
}

/// The backward pass: the efforts of the bodies' forces and moments.
fn backward(
    model: &Model,
    vars: Vars,
    motion: &[Motion],
    steps: &[Vec<Step>],
    g: &mut Graph,
) -> Vec<Id> {
    let n = vars.n;
    let zero = g.constant(0.0);
    let z3 = [zero; 3];
    // Backward: force f and moment n about each link frame's origin.
    let mut f: Vec<V3> = vec![z3; model.links.len()];
    let mut nm: Vec<V3> = vec![z3; model.links.len()];
    let mut tau: Vec<Vec<Id>> = vec![Vec::new(); n];
    for (k, link) in model.links.iter().enumerate().rev() {
        let mo = motion[k];
        let mut bodies = Vec::new();
        if let Some(inert) = &link.inertial {
            bodies.push((&inert.mass, &inert.com, Some(&inert.inertia)));
        }
        for p in &link.points {
            if let Some(mass) = &p.mass {
                bodies.push((mass, &p.at, None));
            }
        }
        for (mass, at, inertia) in bodies {
            let mass = lower(mass, None, vars, g);
            let c = at.clone().map(|s| lower(&s, None, vars, g));
            let dwxc = cross(g, mo.dw, c);
            let wxc = cross(g, mo.w, c);
            let wxwxc = cross(g, mo.w, wxc);
            let acc = add3(g, mo.a, dwxc, wxwxc);
            let force = acc.map(|x| g.mul(mass, x));
            let mut moment = cross(g, c, force);
            if let Some(i) = inertia {
                let [xx, yy, zz, xy, xz, yz] = i.clone().map(|s| lower(&s, None, vars, g));
                let tensor = [[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]];
                let idw = mat_vec(g, &tensor, mo.dw);
                let iw = mat_vec(g, &tensor, mo.w);
                let wxiw = cross(g, mo.w, iw);
                moment = add3(g, moment, idw, wxiw);
            }
            f[k] = add(g, f[k], force);
            nm[k] = add(g, nm[k], moment);
        }
        let (Some(p), Some(_)) = (link.parent, link.joint) else {
            continue;
        };
        let (mut fk, mut nk) = (f[k], nm[k]);
        for step in steps[k].iter().rev() {
            match step {
                Step::Rot { e, u, dtheta_dq } => {
                    for (c, d) in dtheta_dq {
                        let un = dot(g, *u, nk);
                        tau[*c].push(g.mul(un, *d));
                    }
                    fk = mat_vec(g, e, fk);
                    nk = mat_vec(g, e, nk);
                }
                Step::Trans { t, dt_dq } => {
                    for (c, d) in dt_dq {
                        let df = dot(g, *d, fk);
                        tau[*c].push(df);
                    }
                    let txf = cross(g, *t, fk);
                    nk = add(g, nk, txf);
                }
            }
        }
        f[p] = add(g, f[p], fk);
        nm[p] = add(g, nm[p], nk);
    }
    tau.iter().map(|t| g.sum(t)).collect()
}

fn add3(g: &mut Graph, a: V3, b: V3, c: V3) -> V3 {
    std::array::from_fn(|i| g.sum(&[a[i], b[i], c[i]]))
}
