//! Writes `<dir>/<robot>.rs`: the code `robot!` emits for each robot of the
//! `robots` crate (every output), as one line of tokens, without compiling
//! the `robots` crate. Used to read the emitted code and to time rustc on it
//! apart from the expansion (`dynamics-codegen/scripts/rustc_time.sh`):
//! `cargo run --release -p dynamics-codegen --example expanded -- /tmp/expanded`.

#[path = "../benches/support/robots_src.rs"]
mod robots_src;

fn main() {
    let dir = std::path::PathBuf::from(
        std::env::args()
            .nth(1)
            .unwrap_or_else(|| "expanded".to_string()),
    );
    if let Err(e) = std::fs::create_dir_all(&dir) {
        eprintln!("cannot create {}: {e}", dir.display());
        std::process::exit(1);
    }
    let options = dynamics_codegen::Options {
        base_dir: robots_src::robots_dir(),
        ir_dir: None,
    };
    for (file, name) in robots_src::ROBOTS {
        let out = dynamics_codegen::expand(robots_src::input(file, name), &options).to_string();
        if out.contains("compile_error") {
            eprintln!("{name}: the expansion reports an error");
            std::process::exit(1);
        }
        let path = dir.join(format!("{}.rs", name.to_lowercase()));
        if let Err(e) = std::fs::write(&path, out + "\n") {
            eprintln!("cannot write {}: {e}", path.display());
            std::process::exit(1);
        }
        println!("{}", path.display());
    }
}
