//! Sums and products written as Rust expressions: literals, signs,
//! powers, quotients, and (for [`emit_fused()`](crate::emit_fused)) sums
//! folded into fused multiply-adds.

use proc_macro2::{Literal, TokenStream};
use quote::quote;

use super::contract::Contracted;
use super::{by_ready, float};
use crate::node::Id;

/// `-3.0 * a * b * b / (c * d.powi(4))` for the product `c * prod f^e`,
/// factors in the order they become ready (powers 2 and 3 as repeated
/// multiplies, `x^-1` as `1.0 / x`; other powers `math::powi(d, 4i32)`
/// with a `math` module, else `d.powi(4i32)`).
pub(super) fn product(
    c: f64,
    factors: &[(Id, i32)],
    ready: &[u32],
    operand: &dyn Fn(Id) -> TokenStream,
    math: Option<&TokenStream>,
) -> TokenStream {
    // `x^e` for e > 0, and whether it is one operand (needs no parentheses).
    let power = |f: Id, e: i32| -> (TokenStream, bool) {
        let x = operand(f);
        match e {
            1 => (x, true),
            2 => (quote!(#x * #x), false),
            3 => (quote!(#x * #x * #x), false),
            _ => match math {
                Some(m) => (quote!(#m::powi(#x, #e)), true),
                None => (quote!(#x.powi(#e)), true),
            },
        }
    };
    let mut num: Vec<TokenStream> = Vec::new();
    // i32::MIN has no positive counterpart: it stays a powi.
    let in_den = |e: i32| e < 0 && e != i32::MIN;
    if c.abs() != 1.0 || factors.iter().all(|f| in_den(f.1)) {
        num.push(float(c.abs()));
    }
    num.extend(
        by_ready(factors.iter().copied(), ready)
            .into_iter()
            .filter(|f| !in_den(f.1))
            .map(|(f, e)| power(f, e).0),
    );
    let den: Vec<(TokenStream, bool)> = factors
        .iter()
        .filter(|f| in_den(f.1))
        .map(|&(f, e)| power(f, -e))
        .collect();
    let numer = join_mul(num);
    // `-a * b` is `-(a * b)` exactly (rounding is symmetric).
    let signed = if c < 0.0 { quote!(-#numer) } else { numer };
    match &den[..] {
        [] => signed,
        [(d, true)] => quote!(#signed / #d),
        _ => {
            let d = join_mul(den.into_iter().map(|d| d.0).collect());
            quote!(#signed / (#d))
        }
    }
}

/// `k + a - 2.5 * b`: the leading constant, then the terms in order.
pub(super) fn plain_sum(
    k: f64,
    terms: &[(Id, f64)],
    operand: &dyn Fn(Id) -> TokenStream,
) -> TokenStream {
    let mut out = TokenStream::new();
    let mut first = true;
    if k != 0.0 {
        // Leading: a bare `-1.5f64` needs no parentheses.
        out.extend(if k < 0.0 && k.is_finite() {
            let lit = Literal::f64_suffixed(-k);
            quote!(-#lit)
        } else {
            float(k)
        });
        first = false;
    }
    for &(t, c) in terms {
        let x = operand(t);
        let mag = c.abs();
        let term = if mag == 1.0 {
            x
        } else {
            let k = float(mag);
            quote!(#k * #x)
        };
        out.extend(match (first, c < 0.0) {
            (true, false) => term,
            (true, true) => quote!(-#term),
            (false, false) => quote!(+ #term),
            (false, true) => quote!(- #term),
        });
        first = false;
    }
    out
}

/// [`plain_sum`] with each scaled term after the first folded into a
/// multiply-add: `f(b, -2.5f64, k + a)` for `k + a - 2.5 * b`, and each
/// product `contracted` gives (its factors) too: `f(x, y, acc)` for
/// `acc + x * y`, `f(-x, y, acc)` for `acc - x * y`.
pub(super) fn fused_sum(
    k: f64,
    terms: &[(Id, f64)],
    operand: &dyn Fn(Id) -> TokenStream,
    contracted: &dyn Fn(Id) -> Option<Contracted>,
    f: &TokenStream,
) -> TokenStream {
    let (mut acc, rest) = match (k != 0.0, terms) {
        (false, []) => return float(0.0),
        (true, _) => (plain_sum(k, &[], operand), terms),
        (false, [first, rest @ ..]) => (plain_sum(0.0, &[*first], operand), rest),
    };
    for &(t, c) in rest {
        if let Some(p) = contracted(t).filter(|_| c.abs() == 1.0) {
            let (x, y) = (operand(p.a), operand(p.b));
            acc = if (c < 0.0) != p.negative {
                quote!(#f(-#x, #y, #acc))
            } else {
                quote!(#f(#x, #y, #acc))
            };
            continue;
        }
        let x = operand(t);
        acc = if c == 1.0 {
            quote!(#acc + #x)
        } else if c == -1.0 {
            quote!(#acc - #x)
        } else {
            // An argument needs no parentheses around `-3f64`.
            let c = if c < 0.0 && c.is_finite() {
                let lit = Literal::f64_suffixed(-c);
                quote!(-#lit)
            } else {
                float(c)
            };
            quote!(#f(#x, #c, #acc))
        };
    }
    acc
}

/// `a * b * c`
fn join_mul(factors: Vec<TokenStream>) -> TokenStream {
    let mut out = TokenStream::new();
    for (k, f) in factors.into_iter().enumerate() {
        if k > 0 {
            out.extend(quote!(*));
        }
        out.extend(f);
    }
    out
}

#[cfg(test)]
mod tests {
    use crate::emit::{emit, emit_fused, names, Calls};
    use crate::{Graph, Var};
    use quote::quote;

    #[test]
    fn lone_trig_powers_and_signs() {
        // The cosine (slowest to compute) is added last.
        let mut g = Graph::new();
        let (x, y) = (g.var(Var(0)), g.var(Var(1)));
        let c = g.cos(x);
        let inv = g.powi(y, -1);
        let m = g.neg(inv);
        let x5 = g.powi(x, 5);
        let two = g.constant(2.0);
        let twox = g.mul(two, x);
        let sq = g.sqrt(twox);
        let ab = g.abs(y);
        let k = g.constant(-1.5);
        let sum = g.sum(&[k, c, m]);
        let out = emit(&g, &[sum, x5, sq, ab], &names);
        assert_eq!(
            out.lets.to_string(),
            "let (t2 , t3 , t8) : (f64 , f64 , f64) = (x . cos () , 1f64 / y , 2f64 * x) ; \
             let (t6 , t9 , t10 , t12) : (f64 , f64 , f64 , f64) = \
             (x . powi (5i32) , t8 . sqrt () , y . abs () , - 1.5f64 - t3 + t2) ;"
        );
    }

    #[test]
    fn negative_coefficients_and_quotients() {
        let mut g = Graph::new();
        let (x, y) = (g.var(Var(0)), g.var(Var(1)));
        let inv = g.powi(y, -1);
        let m = g.neg(inv);
        let k = g.constant(-3.0);
        let p = g.product(&[k, x, inv]);
        let out = emit(&g, &[m, p], &names);
        assert_eq!(
            out.lets.to_string(),
            "let (t4 , t6) : (f64 , f64) = (- 1f64 / y , - 3f64 * x / y) ;"
        );
    }

    #[test]
    fn fused_sums_fold_scaled_terms_after_the_first() {
        let mut g = Graph::new();
        let (x, y, z) = (g.var(Var(0)), g.var(Var(1)), g.var(Var(2)));
        let (k2, k3) = (g.constant(2.0), g.constant(-3.0));
        let (a, b) = (g.mul(k2, x), g.mul(k3, y));
        let mz = g.neg(z);
        // No constant: the first term is a plain product.
        let e = g.sum(&[a, b, mz]);
        let calls = Calls {
            sin_cos: &quote!(sc),
            sin_cos_n: &quote!(scn),
            mul_add: &quote!(f),
            math: &quote!(m),
        };
        let out = emit_fused(&g, &[e], &names, &calls);
        assert_eq!(
            out.lets.to_string(),
            "let t9 : f64 = f (y , - 3f64 , 2f64 * x) - z ;"
        );
    }

    #[test]
    fn fused_emission_calls_the_math_module_not_methods() {
        let mut g = Graph::new();
        let (x, y) = (g.var(Var(0)), g.var(Var(1)));
        let x5 = g.powi(x, 5);
        let r = g.sqrt(y);
        let t = g.tanh(x);
        let a = g.abs(y);
        let calls = Calls {
            sin_cos: &quote!(sc),
            sin_cos_n: &quote!(scn),
            mul_add: &quote!(f),
            math: &quote!(m),
        };
        let out = emit_fused(&g, &[x5, r, t, a], &names, &calls);
        let text = out.lets.to_string();
        for call in [
            "m :: powi (x , 5i32)",
            "m :: sqrt (y)",
            "m :: tanh (x)",
            "y . abs ()",
        ] {
            assert!(text.contains(call), "{call} in {text}");
        }
        // Without the module (plain emission) they stay methods.
        let plain = emit(&g, &[x5, r, t], &names).lets.to_string();
        for call in ["x . powi (5i32)", "y . sqrt ()", "x . tanh ()"] {
            assert!(plain.contains(call), "{call} in {plain}");
        }
    }
}
