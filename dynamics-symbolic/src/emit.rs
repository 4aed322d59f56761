//! Emission of a DAG as a straight-line Rust `let` chain.

use std::collections::HashMap;

use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::quote;

use crate::graph::Graph;
use crate::node::{Id, Node, Var};

/// Largest tuple bound by one `let`.
const MAX_TUPLE: usize = 48;

/// The emitted code: the `let` chain, and the expression of each root.
pub struct Emitted {
    /// `let tN: f64 = ...;` statements, in topological order.
    pub lets: TokenStream,
    /// Each root's value: an identifier, a variable or a literal.
    pub roots: Vec<TokenStream>,
}

/// A float literal, also for values a literal cannot spell.
pub fn float(v: f64) -> TokenStream {
    if v.is_nan() {
        quote!(f64::NAN)
    } else if v.is_infinite() {
        if v > 0.0 {
            quote!(f64::INFINITY)
        } else {
            quote!((-f64::INFINITY))
        }
    } else if v < 0.0 {
        let lit = Literal::f64_suffixed(-v);
        quote!((-#lit))
    } else {
        let lit = Literal::f64_suffixed(v);
        quote!(#lit)
    }
}

fn ident(id: Id) -> Ident {
    Ident::new(&format!("t{}", id.index()), Span::call_site())
}

/// Emits one `let` per used non-leaf node reachable from `roots`; `sin(x)`
/// and `cos(x)` of the same `x` become one `x.sin_cos()`.
///
/// ```
/// use dynamics_symbolic::{emit, Graph, Var};
/// let mut g = Graph::new();
/// let x = g.var(Var(0));
/// let s = g.sin(x);
/// let c = g.cos(x);
/// let e = g.mul(s, c);
/// let out = emit(&g, &[e], &|_| quote::quote!(x));
/// let code = out.lets.to_string();
/// assert!(code.contains("sin_cos"), "{code}");
/// assert_eq!(out.roots[0].to_string(), "t3");
/// ```
pub fn emit(graph: &Graph, roots: &[Id], var: &dyn Fn(Var) -> TokenStream) -> Emitted {
    emit_with(graph, roots, var, &quote!(f64::sin_cos))
}

/// [`emit()`] with the function that computes `(sin x, cos x)` given as a
/// path (called as `path(x)`), e.g. a faster one than `f64::sin_cos`.
///
/// ```
/// use dynamics_symbolic::{emit_with, Graph, Var};
/// let mut g = Graph::new();
/// let x = g.var(Var(0));
/// let s = g.sin(x);
/// let out = emit_with(&g, &[s], &|_| quote::quote!(x), &quote::quote!(my::sin_cos));
/// assert_eq!(out.lets.to_string(), "let t1 = my :: sin_cos (x) . 0 ;");
/// ```
pub fn emit_with(
    graph: &Graph,
    roots: &[Id],
    var: &dyn Fn(Var) -> TokenStream,
    sin_cos: &TokenStream,
) -> Emitted {
    let reach = graph.reachable(roots);
    // sin/cos pairs: argument -> (sin id, cos id)
    let mut trig: HashMap<Id, (Option<Id>, Option<Id>)> = HashMap::new();
    for &id in &reach {
        match graph.node(id) {
            Node::Sin(a) => trig.entry(*a).or_default().0 = Some(id),
            Node::Cos(a) => trig.entry(*a).or_default().1 = Some(id),
            _ => {}
        }
    }
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
    let power = |f: Id, e: i32| -> TokenStream {
        let x = operand(f);
        match e {
            1 => x,
            2 => quote!(#x * #x),
            3 => quote!(#x * #x * #x),
            _ => quote!(#x.powi(#e)),
        }
    };
    // Depth of each node: nodes of one depth do not depend on each other.
    let mut level = vec![0usize; graph.len()];
    for &id in &reach {
        level[id.index()] = graph
            .node(id)
            .children()
            .iter()
            .map(|c| level[c.index()] + 1)
            .max()
            .unwrap_or(0);
    }
    // (depth, pattern, expression) of every binding.
    let mut items: Vec<(usize, TokenStream, TokenStream)> = Vec::new();
    for &id in &reach {
        let name = ident(id);
        let rhs = match graph.node(id) {
            Node::Const(_) | Node::Var(_) => continue,
            Node::Sum { constant, terms } => {
                let mut out = TokenStream::new();
                let mut first = true;
                if constant.get() != 0.0 {
                    out.extend(float(constant.get()));
                    first = false;
                }
                for (t, c) in terms.iter() {
                    let (c, x) = (c.get(), operand(*t));
                    let mag = c.abs();
                    let term = if mag == 1.0 {
                        x
                    } else {
                        let k = float(mag);
                        quote!(#k * #x)
                    };
                    out.extend(match (first, c < 0.0) {
                        (true, false) => term,
                        (true, true) => quote!(-#term),
                        (false, false) => quote!(+ #term),
                        (false, true) => quote!(- #term),
                    });
                    first = false;
                }
                out
            }
            Node::Product { coef, factors } => {
                let num: Vec<TokenStream> = factors
                    .iter()
                    .filter(|f| f.1 > 0)
                    .map(|&(f, e)| power(f, e))
                    .collect();
                let den: Vec<TokenStream> = factors
                    .iter()
                    .filter(|f| f.1 < 0)
                    .map(|&(f, e)| power(f, -e))
                    .collect();
                let c = coef.get();
                let mut all = Vec::new();
                if c.abs() != 1.0 || num.is_empty() {
                    all.push(float(c.abs()));
                }
                all.extend(num);
                let numer = join_mul(all);
                let signed = if c < 0.0 { quote!(-(#numer)) } else { numer };
                if den.is_empty() {
                    signed
                } else {
                    let d = join_mul(den);
                    quote!((#signed) / (#d))
                }
            }
            Node::Sin(a) | Node::Cos(a) => {
                let (s, c) = trig[a];
                match (s, c) {
                    (Some(s), Some(c)) => {
                        if id == s.min(c) {
                            let (si, ci, x) = (ident(s), ident(c), operand(*a));
                            items.push((
                                level[id.index()],
                                quote!((#si, #ci)),
                                quote!(#sin_cos(#x)),
                            ));
                        }
                        continue;
                    }
                    _ => {
                        let x = operand(*a);
                        if matches!(graph.node(id), Node::Sin(_)) {
                            quote!(#sin_cos(#x).0)
                        } else {
                            quote!(#sin_cos(#x).1)
                        }
                    }
                }
            }
            Node::Tanh(a) => {
                let x = operand(*a);
                quote!(#x.tanh())
            }
            Node::Sqrt(a) => {
                let x = operand(*a);
                quote!(#x.sqrt())
            }
            Node::Abs(a) => {
                let x = operand(*a);
                quote!(#x.abs())
            }
        };
        items.push((level[id.index()], quote!(#name), rhs));
    }
    // One `let` per depth (in chunks), binding a tuple: a long chain of
    // single `let`s nests one lexical scope per binding, and rustc's debug
    // info recursion overflows its stack on the tens of thousands a 7-DOF
    // arm needs; the depth of the DAG is small.
    items.sort_by_key(|(l, _, _)| *l);
    let mut lets = TokenStream::new();
    let mut start = 0;
    while start < items.len() {
        let l = items[start].0;
        let mut end = start;
        while end < items.len() && items[end].0 == l && end - start < MAX_TUPLE {
            end += 1;
        }
        let chunk = &items[start..end];
        if chunk.len() == 1 {
            let (_, p, e) = &chunk[0];
            lets.extend(quote!(let #p = #e;));
        } else {
            let pats = chunk.iter().map(|c| &c.1);
            let exprs = chunk.iter().map(|c| &c.2);
            lets.extend(quote!(let (#(#pats),*) = (#(#exprs),*);));
        }
        start = end;
    }
    Emitted {
        lets,
        roots: roots.iter().map(|r| operand(*r)).collect(),
    }
}

/// `a * b * c`
fn join_mul(factors: Vec<TokenStream>) -> TokenStream {
    let mut out = TokenStream::new();
    for (k, f) in factors.into_iter().enumerate() {
        if k > 0 {
            out.extend(quote!(*));
        }
        out.extend(f);
    }
    out
}
