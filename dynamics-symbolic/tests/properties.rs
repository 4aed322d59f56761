//! Property tests on random expression trees over three variables:
//! simplification keeps values (against a plain recursive evaluator of the
//! tree), derivatives agree with finite differences, emitted code parses.

mod common;

use common::{abs_signs, build, close, eval, tree};
use dynamics_symbolic::{Graph, Var};
use proptest::prelude::*;

/// Fourth-order central difference of the reference evaluator (error
/// ~h^4 f^(5) / 30 + 2 eps |f| / h, about 1e-12 for h = 1e-3).
fn central(t: &common::Tree, x: &[f64; 3], k: usize, h: f64) -> f64 {
    let at = |s: f64| {
        let mut y = *x;
        y[k] += s * h;
        eval(t, &y)
    };
    (-at(2.0) + 8.0 * at(1.0) - 8.0 * at(-1.0) + at(-2.0)) / (12.0 * h)
}

/// A converged finite difference: the first step h whose value agrees with
/// that of h / 2 to 1e-9, or None for a function too wild to difference
/// (an argument like 1e6 x^12 under a cos).
fn finite_difference(t: &common::Tree, x: &[f64; 3], k: usize) -> Option<(f64, f64)> {
    [1e-2, 3e-3, 1e-3, 3e-4].into_iter().find_map(|h| {
        let (a, b) = (central(t, x, k, h), central(t, x, k, h / 2.0));
        close(a, b, 1e-9).then_some((b, h))
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1024))]

    #[test]
    fn simplification_keeps_values(t in tree(true), x in prop::array::uniform3(-2.0f64..2.0)) {
        let mut g = Graph::new();
        let id = build(&t, &mut g);
        let ours = g.eval(&[id], &|v| x[v.0 as usize])[0];
        let truth = eval(&t, &x);
        prop_assert!(close(ours, truth, 1e-12), "{ours} vs {truth} for {t:?}");
    }

    #[test]
    fn derivatives_match_finite_differences(
        t in tree(true),
        x in prop::array::uniform3(-2.0f64..2.0),
        k in 0usize..3,
    ) {
        let fd = finite_difference(&t, &x, k);
        prop_assume!(fd.is_some());
        let Some((fd, h)) = fd else { unreachable!() };
        // No abs kink between the stencil points.
        let mut signs = Vec::new();
        abs_signs(&t, &x, &mut signs);
        for s in [-2.0, 2.0] {
            let mut y = x;
            y[k] += s * h;
            let mut other = Vec::new();
            abs_signs(&t, &y, &mut other);
            prop_assume!(other == signs && !signs.contains(&0.0));
        }
        let mut g = Graph::new();
        let id = build(&t, &mut g);
        let d = g.diff(id, Var(k as u32));
        let ours = g.eval(&[d], &|v| x[v.0 as usize])[0];
        prop_assert!(close(ours, fd, 1e-6), "d/dx{k}: {ours} vs {fd} for {t:?}");
    }

    #[test]
    fn second_derivatives_are_symmetric(t in tree(false), x in prop::array::uniform3(-2.0f64..2.0)) {
        let mut g = Graph::new();
        let id = build(&t, &mut g);
        let d0 = g.diff(id, Var(0));
        let d01 = g.diff(d0, Var(1));
        let d1 = g.diff(id, Var(1));
        let d10 = g.diff(d1, Var(0));
        let v = g.eval(&[d01, d10], &|v| x[v.0 as usize]);
        prop_assert!(close(v[0], v[1], 1e-10), "{} vs {} for {t:?}", v[0], v[1]);
    }

    #[test]
    fn emitted_code_parses(t in tree(true)) {
        let mut g = Graph::new();
        let id = build(&t, &mut g);
        let d = g.diff(id, Var(0));
        let out = dynamics_symbolic::emit(&g, &[id, d], &|v| {
            let n = proc_macro2::Ident::new(&format!("x{}", v.0), proc_macro2::Span::call_site());
            quote::quote!(#n)
        });
        let src = format!(
            "fn f(x0: f64, x1: f64, x2: f64) -> (f64, f64) {{ {} ({}, {}) }}",
            out.lets, out.roots[0], out.roots[1]
        );
        prop_assert!(syn::parse_str::<syn::File>(&src).is_ok(), "{src}");
    }
}
