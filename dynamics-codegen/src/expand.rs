//! The pipeline, in one visible place:
//! parse -> model (validated kinematic tree) -> derive (expression DAG of the
//! dynamics) -> emit (tokens).

use std::panic::{catch_unwind, AssertUnwindSafe};

use proc_macro2::TokenStream;
use quote::quote;

use crate::ctxt::Ctxt;
use crate::parse::ast::Item;
use crate::{derive, dump, emit, model, parse, Options};

/// Expands `robot! { ... }`. Never panics: an internal failure becomes a
/// compile error.
pub fn robot(input: TokenStream, options: &Options) -> TokenStream {
    match catch_unwind(AssertUnwindSafe(|| expand(input, options))) {
        Ok(tokens) => tokens,
        Err(_) => quote! {
            ::core::compile_error!("internal error in `robot!` (a bug: please report it with this input)");
        },
    }
}

/// Parses and builds the model only. Never panics.
pub fn check(input: TokenStream, options: &Options) -> Result<(), TokenStream> {
    let run = || {
        let mut cx = Ctxt::default();
        let ast = parse::parse(input, &mut cx);
        let complete = cx.is_ok();
        let model = model::build(ast, complete, &options.base_dir, &mut cx);
        match (cx.check(), model) {
            (Ok(()), Some(_)) => Ok(()),
            (Err(err), _) => Err(err.to_compile_error()),
            (Ok(()), None) => Err(quote! {
                ::core::compile_error!("internal error in `robot!`: the model was rejected without a message");
            }),
        }
    };
    catch_unwind(AssertUnwindSafe(run)).unwrap_or_else(|_| {
        Err(quote! {
            ::core::compile_error!("internal error in `robot!` (a bug: please report it with this input)");
        })
    })
}

pub(crate) fn expand(input: TokenStream, options: &Options) -> TokenStream {
    let mut cx = Ctxt::default();
    let ast = parse::parse(input, &mut cx);
    let complete = cx.is_ok();
    let header = ast.items.iter().find_map(|i| match i {
        Item::Header(h) => Some((h.vis.clone(), h.name.clone())),
        _ => None,
    });
    let model = model::build(ast, complete, &options.base_dir, &mut cx);
    match (cx.check(), model) {
        (Ok(()), Some(model)) => {
            let derived = derive::derive(&model);
            if let Some(dir) = &options.ir_dir {
                dump::write(dir, &model, &derived);
            }
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

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    /// Fragments of the grammar, right and wrong, glued at random.
    const FRAGMENTS: &[&str] = &[
        "pub robot R;",
        "robot",
        "gravity = [0.0, -9.81, 0.0];",
        "gravity = [1.0];",
        "const L = 0.5;",
        "const L = q;",
        "param m = 2.0;",
        "param m = m;",
        "link base;",
        "link a { mass = 1.0; com = [L, 0.0, 0.0]; inertia = [1e-3, 0.1, 0.1]; }",
        "link b { mass = m; point tip = [0.1, 0.0, 0.0]; }",
        "link a;",
        "link c { mass = -1.0; }",
        "joint j1 = revolute(base -> a) { transfer = [rot_z(q)]; }",
        "joint j2 = prismatic(a -> b) { transfer = [tu(q)]; spring = 10.0; rest = 0.1; }",
        "joint j3 = revolute(b -> c) { origin = [0.0, 0.0, 1.0]; axis = [0.0, 0.0, 0.0]; }",
        "joint j4 = fixed(b -> c) { transfer = [matrix([[1.0, 0.0], [0.0, 1.0]])]; }",
        "joint j5 = revolute(c -> a) { transfer = [rot_x(q / 0.0)]; damping = 1.0 / 0.0; }",
        "joint j6 = weird(a -> b);",
        "{",
        "}",
        ";",
        "= [",
        "->",
        "q",
        "1e400",
        "sin(",
        ")",
        "link d { inertia = [1.0, 1.0, 1.0, 5.0, 0.0, 0.0]; mass = 1.0; }",
        "joint j7 = revolute(base -> d) { transfer = [rot(q), tu(sqrt(-1.0))]; coulomb = 0.5; }",
    ];

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]

        /// The pipeline never panics, whatever it is given: it expands or
        /// returns compile errors.
        #[test]
        fn never_panics(picks in prop::collection::vec(0..FRAGMENTS.len(), 0..14)) {
            let text: String = picks.iter().map(|&i| FRAGMENTS[i]).collect::<Vec<_>>().join(" ");
            if let Ok(tokens) = text.parse::<proc_macro2::TokenStream>() {
                let out = super::expand(tokens, &crate::Options::default());
                prop_assert!(!out.is_empty());
            }
        }
    }
}
