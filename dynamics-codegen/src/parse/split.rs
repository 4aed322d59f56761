//! Splitting the input into items before parsing them.

use proc_macro2::{TokenStream, TokenTree};

/// Splits at every top-level `;`, and after every top-level `{...}` group
/// (a link or joint body). The `;` stays with its item.
pub fn items(input: TokenStream) -> Vec<TokenStream> {
    let mut items = Vec::new();
    let mut current: Vec<TokenTree> = Vec::new();
    let mut iter = input.into_iter().peekable();
    while let Some(tt) = iter.next() {
        let ends = match &tt {
            TokenTree::Punct(p) => p.as_char() == ';',
            TokenTree::Group(g) => {
                g.delimiter() == proc_macro2::Delimiter::Brace
                    && !matches!(iter.peek(), Some(TokenTree::Punct(p)) if p.as_char() == ';')
            }
            _ => false,
        };
        current.push(tt);
        if ends {
            items.push(current.drain(..).collect());
        }
    }
    if !current.is_empty() {
        items.push(current.into_iter().collect());
    }
    items
}

#[cfg(test)]
mod tests {
    use quote::quote;

    #[test]
    fn splits_at_semicolons_and_bodies() {
        let parts = super::items(quote! {
            robot A; link b; link c { mass = 1.0; } joint j = revolute(b -> c) {} ;
        });
        let texts: Vec<String> = parts.iter().map(|t| t.to_string()).collect();
        assert_eq!(texts.len(), 4, "{texts:?}");
        assert!(texts[2].starts_with("link c"));
        assert!(texts[3].ends_with(";"));
    }
}
