//! The outputs over lanes: the scalar `let` chains with every `f64` a value
//! of the method's lane type `L: dynamics_runtime::lanes::Lanes` (several
//! states per value; see the runtime's `lanes` and `batch`).
//!
//! The chain is the scalar one, node for node and operation for operation
//! (the same DAG through the same emitter, with the runtime's generic
//! `lanes::{mul_add, sin_cos, sin_cos_n, sqrt, tanh, powi}` for the scalar
//! functions), so each lane computes what the scalar method does. What
//! differs is spelled in `lane_tokens.rs`: a float literal `2.5f64` is `L::splat(2.5f64)`,
//! the type `f64` is `L` (also in `f64::NAN`, a constant of `Lanes`), and a
//! parameter is `L::splat(self.params.x)` (`body::Spelling::lanes`).

use proc_macro2::{Ident, Span, TokenStream};
use quote::quote;

use dynamics_symbolic::{Graph, Id};

use super::body::{self, Spelling};

/// The lane type's zero.
fn zero() -> TokenStream {
    quote!(L::splat(0.0f64))
}

/// Body returning `[L; n]`.
pub fn vector(g: &Graph, roots: &[Id], sp: &Spelling) -> TokenStream {
    let n = roots.len();
    let (lets, vals) = body::chain(g, roots, sp);
    let sets = body::assign_vector(g, roots, &vals, quote!(out));
    let z = zero();
    quote! {
        #lets
        let mut out = [#z; #n];
        #sets
        out
    }
}

/// `target[j][i] = value;` for every non-zero root `(i, j)` of row-major
/// roots: lane matrices are column-major as nalgebra's (`m[column][row]`),
/// so that a state's matrix is the columns' lanes in memory order.
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
            (g.as_constant(*id) != Some(0.0)).then(|| quote!(#target[#j][#i] = #v;))
        });
    quote!(#(#sets)*)
}

/// `let mut name = [[zero; n]; n];`
pub fn zero_matrix(name: &str, n: usize) -> TokenStream {
    let name = Ident::new(name, Span::call_site());
    let z = zero();
    quote!(let mut #name = [[#z; #n]; #n];)
}

/// `let mut name = [zero; n];`
pub fn zero_vector(name: &str, n: usize) -> TokenStream {
    let name = Ident::new(name, Span::call_site());
    let z = zero();
    quote!(let mut #name = [#z; #n];)
}
