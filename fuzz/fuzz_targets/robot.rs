//! A URDF file through the whole `robot!` pipeline (read, derive, emit) on
//! any bytes: `compile_error!`s or a robot, never a panic. Slow on valid
//! robots (every derivation runs), so it runs beside `urdf`, not instead.
#![no_main]

use libfuzzer_sys::fuzz_target;

#[global_allocator]
static ALLOC: dynamics_fuzz::Bounded = dynamics_fuzz::Bounded;

fuzz_target!(|data: &[u8]| {
    let dir = std::env::temp_dir().join(format!("dynamics-fuzz-robot-{}", std::process::id()));
    if std::fs::create_dir_all(&dir).is_err() || std::fs::write(dir.join("r.urdf"), data).is_err() {
        return;
    }
    let Ok(tokens) = "pub robot Fuzzed; gravity = [0.0, 0.0, -9.81]; urdf = \"r.urdf\";"
        .parse::<proc_macro2::TokenStream>()
    else {
        return;
    };
    let options = dynamics_codegen::Options {
        base_dir: dir,
        ir_dir: None,
    };
    let _ = dynamics_codegen::expand(tokens, &options);
});
