//! Sines and cosines: `sin(x)` and `cos(x)` of one `x` computed by one
//! `sin_cos` call, and (for [`emit_fused()`](crate::emit_fused)) those of
//! all variables by one `sin_cos_n` call.

use std::collections::HashMap;

use proc_macro2::TokenStream;
use quote::quote;

use super::arith::plain_sum;
use super::{ident, Item, Trig};
use crate::graph::Graph;
use crate::node::{Id, Node};

/// Argument -> (its sine, its cosine), of the reachable nodes.
pub(super) type Pairs = HashMap<Id, (Option<Id>, Option<Id>)>;

/// The sine and cosine nodes of each argument among `reach`.
pub(super) fn pairs(graph: &Graph, reach: &[Id]) -> Pairs {
    let mut trig: Pairs = HashMap::new();
    for &id in reach {
        match graph.node(id) {
            Node::Sin(a) => trig.entry(*a).or_default().0 = Some(id),
            Node::Cos(a) => trig.entry(*a).or_default().1 = Some(id),
            _ => {}
        }
    }
    trig
}

/// The arguments whose sine and cosine one `sin_cos_n` call computes.
///
/// Sines and cosines of variables, or of sums of variables and constants
/// (a joint offset: `q + 1.57`), all in one `sin_cos_n` call, first; such
/// a sum is written into the call, and bound on its own only if something
/// else uses it.
pub(super) struct Batch {
    /// Sorted arguments (none when fewer than two).
    batched: Vec<Id>,
    /// Whether each node is used other than as a batched argument.
    used_apart: Vec<bool>,
}

impl Batch {
    /// The batch of `reach` (empty unless `fast`).
    pub(super) fn new(graph: &Graph, roots: &[Id], reach: &[Id], trig: &Pairs, fast: bool) -> Self {
        let is_leaf = |a: Id| matches!(graph.node(a), Node::Var(_) | Node::Const(_));
        let simple = |a: Id| match graph.node(a) {
            Node::Var(_) => true,
            Node::Sum { terms, .. } => terms.iter().all(|(t, _)| is_leaf(*t)),
            _ => false,
        };
        let mut batched: Vec<Id> = if fast {
            trig.keys().copied().filter(|a| simple(*a)).collect()
        } else {
            Vec::new()
        };
        batched.sort_unstable();
        if batched.len() < 2 {
            batched.clear();
        }
        let mut used_apart: Vec<bool> = vec![false; graph.len()];
        for r in roots {
            used_apart[r.index()] = true;
        }
        for &id in reach {
            let node = graph.node(id);
            if !matches!(node, Node::Sin(a) | Node::Cos(a) if batched.binary_search(a).is_ok()) {
                node.for_each_child(|c| used_apart[c.index()] = true);
            }
        }
        Batch {
            batched,
            used_apart,
        }
    }

    /// Whether `a`'s sine and cosine come from the batch.
    pub(super) fn has(&self, a: Id) -> bool {
        self.batched.binary_search(&a).is_ok()
    }

    /// Whether `id` is a batched argument written into the call only.
    pub(super) fn folded(&self, id: Id) -> bool {
        self.has(id) && !self.used_apart[id.index()]
    }

    /// The binding of the batch's `sin_cos_n` call, if there is a batch.
    pub(super) fn item(
        &self,
        graph: &Graph,
        trig: &Pairs,
        operand: &dyn Fn(Id) -> TokenStream,
        p: &TokenStream,
    ) -> Option<Item> {
        let (batched, used_apart) = (&self.batched, &self.used_apart);
        if batched.is_empty() {
            return None;
        }
        let lane = |t: Option<Id>| match t {
            Some(t) => {
                let i = ident(t);
                quote!(#i)
            }
            None => quote!(_),
        };
        let sins = batched.iter().map(|a| lane(trig[a].0));
        let coss = batched.iter().map(|a| lane(trig[a].1));
        let args = batched.iter().map(|&a| match graph.node(a) {
            Node::Sum { constant, terms } if !used_apart[a.index()] => {
                let terms: Vec<(Id, f64)> = terms.iter().map(|(t, c)| (*t, c.get())).collect();
                plain_sum(constant.get(), &terms, operand)
            }
            _ => operand(a),
        });
        let n = batched.len();
        Some(Item {
            level: 0,
            pat: quote!(([#(#sins),*], [#(#coss),*])),
            ty: quote!(([f64; #n], [f64; #n])),
            expr: quote!(#p([#(#args),*])),
        })
    }
}

/// The binding of the sine (`is_sin`) or cosine node `id` of `x`: with its
/// partner, one `sin_cos` bound at the first of the two (None at the
/// second); alone, `x.sin()` or `sin_cos(x).0`.
pub(super) fn binding(
    id: Id,
    is_sin: bool,
    x: TokenStream,
    pair: (Option<Id>, Option<Id>),
    trig_fn: Trig<'_>,
    level: &[usize],
) -> Option<Item> {
    match pair {
        (Some(s), Some(c)) => {
            if id != s.min(c) {
                return None;
            }
            let pair_level = level[s.index()].min(level[c.index()]);
            let (si, ci) = (ident(s), ident(c));
            let expr = match trig_fn {
                Trig::Method => quote!(#x.sin_cos()),
                Trig::Path(p) => quote!(#p(#x)),
            };
            Some(Item {
                level: pair_level,
                pat: quote!((#si, #ci)),
                ty: quote!((f64, f64)),
                expr,
            })
        }
        _ => {
            let expr = match (trig_fn, is_sin) {
                (Trig::Method, true) => quote!(#x.sin()),
                (Trig::Method, false) => quote!(#x.cos()),
                (Trig::Path(p), true) => quote!(#p(#x).0),
                (Trig::Path(p), false) => quote!(#p(#x).1),
            };
            let name = ident(id);
            Some(Item {
                level: level[id.index()],
                pat: quote!(#name),
                ty: quote!(f64),
                expr,
            })
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::emit::{emit_fused, emit_with, names, Calls};
    use crate::Graph;
    use crate::Var;
    use quote::quote;

    #[test]
    fn custom_sin_cos_path() {
        let mut g = Graph::new();
        let x = g.var(Var(0));
        let (s, c) = (g.sin(x), g.cos(x));
        let y = g.var(Var(1));
        let cy = g.cos(y);
        let e = g.product(&[s, c, cy]);
        let out = emit_with(&g, &[e], &names, &quote!(k::sc));
        assert_eq!(
            out.lets.to_string(),
            "let ((t1 , t2) , t4) : ((f64 , f64) , f64) = (k :: sc (x) , k :: sc (y) . 1) ; \
             let t5 : f64 = t1 * t2 * t4 ;"
        );
    }

    #[test]
    fn joint_offsets_go_into_the_batched_sin_cos() {
        let mut g = Graph::new();
        let (x, y) = (g.var(Var(0)), g.var(Var(1)));
        let k = g.constant(1.5);
        let a = g.add(k, x);
        let (sa, ca, cy) = (g.sin(a), g.cos(a), g.cos(y));
        let p = g.product(&[sa, ca, cy]);
        let calls = Calls {
            sin_cos: &quote!(sc),
            sin_cos_n: &quote!(scn),
            mul_add: &quote!(f),
            math: &quote!(m),
        };
        let out = emit_fused(&g, &[p], &names, &calls);
        assert_eq!(
            out.lets.to_string(),
            "let ([_ , t4] , [t6 , t5]) : ([f64 ; 2usize] , [f64 ; 2usize]) = \
             scn ([y , 1.5f64 + x]) ; let t7 : f64 = t4 * t5 * t6 ;"
        );
        // Used elsewhere too, the offset angle is bound and passed by name.
        let q = g.mul(p, a);
        let out = emit_fused(&g, &[q], &names, &calls);
        assert!(
            out.lets.to_string().contains("scn ([y , t3])"),
            "{}",
            out.lets
        );
    }
}
