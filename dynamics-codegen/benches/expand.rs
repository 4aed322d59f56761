//! Time of one macro expansion (parse, model, URDF, derive, emit) of the
//! robots of the `robots` crate, with every output (the macro always emits
//! them all). The inputs are read from the `robot!` invocations in
//! `robots/src/`, so the bench follows the real descriptions.
//! Run: `cargo bench -p dynamics-codegen --bench expand`.

use std::hint::black_box;
use std::path::{Path, PathBuf};

use criterion::{criterion_group, criterion_main, Criterion};
use dynamics_codegen::{expand, Options};
use proc_macro2::TokenStream;

fn robots_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../robots")
}

/// The body of the `robot!` invocation declaring `robot <name>;` in `file`.
fn input(file: &str, name: &str) -> TokenStream {
    let path = robots_dir().join("src").join(file);
    let text = std::fs::read_to_string(&path).expect("a robots source file");
    let parsed = syn::parse_file(&text).expect("valid Rust");
    let header = format!("robot {name} ;");
    parsed
        .items
        .into_iter()
        .find_map(|item| match item {
            syn::Item::Macro(m) if m.mac.tokens.to_string().contains(&header) => Some(m.mac.tokens),
            _ => None,
        })
        .unwrap_or_else(|| panic!("no `robot {name};` in {}", path.display()))
}

fn expansion(c: &mut Criterion) {
    let options = Options {
        base_dir: robots_dir(),
        ir_dir: None,
    };
    let mut group = c.benchmark_group("expand");
    group.sample_size(10);
    for (file, name) in [
        ("arm3r.rs", "Arm3r"),
        ("rrp.rs", "Rrp"),
        ("mar.rs", "Mar"),
        ("urdf_robots.rs", "Ur5"),
        ("urdf_robots.rs", "Panda"),
    ] {
        let tokens = input(file, name);
        let out = expand(tokens.clone(), &options).to_string();
        assert!(
            !out.contains("compile_error"),
            "{name} expands without errors"
        );
        group.bench_function(name, |b| {
            b.iter(|| black_box(expand(black_box(tokens.clone()), &options)))
        });
    }
    group.finish();
}

criterion_group!(benches, expansion);
criterion_main!(benches);
