//! Stage 1, parse: tokens -> [`ast::Input`], the user's syntax as written
//! (every node keeps its `syn` tokens so later stages can point at them).
//!
//! Items are split at top-level `;` and `{...}` first, then parsed one by one,
//! so one malformed item does not hide the errors of the others.

pub mod ast;
mod item;
mod split;

use proc_macro2::TokenStream;

use crate::ctxt::Ctxt;

/// Parses the whole macro input; errors go to `cx`, items that parsed are kept.
pub fn parse(input: TokenStream, cx: &mut Ctxt) -> ast::Input {
    let mut out = ast::Input::default();
    for tokens in split::items(input) {
        match syn::parse2::<ast::Item>(tokens) {
            Ok(item) => out.items.push(item),
            Err(e) => cx.syn_error(e),
        }
    }
    out
}
