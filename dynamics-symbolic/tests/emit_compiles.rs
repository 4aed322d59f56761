//! The emitted code compiles without a warning (`rustc -D warnings`) and
//! computes what the graph evaluates: random trees and their derivatives
//! are emitted into one program, compiled, run, and its output compared
//! with `Graph::eval`.

mod common;

use std::fmt::Write as _;
use std::path::PathBuf;
use std::process::Command;

use dynamics_symbolic::{emit, emit_fused, emit_with, Calls, Graph, Id, Var};
use proptest::strategy::{Strategy, ValueTree};
use proptest::test_runner::TestRunner;
use quote::quote;

const POINTS: [[f64; 3]; 3] = [[0.3, -1.2, 0.8], [-1.7, 0.4, 1.9], [1.1, 1.5, -0.6]];

#[test]
fn emitted_code_compiles_cleanly_and_agrees_with_eval() {
    let mut runner = TestRunner::deterministic();
    let strategy = common::tree(true);
    let mut g = Graph::new();
    let mut functions = String::new();
    let mut expected: Vec<Vec<f64>> = Vec::new();
    let var = |v: Var| {
        let i = v.0 as usize;
        quote!(x[#i])
    };
    for k in 0..60 {
        let tree = strategy.new_tree(&mut runner).expect("a tree").current();
        let id = common::build(&tree, &mut g);
        let d = g.diff(id, Var(k % 3));
        let roots: Vec<Id> = vec![id, d];
        // A third through the default, a third through a path for sin_cos,
        // a third also with fused multiply-adds.
        let out = match k % 3 {
            0 => emit(&g, &roots, &var),
            1 => emit_with(&g, &roots, &var, &quote!(f64::sin_cos)),
            _ => emit_fused(
                &g,
                &roots,
                &var,
                &Calls {
                    sin_cos: &quote!(f64::sin_cos),
                    sin_cos_n: &quote!(sin_cos_n),
                    mul_add: &quote!(f64::mul_add),
                    math: &quote!(math),
                },
            ),
        };
        let (lets, r0, r1) = (&out.lets, &out.roots[0], &out.roots[1]);
        let _ = writeln!(
            functions,
            "fn f{k}(x: [f64; 3]) -> [f64; 2] {{ let _ = x; {lets} [{r0}, {r1}] }}"
        );
        for p in POINTS {
            expected.push(g.eval(&roots, &|v| p[v.0 as usize]));
        }
    }
    // The module of `sqrt`, `tanh` and `powi`, for `emit_fused`.
    functions.push_str(
        "#[allow(dead_code)] mod math { \
         pub fn sqrt(x: f64) -> f64 { x.sqrt() } \
         pub fn tanh(x: f64) -> f64 { x.tanh() } \
         pub fn powi(x: f64, n: i32) -> f64 { x.powi(n) } }\n",
    );
    // The array form of `f64::sin_cos`, for `emit_fused`.
    functions.push_str(
        "#[allow(dead_code)] fn sin_cos_n<const N: usize>(x: [f64; N]) -> ([f64; N], [f64; N]) { \
         (x.map(f64::sin), x.map(f64::cos)) }\n",
    );
    let mut main = String::from("fn main() {\n");
    for k in 0..60 {
        for p in POINTS {
            let _ = writeln!(
                main,
                "    for v in f{k}([{:?}, {:?}, {:?}]) {{ println!(\"{{:?}}\", v); }}",
                p[0], p[1], p[2]
            );
        }
    }
    main.push_str("}\n");
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("emit_compiles");
    std::fs::create_dir_all(&dir).expect("temp dir");
    let src = dir.join("emitted.rs");
    let exe = dir.join("emitted");
    std::fs::write(&src, format!("{functions}\n{main}")).expect("write");
    let rustc = std::env::var_os("RUSTC").unwrap_or_else(|| "rustc".into());
    let built = Command::new(rustc)
        .args([
            "--edition",
            "2021",
            "-D",
            "warnings",
            "-C",
            "opt-level=0",
            "-o",
        ])
        .arg(&exe)
        .arg(&src)
        .output()
        .expect("rustc runs");
    assert!(
        built.status.success(),
        "{}\n(source in {})",
        String::from_utf8_lossy(&built.stderr),
        src.display()
    );
    let ran = Command::new(&exe).output().expect("program runs");
    assert!(ran.status.success());
    let got: Vec<f64> = String::from_utf8_lossy(&ran.stdout)
        .lines()
        .map(|l| l.parse().expect("a number"))
        .collect();
    let want: Vec<f64> = expected.into_iter().flatten().collect();
    assert_eq!(got.len(), want.len());
    for (i, (a, b)) in got.iter().zip(&want).enumerate() {
        let same = (a.is_nan() && b.is_nan()) || common::close(*a, *b, 1e-10);
        assert!(same, "value {i} (f{}): emitted {a} vs eval {b}", i / 6);
    }
}
