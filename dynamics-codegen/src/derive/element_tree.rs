//! The tree of frames after each transfer element, with the motion of
//! each (spatial velocity and acceleration, gravity as a base acceleration
//! `-gravity`), the twist of every coordinate and the bodies gathered in the
//! frames that move: the first half of the analytic derivatives
//! (`rnea_derivatives.rs`).
//!
//! Through an element with twist S (qd the rate of its coordinate):
//! `v = X v_p + S qd`, `a = X a_p + S qdd + (v x S) qd`, and the same
//! acceleration at `qdd = 0` for the bias forces. Only chains whose
//! moving elements each follow one coordinate at a rate that does not vary
//! with q (revolute and prismatic joints, gear ratios) are accepted.

use dynamics_symbolic::{Graph, Id};

use super::kinematics::rotation;
use super::lower::lower;
use super::spatial::{Inertia, Step, Sv, M3};
use super::Vars;
use crate::model::{Elem, Model};

/// A frame after one transfer element.
pub struct Node {
    /// Node of the frame before the element (the root is its own parent).
    pub parent: usize,
    /// The element.
    pub step: Step,
    /// Whether the step follows a coordinate.
    pub moving: bool,
}

/// A coordinate's twist and the motion of the frame before its element,
/// in the frame after it.
pub struct Coord {
    /// Node of the frame after the element.
    pub node: usize,
    /// Twist per unit rate.
    pub s: Sv,
    /// Velocity of the frame before the element.
    pub vp: Sv,
    /// Acceleration of the frame before the element.
    pub ap: Sv,
}

/// The frames of a model; node 0 is the base.
pub struct Tree {
    /// The frames, each after its parent.
    pub nodes: Vec<Node>,
    /// (velocity, acceleration) of each node.
    pub motion: Vec<(Sv, Sv)>,
    /// The acceleration of each node at `qdd = 0` (gravity and the
    /// velocity products only), for the bias forces.
    pub rest: Vec<Sv>,
    /// Per coordinate (`None` if no element follows it).
    pub coords: Vec<Option<Coord>>,
    /// The bodies, summed per moving node.
    pub held: Vec<Option<Inertia>>,
}

/// The frames, motions and bodies of `model`, or `None` when a chain or a
/// body is outside what the analytic derivatives handle.
pub fn tree(model: &Model, vars: Vars, g: &mut Graph) -> Option<Tree> {
    let n = vars.n;
    let zero = g.constant(0.0);
    let root = Node {
        parent: 0,
        step: Step::Trans([zero; 3]),
        moving: false,
    };
    let mut nodes = vec![root];
    let gravity = model.gravity.map(|x| g.constant(-x));
    let mut motion = vec![(
        Sv::zero(g),
        Sv {
            w: [zero; 3],
            v: gravity,
        },
    )];
    let mut rest = vec![motion[0].1];
    let mut link_node = vec![0; model.links.len()];
    let mut coords: Vec<Option<Coord>> = (0..n).map(|_| None).collect();
    for (l, link) in model.links.iter().enumerate() {
        let (Some(p), Some(j)) = (link.parent, link.joint) else {
            continue;
        };
        let joint = &model.joints[j];
        let mut node = link_node[p];
        for e in &joint.chain {
            let mut steps: Vec<(Step, Option<(usize, Sv)>)> = Vec::new();
            match e {
                Elem::Rot(u, angle) => {
                    let theta = lower(angle, joint.coord, vars, g);
                    let rate = single_rate(g, &[theta], vars)?;
                    let e = rotation(g, *u, theta);
                    let s = rate.map(|(c, k)| {
                        let w = u.map(|x| {
                            let x = g.constant(x);
                            g.mul(x, k[0])
                        });
                        (c, Sv { w, v: [zero; 3] })
                    });
                    steps.push((Step::Rot(e), s));
                }
                Elem::Trans(t) => {
                    let t = t.clone().map(|s| lower(&s, joint.coord, vars, g));
                    let rate = single_rate(g, &t, vars)?;
                    let s = rate.map(|(c, k)| {
                        let v = [k[0], k[1], k[2]];
                        (c, Sv { w: [zero; 3], v })
                    });
                    steps.push((Step::Trans(t), s));
                }
                Elem::Matrix(r, t) => {
                    let t = t.clone().map(|s| lower(&s, joint.coord, vars, g));
                    let r: M3 = std::array::from_fn(|i| {
                        std::array::from_fn(|c| lower(&r[i][c], joint.coord, vars, g))
                    });
                    let all: Vec<Id> = r.iter().flatten().chain(t.iter()).copied().collect();
                    if single_rate(g, &all, vars)?.is_some() {
                        return None;
                    }
                    steps.push((Step::Trans(t), None));
                    steps.push((Step::Rot(r), None));
                }
            }
            for (step, s) in steps {
                let (v0, a0) = motion[node];
                let vp = v0.motion_forward(g, &step);
                let ap = a0.motion_forward(g, &step);
                let rest_p = rest[node].motion_forward(g, &step);
                nodes.push(Node {
                    parent: node,
                    step,
                    moving: s.is_some(),
                });
                node = nodes.len() - 1;
                let (v, a, a_rest) = match s {
                    None => (vp, ap, rest_p),
                    Some((c, s)) => {
                        if coords[c].is_some() {
                            return None;
                        }
                        let qd = g.var(vars.qd(c));
                        let qdd = g.var(vars.qdd(c));
                        let sqd = s.scale(g, qd);
                        let v = vp.add(g, sqd);
                        let sqdd = s.scale(g, qdd);
                        let vxs = v.cross_motion(g, s).scale(g, qd);
                        let a = ap.add(g, sqdd).add(g, vxs);
                        coords[c] = Some(Coord { node, s, vp, ap });
                        (v, a, rest_p.add(g, vxs))
                    }
                };
                motion.push((v, a));
                rest.push(a_rest);
            }
        }
        link_node[l] = node;
    }

    // Each body joins the frame after the last moving element above it
    // (constant steps fold); bodies fixed to the base drop out.
    let mut held: Vec<Option<Inertia>> = vec![None; nodes.len()];
    for (l, &start) in link_node.iter().enumerate() {
        for body in bodies(model, l, vars, g)? {
            let (mut node, mut body) = (start, body);
            while node != 0 && !nodes[node].moving {
                body = body.back(g, &nodes[node].step);
                node = nodes[node].parent;
            }
            if node != 0 {
                let sum = match held[node] {
                    Some(b) => b.add(g, body),
                    None => body,
                };
                held[node] = Some(sum);
            }
        }
    }

    Some(Tree {
        nodes,
        motion,
        rest,
        coords,
        held,
    })
}

/// How an element's expressions move: `None` when unsupported (time, more
/// than one coordinate, a rate that varies with q), `Some(None)` when
/// constant, else the coordinate and the rate of each expression.
fn single_rate(g: &mut Graph, exprs: &[Id], vars: Vars) -> Option<Option<(usize, Vec<Id>)>> {
    if exprs.iter().any(|&e| g.depends_on(e, vars.time())) {
        return None;
    }
    let mut found = None;
    for c in 0..vars.n {
        let rates: Vec<Id> = exprs.iter().map(|&e| g.diff(e, vars.q(c))).collect();
        if rates.iter().all(|&r| g.is_zero(r)) {
            continue;
        }
        let varies = rates
            .iter()
            .any(|&r| (0..vars.n).any(|c2| g.depends_on(r, vars.q(c2))));
        if found.is_some() || varies {
            return None;
        }
        found = Some((c, rates));
    }
    Some(found)
}

/// The spatial inertias of a link's bodies (its own and its point masses)
/// about the link frame; `None` if one moves with q.
fn bodies(model: &Model, l: usize, vars: Vars, g: &mut Graph) -> Option<Vec<Inertia>> {
    let link = &model.links[l];
    let zero = g.constant(0.0);
    let mut out = Vec::new();
    let mut parts = Vec::new();
    if let Some(inert) = &link.inertial {
        parts.push((&inert.mass, &inert.com, Some(&inert.inertia)));
    }
    for p in &link.points {
        if let Some(mass) = &p.mass {
            parts.push((mass, &p.at, None));
        }
    }
    for (mass, at, inertia) in parts {
        let m = lower(mass, None, vars, g);
        let c = at.clone().map(|s| lower(&s, None, vars, g));
        let ic = match inertia {
            Some(i) => {
                let [xx, yy, zz, xy, xz, yz] = i.clone().map(|s| lower(&s, None, vars, g));
                [[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]]
            }
            None => [[zero; 3]; 3],
        };
        let all = std::iter::once(m).chain(c).chain(ic.into_iter().flatten());
        let moving = all.clone().any(|e| {
            g.depends_on(e, vars.time()) || (0..vars.n).any(|j| g.depends_on(e, vars.q(j)))
        });
        if moving {
            return None;
        }
        out.push(Inertia::body(g, m, c, ic));
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use quote::quote;

    use super::*;
    use crate::ctxt::Ctxt;
    use crate::{model, parse};

    /// A coordinate that drives two elements (a mimic joint) is outside the
    /// analytic derivatives: the caller must fall back to exact
    /// differentiation.
    #[test]
    fn a_coordinate_driving_two_elements_is_refused() {
        let tokens = quote! {
            pub robot Gripper;
            gravity = [0.0, 0.0, -9.81];
            link palm;
            link left { mass = 0.05; }
            link right { mass = 0.05; }
            joint finger_left = prismatic(palm -> left) { axis = [0.0, 1.0, 0.0]; }
            joint finger_right = prismatic(palm -> right) { axis = [0.0, 1.0, 0.0]; mimic = finger_left; multiplier = -1.0; }
        };
        let mut cx = Ctxt::default();
        let ast = parse::parse(tokens, &mut cx);
        let m = model::build(ast, true, std::path::Path::new("."), &mut cx).expect("valid model");
        let vars = Vars { n: 1, n_params: 0 };
        assert!(tree(&m, vars, &mut Graph::new()).is_none());
    }
}
