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
//!
//! Here: the entry points and what they share; the one emission pass in
//! `staged.rs`, its parts in `schedule.rs` (levels, tuple bindings),
//! `arith.rs` (sums, products), `trig.rs` (sines and cosines) and
//! `contract.rs` (products folded into fused multiply-adds).

mod arith;
mod contract;
mod schedule;
mod staged;
mod trig;

use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::quote;

use crate::graph::Graph;
use crate::node::{Id, Var};
use schedule::{by_ready, Item};
use staged::emit_staged;

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
    /// A module with `sqrt(x)`, `tanh(x)` and `powi(x, n)`, called as
    /// `math::sqrt(x)` (`core` has no `f64::sqrt`: code for `no_std`
    /// cannot call the methods).
    pub math: &'a TokenStream,
}

/// [`emit_with()`] that also writes every term `k * x` of a sum after the
/// first as one fused multiply-add `mul_add(x, k, rest)` (`x * k + rest`):
/// one rounding and one instruction where the target has FMA, which rustc
/// never contracts by itself (C compilers do by default); that computes
/// the sines and cosines of all variables in one `sin_cos_n` call, which
/// can share vector instructions; and that calls `sqrt`, `tanh` and `powi`
/// as functions of the module `math` (no method of `f64` but `abs`, which
/// `core` has).
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
/// let calls = Calls { sin_cos: &quote!(sc), sin_cos_n: &quote!(scn), mul_add: &quote!(fma), math: &quote!(m) };
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
    emit_impl(graph, roots, var, Trig::Path(calls.sin_cos), Some(calls))
}

/// [`emit_fused()`] of several stages of roots, for one function body that
/// runs code of its own between them (e.g. a solve whose result the next
/// stage reads as variables): each stage binds only the values no earlier
/// stage bound, and reads those by name.
///
/// ```
/// use dynamics_symbolic::{emit_fused_stages, Calls, Graph, Var};
/// use quote::quote;
/// let mut g = Graph::new();
/// let (x, y) = (g.var(Var(0)), g.var(Var(1)));
/// let s = g.sin(x);
/// let sy = g.mul(s, y);
/// let names = |v: Var| if v.0 == 0 { quote!(x) } else { quote!(y) };
/// let calls = Calls { sin_cos: &quote!(sc), sin_cos_n: &quote!(scn), mul_add: &quote!(fma), math: &quote!(m) };
/// let stages = emit_fused_stages(&g, &[&[s], &[sy]], &names, &calls);
/// assert_eq!(stages[0].lets.to_string(), "let t2 : f64 = sc (x) . 0 ;");
/// assert_eq!(stages[1].lets.to_string(), "let t3 : f64 = y * t2 ;");
/// ```
pub fn emit_fused_stages(
    graph: &Graph,
    stages: &[&[Id]],
    var: &dyn Fn(Var) -> TokenStream,
    calls: &Calls,
) -> Vec<Emitted> {
    let mut bound = vec![false; graph.len()];
    stages
        .iter()
        .map(|roots| {
            let e = emit_staged(
                graph,
                roots,
                var,
                Trig::Path(calls.sin_cos),
                Some(calls),
                &bound,
            );
            for id in graph.reachable(roots) {
                // A batched trig argument written only into the call, or
                // a product written into its sum, is not bound: a later
                // stage must bind it itself.
                if !e.folded.contains(&id) {
                    bound[id.index()] = true;
                }
            }
            e.emitted
        })
        .collect()
}

fn emit_impl(
    graph: &Graph,
    roots: &[Id],
    var: &dyn Fn(Var) -> TokenStream,
    trig_fn: Trig<'_>,
    fast: Option<&Calls>,
) -> Emitted {
    emit_staged(graph, roots, var, trig_fn, fast, &[]).emitted
}

/// The test names of variables 0, 1, 2: `x`, `y`, `z`.
#[cfg(test)]
fn names(v: Var) -> TokenStream {
    let n = Ident::new(["x", "y", "z"][v.0 as usize], Span::call_site());
    quote!(#n)
}

#[cfg(test)]
mod tests;
