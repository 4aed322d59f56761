//! Joint limits as constants, and the `include_str!` that makes Cargo
//! rebuild when the URDF file changes (as pest does for its grammars).

use proc_macro2::TokenStream;
use quote::quote;

use crate::model::Model;

/// `impl Robot { pub const LOWER/UPPER/EFFORT/VELOCITY }` and the include.
pub fn emit(model: &Model) -> TokenStream {
    let name = &model.name;
    let coords = model.coords();
    let n = coords.len();
    let pick = |f: fn(&crate::urdf::Limits) -> f64, default: f64| -> Vec<TokenStream> {
        coords
            .iter()
            .map(|&j| {
                let v = model
                    .limits
                    .get(&model.joints[j].name.to_string())
                    .map(f)
                    .unwrap_or(default);
                dynamics_symbolic::float(v)
            })
            .collect()
    };
    let lower = pick(|l| l.lower, f64::NEG_INFINITY);
    let upper = pick(|l| l.upper, f64::INFINITY);
    let effort = pick(|l| l.effort, f64::INFINITY);
    let velocity = pick(|l| l.velocity, f64::INFINITY);
    let include = model.urdf.as_ref().map(|p| {
        let p = p.display().to_string();
        quote!(
            const _: &str = ::core::include_str!(#p);
        )
    });
    // The file's numbers as written: 6.28318530718 is a limit, not a
    // misspelt TAU.
    quote! {
        #[allow(clippy::approx_constant, clippy::excessive_precision)]
        impl #name {
            /// Lower position limits (URDF `<limit lower>`; -inf where none).
            pub const LOWER: [f64; #n] = [#(#lower),*];
            /// Upper position limits (URDF `<limit upper>`; +inf where none).
            pub const UPPER: [f64; #n] = [#(#upper),*];
            /// Effort limits (URDF `<limit effort>`; +inf where none).
            pub const EFFORT: [f64; #n] = [#(#effort),*];
            /// Velocity limits (URDF `<limit velocity>`; +inf where none).
            pub const VELOCITY: [f64; #n] = [#(#velocity),*];
        }
        #include
    }
}
