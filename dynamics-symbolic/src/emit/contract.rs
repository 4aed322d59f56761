//! Products folded into the multiply-add of the sum that uses them: a
//! product `a * b` (or `-a * b`, or `a * a`) with one user, added to a sum
//! with coefficient +-1 after the sum's first term, is written as
//! `mul_add(a, b, rest)` there and never bound on its own. What a C
//! compiler's `-ffp-contract=fast` does, chosen here because rustc never
//! contracts: one instruction and one rounding fewer for each, and a value
//! fewer to keep alive.

use std::collections::HashMap;

use super::by_ready;
use crate::graph::Graph;
use crate::node::{Id, Node};

/// A product written into its user's multiply-add: its two factors, and
/// whether its coefficient is -1.
#[derive(Clone, Copy, Debug)]
pub(super) struct Contracted {
    pub(super) a: Id,
    pub(super) b: Id,
    pub(super) negative: bool,
}

/// The products of `reach` to contract, each with its factors.
pub(super) fn products(
    graph: &Graph,
    roots: &[Id],
    reach: &[Id],
    ready: &[u32],
) -> HashMap<Id, Contracted> {
    let mut uses = vec![0u32; graph.len()];
    for r in roots {
        uses[r.index()] += 1;
    }
    for &id in reach {
        graph.node(id).for_each_child(|c| uses[c.index()] += 1);
    }
    let two_factors = |p: Id| -> Option<Contracted> {
        let Node::Product { coef, factors } = graph.node(p) else {
            return None;
        };
        let negative = match coef.get() {
            1.0 => false,
            -1.0 => true,
            _ => return None,
        };
        match factors[..] {
            [(a, 1), (b, 1)] => Some(Contracted { a, b, negative }),
            [(a, 2)] => Some(Contracted { a, b: a, negative }),
            _ => None,
        }
    };
    let mut out = HashMap::new();
    for &id in reach {
        let Node::Sum { constant, terms } = graph.node(id) else {
            continue;
        };
        let sorted = by_ready(terms.iter().map(|(t, c)| (*t, c.get())), ready);
        // The first term is written plainly when there is no constant.
        let skip = usize::from(constant.get() == 0.0);
        for &(t, c) in sorted.iter().skip(skip) {
            if c.abs() == 1.0 && uses[t.index()] == 1 {
                if let Some(p) = two_factors(t) {
                    out.insert(t, p);
                }
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use crate::emit::{emit_fused, names, Calls};
    use crate::{Graph, Var};
    use quote::quote;

    fn calls_emit(g: &Graph, roots: &[crate::Id]) -> String {
        let calls = Calls {
            sin_cos: &quote!(sc),
            sin_cos_n: &quote!(scn),
            mul_add: &quote!(fma),
            math: &quote!(m),
        };
        emit_fused(g, roots, &names, &calls).lets.to_string()
    }

    #[test]
    fn single_use_products_go_into_the_multiply_add() {
        let mut g = Graph::new();
        let (x, y, z) = (g.var(Var(0)), g.var(Var(1)), g.var(Var(2)));
        let xy = g.mul(x, y);
        let yz = g.mul(y, z);
        let neg = g.neg(yz);
        let zz = g.mul(z, z);
        let s = g.sum(&[x, xy, neg, zz]);
        assert_eq!(
            calls_emit(&g, &[s]),
            "let t8 : f64 = fma (z , z , fma (- y , z , fma (x , y , x))) ;"
        );
    }

    #[test]
    fn shared_scaled_or_leading_products_stay_bound() {
        let mut g = Graph::new();
        let (x, y) = (g.var(Var(0)), g.var(Var(1)));
        let xy = g.mul(x, y);
        let s = g.sum(&[x, xy]);
        // `x * y` is also a root: bound once, used twice.
        let out = calls_emit(&g, &[s, xy]);
        assert!(out.contains("= x * y"), "{out}");
        // First in its sum (`sin y` is ready later), it is bound plainly.
        let mut g = Graph::new();
        let (x, y) = (g.var(Var(0)), g.var(Var(1)));
        let xy = g.mul(x, y);
        let sy = g.sin(y);
        let s = g.sum(&[sy, xy]);
        let out = calls_emit(&g, &[s]);
        assert!(out.contains("x * y"), "{out}");
    }
}
