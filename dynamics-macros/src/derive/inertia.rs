//! The inertia matrix from link Jacobians:
//! `A = sum_k m_k Jv_k^T Jv_k + Jw_k^T R_k I_k R_k^T Jw_k`, plus
//! `m Jv^T Jv` for every point mass. Only the upper triangle is built;
//! the lower one shares its nodes.

use dynamics_symbolic::{Graph, Id};

use super::kinematics::{point_world, transpose, LinkKin};
use super::lower::lower;
use super::Vars;
use crate::model::scalar::Scalar;
use crate::model::Model;

/// A(q), n x n, symmetric by construction.
pub fn mass_matrix(model: &Model, kin: &[LinkKin], vars: Vars, g: &mut Graph) -> Vec<Vec<Id>> {
    let n = vars.n;
    let mut terms: Vec<Vec<Vec<Id>>> = vec![vec![Vec::new(); n]; n];
    for (l, link) in model.links.iter().enumerate() {
        if let Some(inert) = &link.inertial {
            let m = lower(&inert.mass, None, vars, g);
            translational(&mut terms, g, vars, m, &kin[l], &inert.com);
            // Jw in the body frame: R^T Jw; then Jwb^T I Jwb.
            let rt = transpose(&kin[l].pose.r);
            let jwb: Vec<[Id; 3]> = kin[l]
                .w
                .iter()
                .map(|col| super::kinematics::mat_vec(g, &rt, *col))
                .collect();
            let [xx, yy, zz, xy, xz, yz] = inert.inertia.clone().map(|s| lower(&s, None, vars, g));
            let tensor = [[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]];
            for i in 0..n {
                if jwb[i].iter().all(|x| g.is_zero(*x)) {
                    continue;
                }
                let iw = super::kinematics::mat_vec(g, &tensor, jwb[i]);
                for j in i..n {
                    let t: Vec<Id> = (0..3).map(|r| g.mul(iw[r], jwb[j][r])).collect();
                    let s = g.sum(&t);
                    terms[i][j].push(s);
                }
            }
        }
        for p in &link.points {
            if let Some(mass) = &p.mass {
                let m = lower(mass, None, vars, g);
                translational(&mut terms, g, vars, m, &kin[l], &p.at);
            }
        }
    }
    let mut a = vec![vec![g.constant(0.0); n]; n];
    for i in 0..n {
        for j in i..n {
            let s = g.sum(&terms[i][j]);
            a[i][j] = s;
            a[j][i] = s;
        }
    }
    a
}

/// Adds `m Jv^T Jv` of the point `at` of a link.
fn translational(
    terms: &mut [Vec<Vec<Id>>],
    g: &mut Graph,
    vars: Vars,
    m: Id,
    kin: &LinkKin,
    at: &[Scalar; 3],
) {
    let n = vars.n;
    let c = point_world(kin, at, vars, g);
    let jv: Vec<[Id; 3]> = (0..n)
        .map(|j| std::array::from_fn(|r| g.diff(c[r], vars.q(j))))
        .collect();
    for i in 0..n {
        if jv[i].iter().all(|x| g.is_zero(*x)) {
            continue;
        }
        for j in i..n {
            let t: Vec<Id> = (0..3).map(|r| g.mul(jv[i][r], jv[j][r])).collect();
            let dot = g.sum(&t);
            let mt = g.mul(m, dot);
            terms[i][j].push(mt);
        }
    }
}
