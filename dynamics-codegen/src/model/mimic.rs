//! Mimic joints. A joint declared `mimic = other; multiplier = m; offset =
//! o;` has no coordinate of its own: its position is `m q_other + o`,
//! composed through chains of mimics down to an independent coordinate and
//! substituted for `q` in its transfer chain. Every later stage
//! (kinematics, Jacobians, A, Newton-Euler, K, D) then sees the coupling
//! symbolically, and the efforts are those of the independent coordinates:
//! the generalized forces of the reduced coordinates, `G^T tau` of the free
//! twin with `q = G q_red + offset`.

use std::collections::HashMap;

use super::scalar::{BinOp, Scalar};
use super::{Elem, Follow, Joint, JointKind};
use crate::ctxt::Ctxt;

/// Resolves every `mimic` of the ordered joints (coordinates assigned) and
/// rewrites the mimic joints' chains; errors name the joints.
pub fn resolve(joints: &mut [Joint], cx: &mut Ctxt) {
    let n = joints.len();
    let index: HashMap<String, usize> = joints
        .iter()
        .enumerate()
        .map(|(i, j)| (j.name.to_string(), i))
        .collect();
    // The joint each mimic follows directly.
    let mut edge: Vec<Option<usize>> = vec![None; n];
    for (i, joint) in joints.iter().enumerate() {
        let Some(m) = &joint.mimic else { continue };
        match index.get(&m.of.to_string()) {
            None => cx.error_spanned_by(
                &m.of,
                format!(
                    "joint `{}` mimics `{}`, which is not a joint of this robot",
                    joint.name, m.of
                ),
            ),
            Some(&t) if t == i => {
                cx.error_spanned_by(&m.of, format!("joint `{}` mimics itself", joint.name))
            }
            Some(&t) if joints[t].kind == JointKind::Fixed => cx.error_spanned_by(
                &m.of,
                format!(
                    "joint `{}` mimics `{}`, a fixed joint: there is no motion to follow",
                    joint.name, m.of
                ),
            ),
            Some(&t) => edge[i] = Some(t),
        }
    }
    for i in 0..n {
        if edge[i].is_none() {
            continue;
        }
        match follow(joints, &edge, i) {
            Ok(Some(f)) => joints[i].follows = Some(f),
            Ok(None) => {} // below a mimic whose own target failed
            Err(cycle) => {
                // Reported once, at the first joint of the cycle.
                if cycle.iter().min() == Some(&i) {
                    let names: Vec<String> = cycle
                        .iter()
                        .chain(std::iter::once(&i))
                        .map(|&k| format!("`{}`", joints[k].name))
                        .collect();
                    cx.error_spanned_by(
                        &joints[i].name,
                        format!(
                            "mimic joints form a cycle ({}): one of them must be independent",
                            names.join(" -> ")
                        ),
                    );
                }
            }
        }
    }
    for joint in joints.iter_mut() {
        let Some(f) = joint.follows else { continue };
        let q = coupling(f);
        for e in &mut joint.chain {
            substitute_elem(e, &q);
        }
    }
}

/// The composed coupling of mimic `i`; `Err(cycle)` (the joints met from
/// `i` on) when `i` lies on a cycle, `Ok(None)` when the chain ends at a
/// joint without a coordinate (an error reported elsewhere) or runs into a
/// cycle `i` is not part of.
fn follow(
    joints: &[Joint],
    edge: &[Option<usize>],
    i: usize,
) -> Result<Option<Follow>, Vec<usize>> {
    let (mut multiplier, mut offset) = (1.0, 0.0);
    let mut at = i;
    let mut path = Vec::new();
    while let Some(t) = edge[at] {
        let Some(m) = &joints[at].mimic else {
            return Ok(None);
        };
        // position_i = multiplier * position_at + offset, position_at = m q_t + o
        offset += multiplier * m.offset;
        multiplier *= m.multiplier;
        path.push(at);
        at = t;
        if at == i {
            return Err(path);
        }
        if path.len() > joints.len() {
            return Ok(None);
        }
    }
    if joints[at].mimic.is_some() {
        return Ok(None);
    }
    Ok(joints[at].coord.map(|coord| Follow {
        coord,
        multiplier,
        offset,
    }))
}

/// `multiplier * q[coord] + offset`, without the factor 1 or the term 0.
pub fn coupling(f: Follow) -> Scalar {
    let q = Scalar::Joint(f.coord);
    let scaled = if f.multiplier == 1.0 {
        q
    } else {
        Scalar::Bin(BinOp::Mul, Box::new(Scalar::Num(f.multiplier)), Box::new(q))
    };
    if f.offset == 0.0 {
        scaled
    } else {
        Scalar::Bin(
            BinOp::Add,
            Box::new(scaled),
            Box::new(Scalar::Num(f.offset)),
        )
    }
}

fn substitute_elem(e: &mut Elem, q: &Scalar) {
    match e {
        Elem::Rot(_, a) => substitute(a, q),
        Elem::Trans(t) => t.iter_mut().for_each(|s| substitute(s, q)),
        Elem::Matrix(r, t) => {
            r.iter_mut().flatten().for_each(|s| substitute(s, q));
            t.iter_mut().for_each(|s| substitute(s, q));
        }
    }
}

/// Replaces the joint coordinate `q` in `s` by `with`.
fn substitute(s: &mut Scalar, with: &Scalar) {
    match s {
        Scalar::Coord => *s = with.clone(),
        Scalar::Num(_) | Scalar::Param(_) | Scalar::Joint(_) | Scalar::Time => {}
        Scalar::Neg(a) | Scalar::Call(_, a) => substitute(a, with),
        Scalar::Bin(_, a, b) => {
            substitute(a, with);
            substitute(b, with);
        }
    }
}

#[cfg(test)]
mod tests {
    use quote::quote;

    use super::*;
    use crate::model::{build, Model};
    use crate::parse;

    fn model(tokens: proc_macro2::TokenStream) -> Model {
        let mut cx = Ctxt::default();
        let ast = parse::parse(tokens, &mut cx);
        let m = build(ast, true, std::path::Path::new("."), &mut cx);
        assert!(cx.check().is_ok());
        m.expect("a valid model")
    }

    /// A mimic of a mimic composes to the independent joint, whatever the
    /// declaration order; the mimics get no coordinate and their chains
    /// name the leader's.
    #[test]
    fn chains_of_mimics_compose() {
        let m = model(quote! {
            pub robot R;
            gravity = [0.0, 0.0, -9.81];
            link base;
            link a { mass = 1.0; }
            link b { mass = 1.0; }
            link c { mass = 1.0; }
            joint j3 = revolute(b -> c) { axis = [0.0, 0.0, 1.0]; mimic = j2; multiplier = -2.0; offset = 0.3; }
            joint j1 = revolute(base -> a) { axis = [0.0, 0.0, 1.0]; }
            joint j2 = prismatic(a -> b) { transfer = [trans_x(2.0 * q)]; mimic = j1; multiplier = 0.5; offset = 0.1; }
        });
        let by = |n: &str| m.joints.iter().find(|j| j.name == n).expect("a joint");
        assert_eq!(by("j1").coord, Some(0));
        assert_eq!(m.coords().len(), 1);
        let f = by("j3").follows.expect("j3 follows j1");
        assert_eq!((f.coord, f.multiplier), (0, -1.0));
        assert!((f.offset - 0.1).abs() < 1e-15);
        // j2's `2 q` became `2 (0.5 q_0 + 0.1)`.
        match &by("j2").chain[..] {
            [Elem::Trans([x, _, _])] => {
                assert!(x.moves() && !x.has_coord());
                let want = Scalar::Bin(
                    BinOp::Mul,
                    Box::new(Scalar::Num(2.0)),
                    Box::new(coupling(Follow {
                        coord: 0,
                        multiplier: 0.5,
                        offset: 0.1,
                    })),
                );
                assert_eq!(*x, want);
            }
            other => panic!("unexpected chain {other:?}"),
        }
    }
}
