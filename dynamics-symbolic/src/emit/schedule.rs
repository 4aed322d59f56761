//! When each value is computed: the level (depth in the DAG, then as late
//! as its first user allows) each binding is placed at, the estimated
//! cycle each value is ready at (operands are written in that order), and
//! the tuple `let`s that bind one level at a time.

use proc_macro2::TokenStream;
use quote::quote;

use crate::graph::Graph;
use crate::node::{Id, Node};

/// Largest tuple bound by one `let`.
pub(crate) const MAX_TUPLE: usize = 48;

/// One binding: depth, pattern, type, expression.
pub(super) struct Item {
    pub(super) level: usize,
    pub(super) pat: TokenStream,
    pub(super) ty: TokenStream,
    pub(super) expr: TokenStream,
}

/// The level of each node reachable from the roots: nodes of one level do
/// not depend on each other.
pub(super) fn levels(graph: &Graph, reach: &[Id]) -> Vec<usize> {
    // Depth of each node: nodes of one depth do not depend on each other.
    let mut level = vec![0usize; graph.len()];
    for &id in reach {
        let mut l = 0;
        graph
            .node(id)
            .for_each_child(|c| l = l.max(level[c.index()] + 1));
        level[id.index()] = l;
    }
    // Then as late as possible: each node one level before its earliest
    // user (roots at the last level). Nodes of one level still do not
    // depend on each other, and a value is computed close to where it is
    // used, which keeps fewer values alive at once (fewer spills).
    let last = reach.iter().map(|id| level[id.index()]).max().unwrap_or(0);
    for &id in reach {
        level[id.index()] = last;
    }
    for &id in reach.iter().rev() {
        let l = level[id.index()];
        graph.node(id).for_each_child(|c| {
            level[c.index()] = level[c.index()].min(l.saturating_sub(1));
        });
    }
    level
}

/// Estimated cycle at which each node's value is ready (latencies of a
/// current x86-64 core: add and multiply 3, divide 13, sin/cos 40, other
/// calls 20), each sum and product evaluated left to right as emitted.
pub(super) fn ready_times(graph: &Graph, reach: &[Id]) -> Vec<u32> {
    const ADD: u32 = 3;
    const MUL: u32 = 3;
    let mut ready = vec![0u32; graph.len()];
    for &id in reach {
        let chain = |parts: Vec<u32>, step: u32| -> u32 {
            let mut sorted = parts;
            sorted.sort_unstable();
            let mut it = sorted.into_iter();
            let first = it.next().unwrap_or(0);
            it.fold(first, |acc, t| acc.max(t) + step)
        };
        ready[id.index()] = match graph.node(id) {
            Node::Const(_) | Node::Var(_) => 0,
            Node::Sum { terms, .. } => chain(
                terms
                    .iter()
                    .map(|(t, c)| ready[t.index()] + if c.get().abs() == 1.0 { 0 } else { MUL })
                    .collect(),
                ADD,
            ),
            Node::Product { factors, .. } => {
                chain(
                    factors
                        .iter()
                        .map(|(f, e)| ready[f.index()] + if e.unsigned_abs() > 1 { MUL } else { 0 })
                        .collect(),
                    MUL,
                ) + if factors.iter().any(|f| f.1 < 0) {
                    13
                } else {
                    0
                }
            }
            Node::Sin(a) | Node::Cos(a) => ready[a.index()] + 40,
            Node::Tanh(a) | Node::Sqrt(a) | Node::Abs(a) => ready[a.index()] + 20,
        };
    }
    ready
}

/// Operands in the order they become ready (stable: ties keep the graph's
/// order), so that a left-to-right sum or product adds the last-computed
/// operand last and its chain of operations waits on it only once: the
/// emitted code is latency-bound (a Newton-Euler pass is a chain from the
/// base to the tip and back), and floating-point operations are never
/// reordered by the compiler.
pub(super) fn by_ready<T: Copy>(
    operands: impl Iterator<Item = (Id, T)>,
    ready: &[u32],
) -> Vec<(Id, T)> {
    let mut v: Vec<(Id, T)> = operands.collect();
    v.sort_by_key(|(id, _)| ready[id.index()]);
    v
}

/// The `let` statements: one per level (in chunks of at most
/// [`MAX_TUPLE`]), binding a tuple, levels in order.
pub(super) fn bind(mut items: Vec<Item>) -> TokenStream {
    items.sort_by_key(|it| it.level);
    let mut lets = TokenStream::new();
    for group in items.chunk_by(|a, b| a.level == b.level) {
        for chunk in group.chunks(MAX_TUPLE) {
            if let [it] = chunk {
                let (p, t, e) = (&it.pat, &it.ty, &it.expr);
                lets.extend(quote!(let #p: #t = #e;));
            } else {
                let pats = chunk.iter().map(|c| &c.pat);
                let tys = chunk.iter().map(|c| &c.ty);
                let exprs = chunk.iter().map(|c| &c.expr);
                lets.extend(quote!(let (#(#pats),*): (#(#tys),*) = (#(#exprs),*);));
            }
        }
    }
    lets
}

#[cfg(test)]
mod tests {
    use super::MAX_TUPLE;
    use crate::emit::{emit, names};
    use crate::{Graph, Id, Var};

    #[test]
    fn wide_levels_are_split_into_tuples_of_max_size() {
        let mut g = Graph::new();
        let x = g.var(Var(0));
        let roots: Vec<Id> = (1..=(MAX_TUPLE as i32 + 2))
            .map(|n| g.powi(x, n + 3))
            .collect();
        let out = emit(&g, &roots, &names);
        let lets = out.lets.to_string();
        assert_eq!(lets.matches("let").count(), 2, "{lets}");
        assert_eq!(lets.matches("powi").count(), MAX_TUPLE + 2);
    }
}
