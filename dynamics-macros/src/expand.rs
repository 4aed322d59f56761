//! The pipeline, in one visible place:
//! parse -> model (validated kinematic tree) -> derive (expression DAG of the
//! dynamics) -> emit (tokens).

use std::panic::{catch_unwind, AssertUnwindSafe};

use proc_macro2::TokenStream;
use quote::quote;

use crate::ctxt::Ctxt;
use crate::parse::ast::Item;
use crate::{derive, dump, emit, model, parse};

/// Expands `robot! { ... }`. Never panics: an internal failure becomes a
/// compile error.
pub fn robot(input: TokenStream) -> TokenStream {
    match catch_unwind(AssertUnwindSafe(|| expand(input))) {
        Ok(tokens) => tokens,
        Err(_) => quote! {
            ::core::compile_error!("internal error in `robot!` (a bug: please report it with this input)");
        },
    }
}

fn expand(input: TokenStream) -> TokenStream {
    let mut cx = Ctxt::default();
    let ast = parse::parse(input, &mut cx);
    let complete = cx.is_ok();
    let header = ast.items.iter().find_map(|i| match i {
        Item::Header(h) => Some((h.vis.clone(), h.name.clone())),
        _ => None,
    });
    let model = model::build(ast, complete, &mut cx);
    match (cx.check(), model) {
        (Ok(()), Some(model)) => {
            let derived = derive::derive(&model);
            dump::maybe_write(&model, &derived);
            emit::emit(&model, &derived)
        }
        (Err(err), _) => {
            let mut out = err.to_compile_error();
            if let Some((vis, name)) = header {
                out.extend(emit::fallback(&vis, &name));
            }
            out
        }
        (Ok(()), None) => quote! {
            ::core::compile_error!("internal error in `robot!`: the model was rejected without a message");
        },
    }
}
