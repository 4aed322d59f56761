//! The bodies of `inertial_regressor` and `inertial_parameters`: each
//! link's regressor and ten inertial parameters written into the caller's
//! slice.

use proc_macro2::TokenStream;
use quote::{format_ident, quote};

use super::body::{self, Spelling};
use crate::derive::Derived;

/// The bodies of `inertial_regressor` and `inertial_parameters`: the
/// output slice destructured into one binding per link (a wrong length
/// returns the error before anything is written), one `let` chain, then
/// the non-zero entries.
pub(super) fn bodies(d: &Derived, sp: &Spelling) -> (TokenStream, TokenStream) {
    let g = &d.graph;
    let n = d.vars.n;
    let r = &d.regressor;
    let count = r.links.len();
    let names: Vec<_> = (0..count).map(|k| format_ident!("out_{}", k)).collect();
    let destructure = |quantity: &str| {
        quote! {
            let [#(#names),*] = out else {
                return ::core::result::Result::Err(::dynamics_runtime::DynamicsError::Length {
                    quantity: #quantity,
                    expected: #count,
                    found: out.len(),
                });
            };
        }
    };
    let body = |roots_of: &dyn Fn(usize) -> Vec<dynamics_symbolic::Id>,
                ty: TokenStream,
                cols: usize,
                quantity: &str| {
        let roots: Vec<_> = (0..count).flat_map(roots_of).collect();
        let (lets, vals) = body::chain(g, &roots, sp);
        let per = roots.len() / count.max(1);
        let sets = names.iter().enumerate().map(|(k, name)| {
            let range = k * per..(k + 1) * per;
            let set = body::assign_matrix(
                g,
                &roots[range.clone()],
                &vals[range],
                cols,
                quote!((*#name)),
            );
            quote! { *#name = #ty::zeros(); #set }
        });
        let head = destructure(quantity);
        quote! {
            #head
            #lets
            #(#sets)*
            ::core::result::Result::Ok(())
        }
    };
    let y = body(
        &|k| r.y[k].clone(),
        quote!(::dynamics_runtime::nalgebra::SMatrix::<f64, #n, 10>),
        10,
        "inertial_regressor",
    );
    let pi = body(
        &|k| r.pi[k].to_vec(),
        quote!(::dynamics_runtime::nalgebra::SVector::<f64, 10>),
        1,
        "inertial_parameters",
    );
    (y, pi)
}
