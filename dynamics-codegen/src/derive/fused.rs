//! A and Qqt1 + Qqt2 for `motion_and_jacobians`, the function that computes
//! A and the bias, hands them to the caller's solve for qdd, then computes K
//! and D at that qdd: the analytic K, D pass has both nearly for free (the
//! composite momenta it carries up are A's columns; its bodies' `v x* I v`
//! are the bias forces' too), so the fused function takes them from there
//! when that costs fewer operations than the forms the other outputs use.

use dynamics_symbolic::{Graph, Id};

use super::perturbation;

/// A and Qqt1 + Qqt2.
pub type Fused = (Vec<Vec<Id>>, Vec<Id>);

/// The motion terms as the other outputs compute them.
pub struct Shared<'a> {
    pub a: &'a [Vec<Id>],
    pub qqt: &'a [Id],
    pub q0: &'a [Id],
    pub gravity: &'a [Id],
}

/// A and Qqt1 + Qqt2 as `motion_and_jacobians` computes them beside K and
/// D: each from the analytic pass (`A_ij = S_i . u_j`; `Qqt = g - tau(qdd
/// = 0)`, with `g` the gravity efforts Q(0) already holds) or as the other
/// outputs have them, whichever pair costs fewer operations together with
/// K, D and Q(0).
pub fn terms(
    Shared {
        a,
        qqt,
        q0,
        gravity,
    }: Shared,
    rigid: Option<Fused>,
    p: &perturbation::Perturbation,
    g: &mut Graph,
) -> Fused {
    let mut choices = vec![(a.to_vec(), qqt.to_vec())];
    if let Some((rigid_a, bias)) = rigid {
        let rigid_qqt: Vec<Id> = gravity
            .iter()
            .zip(&bias)
            .map(|(&gr, &b)| g.sub(gr, b))
            .collect();
        choices.push((rigid_a.clone(), qqt.to_vec()));
        choices.push((a.to_vec(), rigid_qqt.clone()));
        choices.push((rigid_a, rigid_qqt));
    }
    let jacobians: Vec<Id> = p.k.iter().chain(&p.d).flatten().copied().collect();
    let cost = |g: &Graph, (a, qqt): &Fused| {
        let roots: Vec<Id> = a
            .iter()
            .flatten()
            .chain(qqt)
            .chain(q0)
            .chain(&jacobians)
            .copied()
            .collect();
        g.count_ops(&roots).total()
    };
    let best = (0..choices.len())
        .min_by_key(|&c| cost(g, &choices[c]))
        .unwrap_or(0);
    choices.swap_remove(best)
}
