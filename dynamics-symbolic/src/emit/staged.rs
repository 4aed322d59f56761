//! One emission pass: the bindings of what the roots need beyond the nodes
//! an earlier stage bound, each node written by its kind (sums and
//! products, sines and cosines, the unary functions) and scheduled into
//! tuple `let`s by level.

use proc_macro2::TokenStream;
use quote::quote;

use super::schedule::{self, by_ready, Item};
use super::{arith, contract, float, ident, trig, Calls, Emitted, Trig};
use crate::graph::Graph;
use crate::node::{Id, Node, Var};

/// The emission, and the nodes it wrote into their users unbound.
pub(super) struct Staged {
    pub(super) emitted: Emitted,
    pub(super) folded: Vec<Id>,
}

/// The emission of what `roots` need beyond the nodes marked in `bound`
/// (read by name).
pub(super) fn emit_staged(
    graph: &Graph,
    roots: &[Id],
    var: &dyn Fn(Var) -> TokenStream,
    trig_fn: Trig<'_>,
    fast: Option<&Calls>,
    bound: &[bool],
) -> Staged {
    let mul_add = fast.map(|f| f.mul_add);
    let math = fast.map(|f| f.math);
    let mut reach = graph.reachable(roots);
    reach.retain(|id| !bound.get(id.index()).copied().unwrap_or(false));
    let pairs = trig::pairs(graph, &reach);
    let operand = |id: Id| -> TokenStream {
        match graph.node(id) {
            Node::Const(c) => float(c.get()),
            Node::Var(v) => var(*v),
            _ => {
                let i = ident(id);
                quote!(#i)
            }
        }
    };
    let level = schedule::levels(graph, &reach);
    let ready = schedule::ready_times(graph, &reach);
    let contracted = match fast {
        Some(_) => contract::products(graph, roots, &reach, &ready),
        None => Default::default(),
    };
    let mut items: Vec<Item> = Vec::new();
    let batch = trig::Batch::new(graph, roots, &reach, &pairs, fast.is_some());
    if let Some(calls) = fast {
        items.extend(batch.item(graph, &pairs, &operand, calls.sin_cos_n));
    }
    let mut folded = Vec::new();
    for &id in &reach {
        let name = ident(id);
        if batch.folded(id) || contracted.contains_key(&id) {
            folded.push(id);
            continue;
        }
        let expr = match graph.node(id) {
            Node::Const(_) | Node::Var(_) => continue,
            Node::Sum { constant, terms } => {
                let terms = by_ready(terms.iter().map(|(t, c)| (*t, c.get())), &ready);
                match mul_add {
                    Some(f) => arith::fused_sum(
                        constant.get(),
                        &terms,
                        &operand,
                        &|t| contracted.get(&t).copied(),
                        f,
                    ),
                    None => arith::plain_sum(constant.get(), &terms, &operand),
                }
            }
            Node::Product { coef, factors } => {
                arith::product(coef.get(), factors, &ready, &operand, math)
            }
            Node::Sin(a) | Node::Cos(a) if batch.has(*a) => continue,
            node @ (Node::Sin(a) | Node::Cos(a)) => {
                let is_sin = matches!(node, Node::Sin(_));
                items.extend(trig::binding(
                    id,
                    is_sin,
                    operand(*a),
                    pairs[a],
                    trig_fn,
                    &level,
                ));
                continue;
            }
            Node::Tanh(a) => {
                let x = operand(*a);
                match math {
                    Some(m) => quote!(#m::tanh(#x)),
                    None => quote!(#x.tanh()),
                }
            }
            Node::Sqrt(a) => {
                let x = operand(*a);
                match math {
                    Some(m) => quote!(#m::sqrt(#x)),
                    None => quote!(#x.sqrt()),
                }
            }
            Node::Abs(a) => {
                let x = operand(*a);
                quote!(#x.abs())
            }
        };
        items.push(Item {
            level: level[id.index()],
            pat: quote!(#name),
            ty: quote!(f64),
            expr,
        });
    }
    Staged {
        emitted: Emitted {
            lets: schedule::bind(items),
            roots: roots.iter().map(|r| operand(*r)).collect(),
        },
        folded,
    }
}
