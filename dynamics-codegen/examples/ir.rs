//! Writes `<dir>/<Robot>.ir.txt` (operation count of every output, and the
//! expression DAG of each) for the robots of the `robots` crate without
//! compiling them: `cargo run --release -p dynamics-codegen --example ir -- /tmp/ir`.

#[path = "../benches/support/robots_src.rs"]
mod robots_src;

fn main() {
    let dir = std::env::args().nth(1).unwrap_or_else(|| "ir".to_string());
    let options = dynamics_codegen::Options {
        base_dir: robots_src::robots_dir(),
        ir_dir: Some(dir.clone().into()),
    };
    for (file, name) in robots_src::ROBOTS {
        let out = dynamics_codegen::expand(robots_src::input(file, name), &options).to_string();
        if out.contains("compile_error") {
            eprintln!("{name}: the expansion reports an error");
            std::process::exit(1);
        }
        println!("{dir}/{name}.ir.txt");
    }
}
