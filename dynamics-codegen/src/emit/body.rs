//! Method bodies: a `let` chain from the symbolic engine, then the outputs
//! written into fixed-size nalgebra values (zeros are left as they are).

use dynamics_symbolic::{Graph, Id, Var};
use proc_macro2::TokenStream;
use quote::{format_ident, quote};

use crate::derive::Vars;
use crate::model::Model;

/// How free variables are spelled in the emitted code.
pub struct Spelling<'a> {
    vars: Vars,
    model: &'a Model,
    /// Parameters as lane values `L::splat(self.params.x)` (the lane
    /// methods) rather than `self.params.x`.
    lanes: bool,
}

impl<'a> Spelling<'a> {
    /// For this model.
    pub fn new(vars: Vars, model: &'a Model) -> Self {
        Self {
            vars,
            model,
            lanes: false,
        }
    }

    /// For the lane methods of this model (see `lanes.rs`).
    pub fn lanes(vars: Vars, model: &'a Model) -> Self {
        Self {
            vars,
            model,
            lanes: true,
        }
    }

    /// The emitted chain and roots as this spelling writes them: over
    /// lanes, every `f64` of the scalar code made a lane value.
    fn finish(
        &self,
        lets: TokenStream,
        roots: Vec<TokenStream>,
    ) -> (TokenStream, Vec<TokenStream>) {
        if self.lanes {
            (
                super::lane_tokens::over_lanes(lets),
                roots
                    .into_iter()
                    .map(super::lane_tokens::over_lanes)
                    .collect(),
            )
        } else {
            (lets, roots)
        }
    }

    fn var(&self, v: Var) -> TokenStream {
        let (kind, i) = self.vars.classify(v);
        match kind {
            0 => quote!(q[#i]),
            1 => quote!(qd[#i]),
            2 => quote!(qdd[#i]),
            4 => quote!(t),
            _ => {
                let field = format_ident!("{}", self.model.params[i].name.to_string());
                if self.lanes {
                    quote!(L::splat(self.params.#field))
                } else {
                    quote!(self.params.#field)
                }
            }
        }
    }
}

/// The `let` chain for `roots` and the tokens of each root's value.
pub fn chain(g: &Graph, roots: &[Id], sp: &Spelling) -> (TokenStream, Vec<TokenStream>) {
    let e = with_calls(sp.lanes, |calls| {
        dynamics_symbolic::emit_fused(g, roots, &|v| sp.var(v), calls)
    });
    sp.finish(e.lets, e.roots)
}

/// `f` with the runtime functions the emitted code calls: the scalar ones,
/// or their generic versions over lanes (`dynamics_runtime::lanes`).
fn with_calls<T>(lanes: bool, f: impl FnOnce(&dynamics_symbolic::Calls) -> T) -> T {
    let (sin_cos, sin_cos_n, mul_add, math) = if lanes {
        (
            quote!(::dynamics_runtime::lanes::sin_cos),
            quote!(::dynamics_runtime::lanes::sin_cos_n),
            quote!(::dynamics_runtime::lanes::mul_add),
            quote!(::dynamics_runtime::lanes),
        )
    } else {
        (
            quote!(::dynamics_runtime::trig::sin_cos),
            quote!(::dynamics_runtime::trig::sin_cos_n),
            quote!(::dynamics_runtime::fma::mul_add),
            quote!(::dynamics_runtime::math),
        )
    };
    f(&dynamics_symbolic::Calls {
        sin_cos: &sin_cos,
        sin_cos_n: &sin_cos_n,
        mul_add: &mul_add,
        math: &math,
    })
}

/// The `let` chains of several stages of roots in one body, each binding
/// only what earlier stages did not (code may run between them), with the
/// tokens of each stage's roots.
pub fn stages(g: &Graph, stages: &[&[Id]], sp: &Spelling) -> Vec<(TokenStream, Vec<TokenStream>)> {
    with_calls(sp.lanes, |calls| {
        dynamics_symbolic::emit_fused_stages(g, stages, &|v| sp.var(v), calls)
    })
    .into_iter()
    .map(|e| sp.finish(e.lets, e.roots))
    .collect()
}

/// Body returning an `SVector<f64, n>`.
pub fn vector(g: &Graph, roots: &[Id], sp: &Spelling) -> TokenStream {
    let n = roots.len();
    let (lets, vals) = chain(g, roots, sp);
    let sets = assign_vector(g, roots, &vals, quote!(out));
    quote! {
        #lets
        let mut out = ::dynamics_runtime::nalgebra::SVector::<f64, #n>::zeros();
        #sets
        out
    }
}

/// `target[i] = value;` for every non-zero root.
pub fn assign_vector(
    g: &Graph,
    roots: &[Id],
    vals: &[TokenStream],
    target: TokenStream,
) -> TokenStream {
    let sets = roots
        .iter()
        .zip(vals)
        .enumerate()
        .filter(|(_, (id, _))| g.as_constant(**id) != Some(0.0))
        .map(|(i, (_, v))| quote!(#target[#i] = #v;));
    quote!(#(#sets)*)
}

/// `target[(i, j)] = value;` for every non-zero root of a row-major matrix.
pub fn assign_matrix(
    g: &Graph,
    roots: &[Id],
    vals: &[TokenStream],
    cols: usize,
    target: TokenStream,
) -> TokenStream {
    let sets = roots
        .iter()
        .zip(vals)
        .enumerate()
        .filter_map(|(k, (id, v))| {
            let (i, j) = (k / cols, k % cols);
            (g.as_constant(*id) != Some(0.0)).then(|| quote!(#target[(#i, #j)] = #v;))
        });
    quote!(#(#sets)*)
}

/// Body returning an `SMatrix<f64, rows, cols>` from row-major roots.
pub fn matrix(g: &Graph, roots: &[Id], rows: usize, cols: usize, sp: &Spelling) -> TokenStream {
    let (lets, vals) = chain(g, roots, sp);
    let sets = assign_matrix(g, roots, &vals, cols, quote!(out));
    quote! {
        #lets
        let mut out = ::dynamics_runtime::nalgebra::SMatrix::<f64, #rows, #cols>::zeros();
        #sets
        out
    }
}

/// Body returning a scalar.
pub fn scalar(g: &Graph, root: Id, sp: &Spelling) -> TokenStream {
    let (lets, vals) = chain(g, &[root], sp);
    let v = &vals[0];
    quote! { #lets #v }
}
