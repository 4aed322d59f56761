//! The `<Robot>Params` struct: one `f64` field per `param` item, its
//! `Default` from the declared defaults, and `Parameters` by name.

use proc_macro2::{Literal, TokenStream};
use quote::{format_ident, quote};

use crate::model::Model;

/// The parameter struct and its impls.
pub fn emit(model: &Model) -> TokenStream {
    let vis = &model.vis;
    let name = format_ident!("{}Params", model.name);
    let fields = model.params.iter().map(|p| {
        let attrs = &p.attrs;
        let field = &p.name;
        let doc = if attrs.iter().any(|a| a.path().is_ident("doc")) {
            quote!()
        } else {
            let text = format!(" Run-time parameter `{}` (default {}).", p.name, p.default);
            quote!(#[doc = #text])
        };
        quote! { #(#attrs)* #doc pub #field: f64, }
    });
    let defaults = model.params.iter().map(|p| {
        let field = &p.name;
        let v = Literal::f64_suffixed(p.default);
        quote! { #field: #v, }
    });
    let names = model.params.iter().map(|p| p.name.to_string());
    let get = model.params.iter().enumerate().map(|(i, p)| {
        let field = &p.name;
        quote! { #i => ::core::option::Option::Some(self.#field), }
    });
    let set = model.params.iter().enumerate().map(|(i, p)| {
        let field = &p.name;
        quote! { #i => { self.#field = value; true } }
    });
    let doc = format!(
        " Run-time parameters of [`{}`], with the defaults declared in `robot!`.",
        model.name
    );
    quote! {
        #[doc = #doc]
        #[derive(Debug, Clone, Copy, PartialEq)]
        #vis struct #name { #(#fields)* }

        impl ::core::default::Default for #name {
            fn default() -> Self { Self { #(#defaults)* } }
        }

        impl ::dynamics_runtime::Parameters for #name {
            const NAMES: &'static [&'static str] = &[#(#names),*];
            #[allow(unused_variables)]
            fn value(&self, index: usize) -> ::core::option::Option<f64> {
                match index { #(#get)* _ => ::core::option::Option::None }
            }
            #[allow(unused_variables)]
            fn set_value(&mut self, index: usize, value: f64) -> bool {
                match index { #(#set)* _ => false }
            }
        }
    }
}
