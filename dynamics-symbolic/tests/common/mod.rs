//! Random expression trees over three variables, a plain recursive
//! evaluator of them (the reference: it never touches the graph), and a
//! builder that puts them through the simplifying graph.

#![allow(dead_code)] // each test file uses a part

use dynamics_symbolic::{Graph, Id, Var};
use proptest::prelude::*;

/// A plain expression tree.
#[derive(Debug, Clone)]
pub enum Tree {
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
    /// a^n, n in 0..=4
    Pow(Box<Tree>, i32),
    /// (1 + a^2)^n, n in -3..=-1
    PowNeg(Box<Tree>, i32),
    /// sqrt(1 + a^2)
    Sqrt(Box<Tree>),
    Abs(Box<Tree>),
    /// a sin(b)^2 + c cos(b)^2, often with c = a (then it is a).
    Pyth(Box<Tree>, Box<Tree>, Box<Tree>),
}

/// Random trees of depth <= 5, up to about 48 nodes; `abs` only when asked
/// (its kink breaks finite differences).
pub fn tree(with_abs: bool) -> impl Strategy<Value = Tree> {
    let leaf = prop_oneof![
        (-3.0f64..3.0).prop_map(Tree::Num),
        prop_oneof![Just(0.0), Just(1.0), Just(-1.0), Just(2.0)].prop_map(Tree::Num),
        (0u32..3).prop_map(Tree::Var),
    ];
    leaf.prop_recursive(5, 48, 2, move |inner| {
        let b = |t: Tree| Box::new(t);
        prop_oneof![
            2 => (inner.clone(), inner.clone()).prop_map(move |(x, y)| Tree::Add(b(x), b(y))),
            2 => (inner.clone(), inner.clone()).prop_map(move |(x, y)| Tree::Sub(b(x), b(y))),
            2 => (inner.clone(), inner.clone()).prop_map(move |(x, y)| Tree::Mul(b(x), b(y))),
            1 => (inner.clone(), inner.clone()).prop_map(move |(x, y)| Tree::Div(b(x), b(y))),
            1 => inner.clone().prop_map(move |x| Tree::Neg(b(x))),
            1 => inner.clone().prop_map(move |x| Tree::Sin(b(x))),
            1 => inner.clone().prop_map(move |x| Tree::Cos(b(x))),
            1 => inner.clone().prop_map(move |x| Tree::Tanh(b(x))),
            1 => (inner.clone(), 0i32..=4).prop_map(move |(x, n)| Tree::Pow(b(x), n)),
            1 => (inner.clone(), -3i32..=-1).prop_map(move |(x, n)| Tree::PowNeg(b(x), n)),
            1 => inner.clone().prop_map(move |x| Tree::Sqrt(b(x))),
            1 => (inner.clone(), inner.clone(), inner.clone(), any::<bool>()).prop_map(
                move |(a, x, c, same)| {
                    let c = if same { a.clone() } else { c };
                    Tree::Pyth(b(a), b(x), b(c))
                }
            ),
            1 => inner.prop_map(move |x| if with_abs { Tree::Abs(b(x)) } else { Tree::Neg(b(x)) }),
        ]
    })
}

/// The reference value of a tree.
pub fn eval(t: &Tree, x: &[f64; 3]) -> f64 {
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
        Tree::PowNeg(a, n) => (1.0 + eval(a, x).powi(2)).powi(*n),
        Tree::Sqrt(a) => (1.0 + eval(a, x).powi(2)).sqrt(),
        Tree::Abs(a) => eval(a, x).abs(),
        Tree::Pyth(a, b, c) => {
            let v = eval(b, x);
            eval(a, x) * v.sin().powi(2) + eval(c, x) * v.cos().powi(2)
        }
    }
}

/// The signs of the arguments of every `abs`, in tree order.
pub fn abs_signs(t: &Tree, x: &[f64; 3], out: &mut Vec<f64>) {
    match t {
        Tree::Num(_) | Tree::Var(_) => {}
        Tree::Add(a, b) | Tree::Sub(a, b) | Tree::Mul(a, b) | Tree::Div(a, b) => {
            abs_signs(a, x, out);
            abs_signs(b, x, out);
        }
        Tree::Abs(a) => {
            out.push(eval(a, x).signum());
            abs_signs(a, x, out);
        }
        Tree::Pyth(a, b, c) => {
            abs_signs(a, x, out);
            abs_signs(b, x, out);
            abs_signs(c, x, out);
        }
        Tree::Neg(a)
        | Tree::Sin(a)
        | Tree::Cos(a)
        | Tree::Tanh(a)
        | Tree::Pow(a, _)
        | Tree::PowNeg(a, _)
        | Tree::Sqrt(a) => abs_signs(a, x, out),
    }
}

/// The tree put through the simplifying builders.
pub fn build(t: &Tree, g: &mut Graph) -> Id {
    let one = g.constant(1.0);
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
        Tree::PowNeg(a, n) => {
            let a = build(a, g);
            let a2 = g.powi(a, 2);
            let s = g.add(one, a2);
            g.powi(s, *n)
        }
        Tree::Sqrt(a) => {
            let a = build(a, g);
            let a2 = g.powi(a, 2);
            let s = g.add(one, a2);
            g.sqrt(s)
        }
        Tree::Abs(a) => {
            let a = build(a, g);
            g.abs(a)
        }
        Tree::Pyth(a, b, c) => {
            let (a, b, c) = (build(a, g), build(b, g), build(c, g));
            let (s, co) = (g.sin(b), g.cos(b));
            let (s2, c2) = (g.powi(s, 2), g.powi(co, 2));
            let (x, y) = (g.mul(a, s2), g.mul(c, c2));
            g.add(x, y)
        }
    }
}

/// |a - b| within `rel` of the larger magnitude (and of 1 near zero).
pub fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * (1.0 + a.abs().max(b.abs()))
}
