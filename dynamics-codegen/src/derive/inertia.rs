//! The inertia matrix from link Jacobians,
//! `A = sum_k m_k Jv_k^T Jv_k + Jw_k^T I_k Jw_k`, plus `m Jv^T Jv` for every
//! point mass, with the Jacobians expressed in each link's own frame
//! (`body_jacobian.rs`), where the inertia tensor is constant and the
//! expressions are smallest. The velocity of a point c of the link is
//! `v + w x c`. Only the upper triangle is built; the lower one shares its
//! nodes.

use dynamics_symbolic::{Graph, Id};

use super::body_jacobian::{cross, Column};
use super::lower::lower;
use super::Vars;
use crate::model::scalar::Scalar;
use crate::model::Model;

/// A(q), n x n, symmetric by construction.
pub fn mass_matrix(
    model: &Model,
    jac: &[Vec<Option<Column>>],
    vars: Vars,
    g: &mut Graph,
) -> Vec<Vec<Id>> {
    let n = vars.n;
    let mut terms: Vec<Vec<Vec<Id>>> = vec![vec![Vec::new(); n]; n];
    for (l, link) in model.links.iter().enumerate() {
        let cols = &jac[l];
        if let Some(inert) = &link.inertial {
            let m = lower(&inert.mass, None, vars, g);
            translational(&mut terms, g, vars, m, cols, &inert.com);
            let [xx, yy, zz, xy, xz, yz] = inert.inertia.clone().map(|s| lower(&s, None, vars, g));
            let tensor = [[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]];
            for i in 0..n {
                let Some(ci) = cols[i] else { continue };
                let iw = super::kinematics::mat_vec(g, &tensor, ci.w);
                for j in i..n {
                    let Some(cj) = cols[j] else { continue };
                    let t: Vec<Id> = (0..3).map(|r| g.mul(iw[r], cj.w[r])).collect();
                    let s = g.sum(&t);
                    terms[i][j].push(s);
                }
            }
        }
        for p in &link.points {
            if let Some(mass) = &p.mass {
                let m = lower(mass, None, vars, g);
                translational(&mut terms, g, vars, m, cols, &p.at);
            }
        }
    }
    let mut a = vec![vec![g.constant(0.0); n]; n];
    for i in 0..n {
        for j in i..n {
            let s = g.sum(&terms[i][j]);
            let s = super::smaller_expanded(g, s);
            a[i][j] = s;
            a[j][i] = s;
        }
    }
    a
}

/// Adds `m Jv^T Jv` of the point `at` (link frame) of a link.
fn translational(
    terms: &mut [Vec<Vec<Id>>],
    g: &mut Graph,
    vars: Vars,
    m: Id,
    cols: &[Option<Column>],
    at: &[Scalar; 3],
) {
    let n = vars.n;
    let c = at.clone().map(|s| lower(&s, None, vars, g));
    let jv: Vec<Option<[Id; 3]>> = cols
        .iter()
        .map(|col| {
            col.map(|col| {
                let wxc = cross(g, col.w, c);
                std::array::from_fn(|r| g.add(col.v[r], wxc[r]))
            })
        })
        .collect();
    for i in 0..n {
        let Some(ji) = jv[i] else { continue };
        for j in i..n {
            let Some(jj) = jv[j] else { continue };
            let t: Vec<Id> = (0..3).map(|r| g.mul(ji[r], jj[r])).collect();
            let dot = g.sum(&t);
            let mt = g.mul(m, dot);
            terms[i][j].push(mt);
        }
    }
}
