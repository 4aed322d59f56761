//! K = dU/dq and D = dU/dqd of the rigid-body Newton-Euler efforts by the
//! analytic O(n^2) algorithm of Carpentier & Mansard (RSS 2018, the one
//! behind Pinocchio's computeRNEADerivatives), derived here in the frames
//! of the transfer elements so that the constant axes fold.
//!
//! Let S_j be the twist of coordinate j (the axis of its moving element),
//! p the frame before that element, `x_j = S_j x v_p`,
//! `y_j = S_j x a_p + v_p x x_j`, and for the subtree moved by j its
//! composite inertia `I^C_j`, momentum `h^C_j`, force `F_j` and inertia rate
//! `dI^C_j` (each body's `v x* I - I v x`). Perturbing q_j moves the subtree
//! rigidly about S_j, which gives, with `B^C z = z x* h^C + dI^C z`,
//!
//! - `dF_k/dq_j = S_j x* F_k - I^C_k y_j - B^C_k x_j` for k in the subtree
//!   of j, so `dtau_k/dq_j = -(u_k . y_j + r_k . x_j)` with `u_k = I^C_k S_k`
//!   and `r_k = (B^C_k)^T S_k = dI^C_k S_k - S_k x* h^C_k`; for k above j,
//!   `dtau_k/dq_j = S_k . G_j`, `G_j = S_j x* F_j - I^C_j y_j - B^C_j x_j`;
//! - `dF_k/dqd_j = B^C_k S_j - 2 I^C_k x_j`, so `dtau_k/dqd_j =
//!   r_k . S_j - 2 u_k . x_j` below j and `S_k . H_j`,
//!   `H_j = B^C_j S_j - 2 I^C_j x_j`, above.
//!
//! The pairs are formed in the frame of the upper coordinate, the force
//! vectors `u, r, G, H` of the lower one carried up element by element.
//! Only for chains whose moving elements each follow one coordinate at a
//! constant rate (revolute and prismatic joints); otherwise `None`.

use dynamics_symbolic::{Graph, Id};

use super::element_tree::{tree, Tree};
use super::spatial::{Inertia, Sv};
use super::Vars;
use crate::model::Model;

/// K and D of the rigid body (no damping, friction or springs), and the
/// inertia matrix from the same composite inertias.
pub struct Rigid {
    /// `k[i][j] = dtau_i/dq_j`.
    pub k: Vec<Vec<Id>>,
    /// `d[i][j] = dtau_i/dqd_j`.
    pub d: Vec<Vec<Id>>,
    /// `a[i][j] = S_i . I^C_j S_j` (j in the subtree of i, else mirrored or
    /// zero): the momentum `u_j` carried up for K is A's column, so beside
    /// K and D the inertia matrix costs one dot product with a constant
    /// axis per entry.
    pub a: Vec<Vec<Id>>,
    /// The rigid-body efforts at `qdd = 0` (velocity products and gravity,
    /// `S_j . F0_j`): the bias, sharing each body's `v x* I v` with K.
    pub bias: Vec<Id>,
}

/// K and D of the rigid body, or `None` when the model is outside
/// [`tree`]'s reach.
pub fn jacobians(model: &Model, vars: Vars, g: &mut Graph) -> Option<Rigid> {
    let n = vars.n;
    let zero = g.constant(0.0);
    let Tree {
        nodes,
        motion,
        rest,
        coords,
        held,
    } = tree(model, vars, g)?;

    // Backward: composite inertia, its rate, momentum and force per node,
    // and the force at qdd = 0.
    let empty = (Inertia::zero(g), Inertia::zero(g), Sv::zero(g), Sv::zero(g));
    let mut comp = vec![empty; nodes.len()];
    let mut comp_rest = vec![Sv::zero(g); nodes.len()];
    for (node, body) in held.iter().enumerate() {
        let Some(body) = *body else {
            continue;
        };
        let (v, a) = motion[node];
        let iv = body.apply(g, v);
        let ia = body.apply(g, a);
        let vxiv = v.cross_force(g, iv);
        let f = vxiv.add(g, ia);
        let rate = body.rate(g, v);
        comp[node] = (body, rate, iv, f);
        let ia_rest = body.apply(g, rest[node]);
        comp_rest[node] = vxiv.add(g, ia_rest);
    }
    for k in (1..nodes.len()).rev() {
        let p = nodes[k].parent;
        if p == 0 {
            continue;
        }
        let (ic, di, h, f) = comp[k];
        let step = nodes[k].step;
        let moved = (
            ic.back(g, &step),
            di.back(g, &step),
            h.force_back(g, &step),
            f.force_back(g, &step),
        );
        let c = comp[p];
        comp[p] = (
            c.0.add(g, moved.0),
            c.1.add(g, moved.1),
            c.2.add(g, moved.2),
            c.3.add(g, moved.3),
        );
        let moved_rest = comp_rest[k].force_back(g, &step);
        comp_rest[p] = comp_rest[p].add(g, moved_rest);
    }
    let bias = coords
        .iter()
        .map(|c| match c {
            Some(info) => info.s.dot(g, comp_rest[info.node]),
            None => zero,
        })
        .collect();

    // Per coordinate: x, y and the force vectors u, r, G, H.
    let mut coord_at = vec![None; nodes.len()];
    let mut per = Vec::with_capacity(n);
    for (c, info) in coords.iter().enumerate() {
        let Some(info) = info else {
            per.push(None);
            continue;
        };
        coord_at[info.node] = Some(c);
        let (ic, di, h, f) = comp[info.node];
        let s = info.s;
        let x = s.cross_motion(g, info.vp);
        let sxa = s.cross_motion(g, info.ap);
        let vxx = info.vp.cross_motion(g, x);
        let y = sxa.add(g, vxx);
        let u = ic.apply(g, s);
        let dis = di.apply(g, s);
        let sxh = s.cross_force(g, h);
        let r = dis.sub(g, sxh);
        let icy = ic.apply(g, y);
        let xxh = x.cross_force(g, h);
        let dix = di.apply(g, x);
        let sxf = s.cross_force(g, f);
        let gj = sxf.sub(g, icy).sub(g, xxh).sub(g, dix);
        let two = g.constant(2.0);
        let icx = ic.apply(g, x).scale(g, two);
        let hj = sxh.add(g, dis).sub(g, icx);
        per.push(Some((s, x, y, [u, r, gj, hj])));
    }

    let mut k = vec![vec![zero; n]; n];
    let mut d = vec![vec![zero; n]; n];
    let mut a = vec![vec![zero; n]; n];
    for (lo, info) in coords.iter().enumerate() {
        let (Some(info), Some((_, _, _, vecs))) = (info, per[lo]) else {
            continue;
        };
        let mut vecs = vecs;
        let mut node = info.node;
        loop {
            if let Some(hi) = coord_at[node] {
                let (s, x, y, _) = per[hi]?;
                let [u, r, gk, hk] = vecs;
                a[hi][lo] = s.dot(g, u);
                a[lo][hi] = a[hi][lo];
                let uy = u.dot(g, y);
                let rx = r.dot(g, x);
                let sum = g.add(uy, rx);
                k[lo][hi] = g.neg(sum);
                let rs = r.dot(g, s);
                let ux = u.dot(g, x);
                let two_ux = g.scale(ux, 2.0);
                d[lo][hi] = g.sub(rs, two_ux);
                if hi != lo {
                    k[hi][lo] = s.dot(g, gk);
                    d[hi][lo] = s.dot(g, hk);
                }
            }
            let parent = nodes[node].parent;
            if parent == 0 {
                break;
            }
            let step = nodes[node].step;
            vecs = vecs.map(|f| f.force_back(g, &step));
            node = parent;
        }
    }
    Some(Rigid { k, d, a, bias })
}

#[cfg(test)]
mod tests {
    use dynamics_symbolic::Var;
    use quote::quote;

    use super::super::rnea::{inverse_dynamics, Terms};
    use super::*;
    use crate::ctxt::Ctxt;
    use crate::{model, parse};

    /// Against the exact derivatives of the Newton-Euler DAG (and A against
    /// the composite-rigid-body pass), on a branched
    /// tree with a tilted axis, rpy offsets, a prismatic joint, a moving
    /// element followed by a constant one, a point mass and tilted gravity.
    #[test]
    fn matches_differentiated_newton_euler() {
        let tokens = quote! {
            pub robot Tree;
            gravity = [0.5, -9.0, 1.5];
            link base;
            link a { mass = 2.0; com = [0.1, 0.05, -0.02]; inertia = [0.02, 0.03, 0.04]; }
            link b { mass = 1.5; com = [0.0, 0.2, 0.1]; inertia = [0.01, 0.02, 0.015]; }
            link c { mass = 0.7; com = [0.05, 0.0, 0.1]; inertia = [0.003, 0.004, 0.005]; }
            link d { point_mass tip = 0.5 at [0.1, 0.0, 0.2]; }
            joint j1 = revolute(base -> a) { origin = [0.1, 0.2, 0.3]; rpy = [0.3, -0.2, 0.5]; axis = [0.0, 0.6, 0.8]; }
            joint j2 = prismatic(a -> b) { transfer = [tu(0.3), rot_y(0.4), trans_z(q)]; }
            joint j3 = revolute(a -> c) { transfer = [tv(0.2), rot_x(q)]; }
            joint j4 = revolute(b -> d) { transfer = [rot_z(q), tu(0.2)]; }
        };
        let mut cx = Ctxt::default();
        let ast = parse::parse(tokens, &mut cx);
        let m = model::build(ast, true, std::path::Path::new("."), &mut cx).expect("valid model");
        assert!(cx.check().is_ok());
        let vars = Vars { n: 4, n_params: 0 };
        let mut g = Graph::new();
        let all = Terms {
            velocity: true,
            acceleration: true,
            gravity: true,
        };
        let tau = inverse_dynamics(&m, vars, all, &mut g).expect("Newton-Euler applies");
        let Rigid { k, d, a, bias } =
            jacobians(&m, vars, &mut g).expect("the analytic form applies");
        let crba =
            super::super::crba::mass_matrix(&m, vars, &mut g).expect("revolute and prismatic");
        let values = |v: Var| 0.3 + 0.7 * (v.0 as f64 * 1.3).sin();
        let at_rest = |v: Var| match vars.classify(v) {
            (2, _) => 0.0,
            _ => values(v),
        };
        let got = g.eval(&bias, &at_rest);
        let want = g.eval(&tau, &at_rest);
        for (i, (x, y)) in got.iter().zip(&want).enumerate() {
            assert!(
                (x - y).abs() <= 1e-12 * (1.0 + y.abs()),
                "bias {i}: {x} vs {y}"
            );
        }
        for i in 0..4 {
            for j in 0..4 {
                let dk = g.diff(tau[i], vars.q(j));
                let dd = g.diff(tau[i], vars.qd(j));
                let got = g.eval(&[k[i][j], d[i][j], a[i][j]], &values);
                let want = g.eval(&[dk, dd, crba[i][j]], &values);
                for (x, y) in got.iter().zip(&want) {
                    assert!(
                        (x - y).abs() <= 1e-12 * (1.0 + y.abs()),
                        "({i}, {j}): {x} vs {y}"
                    );
                }
            }
        }
    }
}
