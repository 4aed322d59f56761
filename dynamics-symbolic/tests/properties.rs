//! Property tests on random expression trees over three variables:
//! simplification keeps values (against a plain recursive evaluator of the
//! tree), and derivatives agree with central finite differences.

use dynamics_symbolic::{Graph, Id, Var};
use proptest::prelude::*;

/// A plain expression tree, evaluated without the graph.
#[derive(Debug, Clone)]
enum Tree {
    Num(f64),
    Var(u32),
    Add(Box<Tree>, Box<Tree>),
    Sub(Box<Tree>, Box<Tree>),
    Mul(Box<Tree>, Box<Tree>),
    /// a / (2 + b^2): denominators kept away from zero.
    Div(Box<Tree>, Box<Tree>),
    Neg(Box<Tree>),
    Sin(Box<Tree>),
    Cos(Box<Tree>),
    Tanh(Box<Tree>),
    Pow(Box<Tree>, i32),
    /// sqrt(1 + a^2)
    Sqrt(Box<Tree>),
}

fn tree() -> impl Strategy<Value = Tree> {
    let leaf = prop_oneof![
        (-3.0f64..3.0).prop_map(Tree::Num),
        prop_oneof![Just(0.0), Just(1.0), Just(-1.0)].prop_map(Tree::Num),
        (0u32..3).prop_map(Tree::Var),
    ];
    leaf.prop_recursive(5, 48, 2, |inner| {
        let b = |t: Tree| Box::new(t);
        prop_oneof![
            (inner.clone(), inner.clone()).prop_map(move |(x, y)| Tree::Add(b(x), b(y))),
            (inner.clone(), inner.clone()).prop_map(move |(x, y)| Tree::Sub(b(x), b(y))),
            (inner.clone(), inner.clone()).prop_map(move |(x, y)| Tree::Mul(b(x), b(y))),
            (inner.clone(), inner.clone()).prop_map(move |(x, y)| Tree::Div(b(x), b(y))),
            inner.clone().prop_map(move |x| Tree::Neg(b(x))),
            inner.clone().prop_map(move |x| Tree::Sin(b(x))),
            inner.clone().prop_map(move |x| Tree::Cos(b(x))),
            inner.clone().prop_map(move |x| Tree::Tanh(b(x))),
            (inner.clone(), 0i32..4).prop_map(move |(x, n)| Tree::Pow(b(x), n)),
            inner.prop_map(move |x| Tree::Sqrt(b(x))),
        ]
    })
}

fn eval(t: &Tree, x: &[f64; 3]) -> f64 {
    match t {
        Tree::Num(v) => *v,
        Tree::Var(i) => x[*i as usize],
        Tree::Add(a, b) => eval(a, x) + eval(b, x),
        Tree::Sub(a, b) => eval(a, x) - eval(b, x),
        Tree::Mul(a, b) => eval(a, x) * eval(b, x),
        Tree::Div(a, b) => eval(a, x) / (2.0 + eval(b, x).powi(2)),
        Tree::Neg(a) => -eval(a, x),
        Tree::Sin(a) => eval(a, x).sin(),
        Tree::Cos(a) => eval(a, x).cos(),
        Tree::Tanh(a) => eval(a, x).tanh(),
        Tree::Pow(a, n) => eval(a, x).powi(*n),
        Tree::Sqrt(a) => (1.0 + eval(a, x).powi(2)).sqrt(),
    }
}

fn build(t: &Tree, g: &mut Graph) -> Id {
    match t {
        Tree::Num(v) => g.constant(*v),
        Tree::Var(i) => g.var(Var(*i)),
        Tree::Add(a, b) => {
            let (a, b) = (build(a, g), build(b, g));
            g.add(a, b)
        }
        Tree::Sub(a, b) => {
            let (a, b) = (build(a, g), build(b, g));
            g.sub(a, b)
        }
        Tree::Mul(a, b) => {
            let (a, b) = (build(a, g), build(b, g));
            g.mul(a, b)
        }
        Tree::Div(a, b) => {
            let (a, b) = (build(a, g), build(b, g));
            let two = g.constant(2.0);
            let b2 = g.powi(b, 2);
            let d = g.add(two, b2);
            g.div(a, d)
        }
        Tree::Neg(a) => {
            let a = build(a, g);
            g.neg(a)
        }
        Tree::Sin(a) => {
            let a = build(a, g);
            g.sin(a)
        }
        Tree::Cos(a) => {
            let a = build(a, g);
            g.cos(a)
        }
        Tree::Tanh(a) => {
            let a = build(a, g);
            g.tanh(a)
        }
        Tree::Pow(a, n) => {
            let a = build(a, g);
            g.powi(a, *n)
        }
        Tree::Sqrt(a) => {
            let a = build(a, g);
            let one = g.constant(1.0);
            let a2 = g.powi(a, 2);
            let s = g.add(one, a2);
            g.sqrt(s)
        }
    }
}

fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * (1.0 + a.abs().max(b.abs()))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn simplification_keeps_values(t in tree(), x in prop::array::uniform3(-2.0f64..2.0)) {
        let mut g = Graph::new();
        let id = build(&t, &mut g);
        let ours = g.eval(&[id], &|v| x[v.0 as usize])[0];
        let truth = eval(&t, &x);
        prop_assert!(close(ours, truth, 1e-12), "{ours} vs {truth} for {t:?}");
    }

    #[test]
    fn derivatives_match_finite_differences(t in tree(), x in prop::array::uniform3(-2.0f64..2.0), k in 0u32..3) {
        let mut g = Graph::new();
        let id = build(&t, &mut g);
        let d = g.diff(id, Var(k));
        let ours = g.eval(&[d], &|v| x[v.0 as usize])[0];
        let h = 1e-6;
        let (mut xp, mut xm) = (x, x);
        xp[k as usize] += h;
        xm[k as usize] -= h;
        let fd = (eval(&t, &xp) - eval(&t, &xm)) / (2.0 * h);
        // Central differences carry O(h^2 f''') + O(eps f / h) error.
        let scale = 1.0 + eval(&t, &x).abs();
        prop_assert!((ours - fd).abs() <= 1e-5 * scale * (1.0 + fd.abs()), "d/dx{k}: {ours} vs {fd} for {t:?}");
    }

    #[test]
    fn emitted_code_parses(t in tree()) {
        let mut g = Graph::new();
        let id = build(&t, &mut g);
        let out = dynamics_symbolic::emit(&g, &[id], &|v| {
            let n = proc_macro2::Ident::new(&format!("x{}", v.0), proc_macro2::Span::call_site());
            quote::quote!(#n)
        });
        let src = format!("fn f(x0: f64, x1: f64, x2: f64) -> f64 {{ {} {} }}", out.lets, out.roots[0]);
        prop_assert!(syn::parse_str::<syn::File>(&src).is_ok(), "{src}");
    }
}
