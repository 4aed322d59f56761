//! The scalar chain's tokens over lanes: every `f64` literal `2.5f64`
//! becomes `L::splat(2.5f64)`, the type `f64` (also in `f64::NAN`, a
//! constant of `Lanes`) becomes the lane type `L` (see `lanes.rs`).

use proc_macro2::{Group, Ident, TokenStream, TokenTree};
use quote::quote;

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
