//! Emission of a DAG as a straight-line Rust `let` chain.
//!
//! Every used non-leaf node N is bound once to `tN: f64`; leaves are inlined
//! (a variable as the caller's tokens, a constant as a suffixed literal).
//! Bindings are grouped by level in the DAG, each node at the last level
//! before its first user: all nodes of one level (at most [`MAX_TUPLE`] at
//! a time) are bound by one tuple `let`, e.g.
//! `let (t4, (t5, t6)): (f64, (f64, f64)) = (x * y, x.sin_cos());`. A chain
//! of tens of thousands of single `let`s nests one scope per binding, and
//! rustc's debug-info pass overflowed its stack on a 7-DOF arm; the depth
//! of these DAGs is small. Operands of sums and products are written in
//! the order their values become ready (the code is latency-bound).
//! Sums are `k + a - 2.5 * b`, products
//! `-3.0 * a * b * b / (c * d.powi(4))` (powers 2 and 3 as repeated
//! multiplies, `x^-1` as `1.0 / x`), no allocation anywhere.

use std::collections::HashMap;

use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::quote;

use crate::graph::Graph;
use crate::node::{Id, Node, Var};

/// Largest tuple bound by one `let`.
pub(crate) const MAX_TUPLE: usize = 48;

/// The emitted code: the `let` chain, and the expression of each root.
#[derive(Debug, Clone)]
pub struct Emitted {
    /// `let` statements in topological order; node N is bound to `tN`.
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

/// How `sin` and `cos` are computed.
#[derive(Clone, Copy)]
enum Trig<'a> {
    /// `x.sin()`, `x.cos()`, `x.sin_cos()`.
    Method,
    /// `path(x).0`, `path(x).1`, `path(x)`.
    Path(&'a TokenStream),
}

/// Emits one binding per used non-leaf node reachable from `roots` (see
/// the module doc for the shape); `sin(x)` and `cos(x)` of the same `x`
/// become one `x.sin_cos()`, a lone one `x.sin()` or `x.cos()`.
///
/// `var` must give an expression that binds tighter than any operator
/// (an identifier, `q[0]`, `self.p`): it is used as a method receiver.
///
/// ```
/// use dynamics_symbolic::{emit, Graph, Var};
/// let mut g = Graph::new();
/// let x = g.var(Var(0));
/// let s = g.sin(x);
/// let c = g.cos(x);
/// let e = g.mul(s, c);
/// let out = emit(&g, &[e, s], &|_| quote::quote!(x));
/// assert_eq!(
///     out.lets.to_string(),
///     "let (t1 , t2) : (f64 , f64) = x . sin_cos () ; let t3 : f64 = t1 * t2 ;"
/// );
/// assert_eq!(out.roots[0].to_string(), "t3");
/// assert_eq!(out.roots[1].to_string(), "t1");
/// ```
pub fn emit(graph: &Graph, roots: &[Id], var: &dyn Fn(Var) -> TokenStream) -> Emitted {
    emit_impl(graph, roots, var, Trig::Method, None)
}

/// [`emit()`] with the function that computes `(sin x, cos x)` given as a
/// path (called as `path(x)`, also for a lone sin or cos), e.g. a faster
/// one than `f64::sin_cos`.
///
/// ```
/// use dynamics_symbolic::{emit_with, Graph, Var};
/// let mut g = Graph::new();
/// let x = g.var(Var(0));
/// let s = g.sin(x);
/// let out = emit_with(&g, &[s], &|_| quote::quote!(x), &quote::quote!(my::sin_cos));
/// assert_eq!(out.lets.to_string(), "let t1 : f64 = my :: sin_cos (x) . 0 ;");
/// ```
pub fn emit_with(
    graph: &Graph,
    roots: &[Id],
    var: &dyn Fn(Var) -> TokenStream,
    sin_cos: &TokenStream,
) -> Emitted {
    emit_impl(graph, roots, var, Trig::Path(sin_cos), None)
}

/// Paths of the functions [`emit_fused()`] calls.
#[derive(Clone, Copy, Debug)]
pub struct Calls<'a> {
    /// `(sin x, cos x)` of one angle, called as `sin_cos(x)`.
    pub sin_cos: &'a TokenStream,
    /// `([sin x_i; n], [cos x_i; n])` of an array of angles, called as
    /// `sin_cos_n([x, y, z])`: used for the variables whose sine or cosine
    /// is needed, when there are two or more.
    pub sin_cos_n: &'a TokenStream,
    /// `a * b + c`, called as `mul_add(a, b, c)`.
    pub mul_add: &'a TokenStream,
}

/// [`emit_with()`] that also writes every term `k * x` of a sum after the
/// first as one fused multiply-add `mul_add(x, k, rest)` (`x * k + rest`):
/// one rounding and one instruction where the target has FMA, which rustc
/// never contracts by itself (C compilers do by default); and that computes
/// the sines and cosines of all variables in one `sin_cos_n` call, which
/// can share vector instructions.
///
/// ```
/// use dynamics_symbolic::{emit_fused, Calls, Graph, Var};
/// use quote::quote;
/// let mut g = Graph::new();
/// let (x, y) = (g.var(Var(0)), g.var(Var(1)));
/// let k = g.constant(2.0);
/// let kx = g.mul(k, x);
/// let one = g.constant(1.0);
/// let e = g.sum(&[kx, y, one]);
/// let names = |v: Var| if v.0 == 0 { quote!(x) } else { quote!(y) };
/// let calls = Calls { sin_cos: &quote!(sc), sin_cos_n: &quote!(scn), mul_add: &quote!(fma) };
/// let out = emit_fused(&g, &[e], &names, &calls);
/// assert_eq!(out.lets.to_string(), "let t5 : f64 = fma (x , 2f64 , 1f64) + y ;");
///
/// let (sx, cy) = (g.sin(x), g.cos(y));
/// let p = g.mul(sx, cy);
/// let out = emit_fused(&g, &[p], &names, &calls);
/// assert_eq!(
///     out.lets.to_string(),
///     "let ([t6 , _] , [_ , t7]) : ([f64 ; 2usize] , [f64 ; 2usize]) = scn ([x , y]) ; \
///      let t8 : f64 = t6 * t7 ;"
/// );
/// ```
pub fn emit_fused(
    graph: &Graph,
    roots: &[Id],
    var: &dyn Fn(Var) -> TokenStream,
    calls: &Calls,
) -> Emitted {
    emit_impl(
        graph,
        roots,
        var,
        Trig::Path(calls.sin_cos),
        Some((calls.mul_add, calls.sin_cos_n)),
    )
}

/// One binding: depth, pattern, type, expression.
struct Item {
    level: usize,
    pat: TokenStream,
    ty: TokenStream,
    expr: TokenStream,
}

/// Estimated cycle at which each node's value is ready (latencies of a
/// current x86-64 core: add and multiply 3, divide 13, sin/cos 40, other
/// calls 20), each sum and product evaluated left to right as emitted.
fn ready_times(graph: &Graph, reach: &[Id]) -> Vec<u32> {
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
fn by_ready<T: Copy>(operands: impl Iterator<Item = (Id, T)>, ready: &[u32]) -> Vec<(Id, T)> {
    let mut v: Vec<(Id, T)> = operands.collect();
    v.sort_by_key(|(id, _)| ready[id.index()]);
    v
}

fn emit_impl(
    graph: &Graph,
    roots: &[Id],
    var: &dyn Fn(Var) -> TokenStream,
    trig_fn: Trig<'_>,
    fast: Option<(&TokenStream, &TokenStream)>,
) -> Emitted {
    let mul_add = fast.map(|f| f.0);
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
    // `x^e` for e > 0, and whether it is one operand (needs no parentheses).
    let power = |f: Id, e: i32| -> (TokenStream, bool) {
        let x = operand(f);
        match e {
            1 => (x, true),
            2 => (quote!(#x * #x), false),
            3 => (quote!(#x * #x * #x), false),
            _ => (quote!(#x.powi(#e)), true),
        }
    };
    let f64_ty = quote!(f64);
    // Depth of each node: nodes of one depth do not depend on each other.
    let mut level = vec![0usize; graph.len()];
    for &id in &reach {
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
    for &id in &reach {
        level[id.index()] = last;
    }
    for &id in reach.iter().rev() {
        let l = level[id.index()];
        graph.node(id).for_each_child(|c| {
            level[c.index()] = level[c.index()].min(l.saturating_sub(1));
        });
    }
    let ready = ready_times(graph, &reach);
    let mut items: Vec<Item> = Vec::new();
    // Sines and cosines of variables, or of sums of variables and constants
    // (a joint offset: `q + 1.57`), all in one `sin_cos_n` call, first; such
    // a sum is written into the call, and bound on its own only if
    // something else uses it.
    let is_leaf = |a: Id| matches!(graph.node(a), Node::Var(_) | Node::Const(_));
    let simple = |a: Id| match graph.node(a) {
        Node::Var(_) => true,
        Node::Sum { terms, .. } => terms.iter().all(|(t, _)| is_leaf(*t)),
        _ => false,
    };
    let mut batched: Vec<Id> = match fast {
        Some(_) => trig.keys().copied().filter(|a| simple(*a)).collect(),
        None => Vec::new(),
    };
    batched.sort_unstable();
    if batched.len() < 2 {
        batched.clear();
    }
    let mut used_apart: Vec<bool> = vec![false; graph.len()];
    for r in roots {
        used_apart[r.index()] = true;
    }
    for &id in &reach {
        let node = graph.node(id);
        if !matches!(node, Node::Sin(a) | Node::Cos(a) if batched.binary_search(a).is_ok()) {
            node.for_each_child(|c| used_apart[c.index()] = true);
        }
    }
    if let (Some((_, p)), false) = (fast, batched.is_empty()) {
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
                plain_sum(constant.get(), &terms, &operand)
            }
            _ => operand(a),
        });
        let n = batched.len();
        items.push(Item {
            level: 0,
            pat: quote!(([#(#sins),*], [#(#coss),*])),
            ty: quote!(([f64; #n], [f64; #n])),
            expr: quote!(#p([#(#args),*])),
        });
    }
    for &id in &reach {
        let name = ident(id);
        if batched.binary_search(&id).is_ok() && !used_apart[id.index()] {
            continue;
        }
        let expr = match graph.node(id) {
            Node::Const(_) | Node::Var(_) => continue,
            Node::Sum { constant, terms } => {
                let terms = by_ready(terms.iter().map(|(t, c)| (*t, c.get())), &ready);
                match mul_add {
                    Some(f) => fused_sum(constant.get(), &terms, &operand, f),
                    None => plain_sum(constant.get(), &terms, &operand),
                }
            }
            Node::Product { coef, factors } => {
                let c = coef.get();
                let mut num: Vec<TokenStream> = Vec::new();
                // i32::MIN has no positive counterpart: it stays a powi.
                let in_den = |e: i32| e < 0 && e != i32::MIN;
                if c.abs() != 1.0 || factors.iter().all(|f| in_den(f.1)) {
                    num.push(float(c.abs()));
                }
                num.extend(
                    by_ready(factors.iter().copied(), &ready)
                        .into_iter()
                        .filter(|f| !in_den(f.1))
                        .map(|(f, e)| power(f, e).0),
                );
                let den: Vec<(TokenStream, bool)> = factors
                    .iter()
                    .filter(|f| in_den(f.1))
                    .map(|&(f, e)| power(f, -e))
                    .collect();
                let numer = join_mul(num);
                // `-a * b` is `-(a * b)` exactly (rounding is symmetric).
                let signed = if c < 0.0 { quote!(-#numer) } else { numer };
                match &den[..] {
                    [] => signed,
                    [(d, true)] => quote!(#signed / #d),
                    _ => {
                        let d = join_mul(den.into_iter().map(|d| d.0).collect());
                        quote!(#signed / (#d))
                    }
                }
            }
            Node::Sin(a) | Node::Cos(a) if batched.binary_search(a).is_ok() => continue,
            node @ (Node::Sin(a) | Node::Cos(a)) => {
                let is_sin = matches!(node, Node::Sin(_));
                let x = operand(*a);
                match trig[a] {
                    (Some(s), Some(c)) => {
                        if id == s.min(c) {
                            let pair_level = level[s.index()].min(level[c.index()]);
                            let (si, ci) = (ident(s), ident(c));
                            let expr = match trig_fn {
                                Trig::Method => quote!(#x.sin_cos()),
                                Trig::Path(p) => quote!(#p(#x)),
                            };
                            items.push(Item {
                                level: pair_level,
                                pat: quote!((#si, #ci)),
                                ty: quote!((f64, f64)),
                                expr,
                            });
                        }
                        continue;
                    }
                    _ => match (trig_fn, is_sin) {
                        (Trig::Method, true) => quote!(#x.sin()),
                        (Trig::Method, false) => quote!(#x.cos()),
                        (Trig::Path(p), true) => quote!(#p(#x).0),
                        (Trig::Path(p), false) => quote!(#p(#x).1),
                    },
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
        items.push(Item {
            level: level[id.index()],
            pat: quote!(#name),
            ty: f64_ty.clone(),
            expr,
        });
    }
    // One `let` per depth (in chunks of at most MAX_TUPLE), binding a tuple.
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
    Emitted {
        lets,
        roots: roots.iter().map(|r| operand(*r)).collect(),
    }
}

/// `k + a - 2.5 * b`: the leading constant, then the terms in order.
fn plain_sum(k: f64, terms: &[(Id, f64)], operand: &dyn Fn(Id) -> TokenStream) -> TokenStream {
    let mut out = TokenStream::new();
    let mut first = true;
    if k != 0.0 {
        // Leading: a bare `-1.5f64` needs no parentheses.
        out.extend(if k < 0.0 && k.is_finite() {
            let lit = Literal::f64_suffixed(-k);
            quote!(-#lit)
        } else {
            float(k)
        });
        first = false;
    }
    for &(t, c) in terms {
        let x = operand(t);
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

/// [`plain_sum`] with each scaled term after the first folded into a
/// multiply-add: `f(b, -2.5f64, k + a)` for `k + a - 2.5 * b`.
fn fused_sum(
    k: f64,
    terms: &[(Id, f64)],
    operand: &dyn Fn(Id) -> TokenStream,
    f: &TokenStream,
) -> TokenStream {
    let (mut acc, rest) = match (k != 0.0, terms) {
        (false, []) => return float(0.0),
        (true, _) => (plain_sum(k, &[], operand), terms),
        (false, [first, rest @ ..]) => (plain_sum(0.0, &[*first], operand), rest),
    };
    for &(t, c) in rest {
        let x = operand(t);
        acc = if c == 1.0 {
            quote!(#acc + #x)
        } else if c == -1.0 {
            quote!(#acc - #x)
        } else {
            // An argument needs no parentheses around `-3f64`.
            let c = if c < 0.0 && c.is_finite() {
                let lit = Literal::f64_suffixed(-c);
                quote!(-#lit)
            } else {
                float(c)
            };
            quote!(#f(#x, #c, #acc))
        };
    }
    acc
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

#[cfg(test)]
mod tests {
    use super::*;

    fn names(v: Var) -> TokenStream {
        let n = Ident::new(["x", "y", "z"][v.0 as usize], Span::call_site());
        quote!(#n)
    }

    #[test]
    fn golden_small_emission() {
        let mut g = Graph::new();
        let (x, y) = (g.var(Var(0)), g.var(Var(1)));
        let (s, c) = (g.sin(x), g.cos(x));
        let k = g.constant(-0.5);
        let ks = g.mul(k, s);
        let c2 = g.powi(c, 2);
        let y3 = g.powi(y, -3);
        let p = g.product(&[ks, c2, y3]);
        let one = g.constant(1.0);
        let e = g.sum(&[p, y, one]);
        let t = g.tanh(y);
        let out = emit(&g, &[e, t, x, k], &names);
        assert_eq!(
            out.lets.to_string(),
            // Each value as late as its first use allows: tanh(y) beside
            // the last sum.
            "let (t2 , t3) : (f64 , f64) = x . sin_cos () ; \
             let t10 : f64 = t2 * t3 * t3 / (y * y * y) ; \
             let (t11 , t12) : (f64 , f64) = (1f64 + y - 0.5f64 * t10 , y . tanh ()) ;"
        );
        let roots: Vec<String> = out.roots.iter().map(|r| r.to_string()).collect();
        assert_eq!(roots, ["t11", "t12", "x", "(- 0.5f64)"]);
    }

    #[test]
    fn lone_trig_powers_and_signs() {
        // The cosine (slowest to compute) is added last.
        let mut g = Graph::new();
        let (x, y) = (g.var(Var(0)), g.var(Var(1)));
        let c = g.cos(x);
        let inv = g.powi(y, -1);
        let m = g.neg(inv);
        let x5 = g.powi(x, 5);
        let two = g.constant(2.0);
        let twox = g.mul(two, x);
        let sq = g.sqrt(twox);
        let ab = g.abs(y);
        let k = g.constant(-1.5);
        let sum = g.sum(&[k, c, m]);
        let out = emit(&g, &[sum, x5, sq, ab], &names);
        assert_eq!(
            out.lets.to_string(),
            "let (t2 , t3 , t8) : (f64 , f64 , f64) = (x . cos () , 1f64 / y , 2f64 * x) ; \
             let (t6 , t9 , t10 , t12) : (f64 , f64 , f64 , f64) = \
             (x . powi (5i32) , t8 . sqrt () , y . abs () , - 1.5f64 - t3 + t2) ;"
        );
    }

    #[test]
    fn negative_coefficients_and_quotients() {
        let mut g = Graph::new();
        let (x, y) = (g.var(Var(0)), g.var(Var(1)));
        let inv = g.powi(y, -1);
        let m = g.neg(inv);
        let k = g.constant(-3.0);
        let p = g.product(&[k, x, inv]);
        let out = emit(&g, &[m, p], &names);
        assert_eq!(
            out.lets.to_string(),
            "let (t4 , t6) : (f64 , f64) = (- 1f64 / y , - 3f64 * x / y) ;"
        );
    }

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
    fn fused_sums_fold_scaled_terms_after_the_first() {
        let mut g = Graph::new();
        let (x, y, z) = (g.var(Var(0)), g.var(Var(1)), g.var(Var(2)));
        let (k2, k3) = (g.constant(2.0), g.constant(-3.0));
        let (a, b) = (g.mul(k2, x), g.mul(k3, y));
        let mz = g.neg(z);
        // No constant: the first term is a plain product.
        let e = g.sum(&[a, b, mz]);
        let calls = Calls {
            sin_cos: &quote!(sc),
            sin_cos_n: &quote!(scn),
            mul_add: &quote!(f),
        };
        let out = emit_fused(&g, &[e], &names, &calls);
        assert_eq!(
            out.lets.to_string(),
            "let t9 : f64 = f (y , - 3f64 , 2f64 * x) - z ;"
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

    #[test]
    fn floats() {
        assert_eq!(float(2.0).to_string(), "2f64");
        assert_eq!(float(-0.25).to_string(), "(- 0.25f64)");
        assert_eq!(float(f64::NAN).to_string(), "f64 :: NAN");
        assert_eq!(float(f64::NEG_INFINITY).to_string(), "(- f64 :: INFINITY)");
    }

    #[test]
    fn leaves_only_emit_nothing() {
        let mut g = Graph::new();
        let x = g.var(Var(2));
        let out = emit(&g, &[x], &names);
        assert!(out.lets.is_empty());
        assert_eq!(out.roots[0].to_string(), "z");
    }
}
