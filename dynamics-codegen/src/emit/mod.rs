//! Stage 5, emit: the derived expressions as Rust items. The robot struct,
//! its parameter struct, and an implementation of
//! `dynamics_runtime::Robot<N>` whose every method is a straight-line
//! `let` chain (no heap, no loops, no symbolic work at run time).

mod body;
mod constraints;
mod lane_tokens;
mod lanes;
mod params;
mod regressor;
mod robot;
mod urdf;

use proc_macro2::TokenStream;
use quote::{format_ident, quote};

use crate::derive::Derived;
use crate::model::Model;

/// All items for a valid model.
pub fn emit(model: &Model, d: &Derived) -> TokenStream {
    let params = params::emit(model);
    let robot = robot::emit(model, d);
    let urdf = urdf::emit(model);
    quote! { #params #robot #urdf }
}

/// What is emitted when the input has errors, beside the errors: the bare
/// types, so that the user sees the real errors and not a cascade of
/// "cannot find type" ones (after thiserror's `fallback.rs`).
pub fn fallback(vis: &syn::Visibility, name: &syn::Ident) -> TokenStream {
    let params = format_ident!("{}Params", name);
    quote! {
        #[derive(Debug, Clone, Copy, Default, PartialEq)]
        #vis struct #params;
        #[derive(Debug, Clone, Copy, Default, PartialEq)]
        #vis struct #name;
    }
}
