//! Time of one macro expansion (parse, model, URDF, derive, emit) of the
//! robots of the `robots` crate, with every output (the macro always emits
//! them all). The inputs are read from the `robot!` invocations in
//! `robots/src/`, so the bench follows the real descriptions.
//! Run: `cargo bench -p dynamics-codegen --bench expand`.

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion};
use dynamics_codegen::{expand, Options};

#[path = "support/robots_src.rs"]
mod robots_src;

fn expansion(c: &mut Criterion) {
    let options = Options {
        base_dir: robots_src::robots_dir(),
        ir_dir: None,
    };
    let mut group = c.benchmark_group("expand");
    group.sample_size(10);
    for (file, name) in robots_src::ROBOTS {
        let tokens = robots_src::input(file, name);
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
