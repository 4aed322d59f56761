//! The outputs over lanes: the scalar `let` chains with every `f64` a value
//! of the method's lane type `L: dynamics_runtime::lanes::Lanes` (several
//! states per value; see the runtime's `lanes` and `batch`).
//!
//! The chain is the scalar one, node for node and operation for operation
//! (the same DAG through the same emitter, with the runtime's generic
//! `lanes::{mul_add, sin_cos, sin_cos_n, sqrt, tanh, powi}` for the scalar
//! functions), so each lane computes what the scalar method does. What
//! differs is spelled here: a float literal `2.5f64` is `L::splat(2.5f64)`,
//! the type `f64` is `L` (also in `f64::NAN`, a constant of `Lanes`), and a
//! parameter is `L::splat(self.params.x)` (`body::Spelling::lanes`).

use proc_macro2::{Group, Ident, Span, TokenStream, TokenTree};
use quote::quote;

use dynamics_symbolic::{Graph, Id};

use super::body::{self, Spelling};

/// `tokens` with every `f64` literal splat into lanes and every `f64` type
/// or path made `L`.
pub fn over_lanes(tokens: TokenStream) -> TokenStream {
    let mut out = TokenStream::new();
    for tree in tokens {
        match tree {
            TokenTree::Group(g) => {
                let mut inner = Group::new(g.delimiter(), over_lanes(g.stream()));
                inner.set_span(g.span());
                out.extend([TokenTree::Group(inner)]);
            }
            TokenTree::Ident(i) if i == "f64" => {
                out.extend([TokenTree::Ident(Ident::new("L", i.span()))]);
            }
            TokenTree::Literal(l) if l.to_string().ends_with("f64") => {
                out.extend(quote!(L::splat(#l)));
            }
            other => out.extend([other]),
        }
    }
    out
}

/// The lane type's zero.
fn zero() -> TokenStream {
    quote!(L::splat(0.0f64))
}

/// Body returning `[L; n]`.
pub fn vector(g: &Graph, roots: &[Id], sp: &Spelling) -> TokenStream {
    let n = roots.len();
    let (lets, vals) = body::chain(g, roots, sp);
    let sets = assign_vector(g, roots, &vals, quote!(out));
    let z = zero();
    quote! {
        #lets
        let mut out = [#z; #n];
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

#[cfg(test)]
mod tests {
    use super::over_lanes;
    use quote::quote;

    #[test]
    fn literals_types_and_paths_become_lane_values() {
        let scalar = quote! {
            let (t1, ([t2, _], [t3, t4])): (f64, ([f64; 2usize], [f64; 2usize])) =
                (f(x, -2.5f64, 1f64), g([y, 1.5f64 + x]));
            let t5: f64 = (-f64::INFINITY) * m::powi(t1, 4i32);
        };
        assert_eq!(
            over_lanes(scalar).to_string(),
            quote! {
                let (t1, ([t2, _], [t3, t4])): (L, ([L; 2usize], [L; 2usize])) =
                    (f(x, -L::splat(2.5f64), L::splat(1f64)), g([y, L::splat(1.5f64) + x]));
                let t5: L = (-L::INFINITY) * m::powi(t1, 4i32);
            }
            .to_string()
        );
    }
}
