//! Syntax built from the file's values, spanned at the `urdf = "..."`
//! literal so that later errors point there.

use proc_macro2::{Literal, Span, TokenStream};
use quote::quote_spanned;
use syn::{Expr, Ident};

use crate::parse::ast::Prop;

/// A name as an identifier (characters that cannot be in one become `_`).
pub fn ident(name: &str, span: Span) -> Ident {
    let mut s: String = name
        .chars()
        .map(|c| {
            if c.is_alphanumeric() || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect();
    if s.is_empty() || s.starts_with(|c: char| c.is_ascii_digit()) {
        s.insert(0, '_');
    }
    if syn::parse_str::<Ident>(&s).is_err() {
        s.push('_');
    }
    Ident::new(&s, span)
}

/// A float literal (negative: a negated literal).
pub fn num(v: f64, span: Span) -> Expr {
    let mut lit = Literal::f64_unsuffixed(v.abs());
    lit.set_span(span);
    let tokens: TokenStream = if v < 0.0 {
        quote_spanned!(span=> -#lit)
    } else {
        quote_spanned!(span=> #lit)
    };
    syn::parse2(tokens).expect("a number is an expression")
}

/// `[x, y, z]`.
pub fn array(v: [f64; 3], span: Span) -> Expr {
    let [a, b, c] = v.map(|x| num(x, span));
    syn::parse_quote_spanned!(span=> [#a, #b, #c])
}

/// `key = value;` as a property.
pub fn value(key: &str, value: Expr, span: Span) -> Prop {
    Prop::Value {
        key: Ident::new(key, span),
        value,
    }
}
