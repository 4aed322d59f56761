//! What `new` writes: the `robot!` body, checked by the macro's own
//! pipeline, and the crate's files around it.

use std::path::Path;

/// The `robot!` body the crate gets.
pub(super) fn robot_body(name: &str, g: [f64; 3], urdf: &str) -> String {
    format!(
        "pub robot {name};\n    gravity = [{:?}, {:?}, {:?}];\n    urdf = {urdf:?};",
        g[0], g[1], g[2]
    )
}

/// The macro's own verdict on the robot: its `compile_error!` messages.
pub(super) fn check_model(body: &str, base_dir: &Path) -> Result<(), String> {
    let tokens: proc_macro2::TokenStream = body.parse().map_err(|e| format!("{e}"))?;
    let options = dynamics_codegen::Options {
        base_dir: base_dir.to_path_buf(),
        ir_dir: None,
    };
    let out = dynamics_codegen::expand(tokens, &options).to_string();
    let mut messages = Vec::new();
    let mut rest = out.as_str();
    while let Some(at) = rest.find("compile_error") {
        rest = &rest[at..];
        let Some(open) = rest.find('"') else { break };
        let mut msg = String::new();
        let mut chars = rest[open + 1..].char_indices();
        let mut end = rest.len();
        while let Some((i, c)) = chars.next() {
            match c {
                '\\' => {
                    if let Some((_, e)) = chars.next() {
                        msg.push(if e == 'n' { '\n' } else { e });
                    }
                }
                '"' => {
                    end = open + 1 + i;
                    break;
                }
                c => msg.push(c),
            }
        }
        messages.push(msg);
        rest = &rest[end.min(rest.len())..];
    }
    if messages.is_empty() {
        Ok(())
    } else {
        Err(messages.join("; "))
    }
}

/// What `new` writes: (relative path, content).
pub(super) fn files(
    package: &str,
    name: &str,
    body: &str,
    urdf_file: &str,
    deps: &str,
) -> Vec<(String, String)> {
    let cargo = format!(
        r#"[package]
name = "{package}"
version = "0.1.0"
edition = "2021"
publish = false

[dependencies]
{deps}
# Its own workspace: builds outside the dynamics workspace.
[workspace]

[profile.release]
debug = false
"#
    );
    let main = format!(
        r#"//! The `dynamics` program for the robot of `{urdf_file}` (written by
//! `dynamics new`): `eval`, `check --reference`, `simulate`, `synth` and
//! `diagnose`, with `--set NAME=VALUE` and `--baseline FILE.json`; see `--help`.

dynamics_macros::robot! {{
    /// The robot of `{urdf_file}`.
    {body}
}}

fn main() -> std::process::ExitCode {{
    // The URDF's joint limits: what `excite` designs within.
    let limits = dynamics_cli::JointLimits::of({name}::LOWER, {name}::UPPER, {name}::VELOCITY, {name}::EFFORT);
    let info = dynamics_cli::RobotInfo {{ limits: Some(limits), ..Default::default() }};
    dynamics_cli::run_with({name}::default(), info)
}}
"#
    );
    vec![
        ("Cargo.toml".into(), cargo),
        ("src/main.rs".into(), main),
        (".gitignore".into(), "/target\n".into()),
    ]
}

/// What `new --python` writes: a maturin package whose module `module`
/// holds the class `Robot` of the bindings (`python/` of the workspace),
/// `Robot()` making this robot: the `robot!` call and one line of bindings.
pub(super) fn python_files(
    package: &str,
    module: &str,
    name: &str,
    body: &str,
    urdf_file: &str,
    deps: &str,
) -> Vec<(String, String)> {
    let cargo = format!(
        r#"[package]
name = "{package}"
version = "0.1.0"
edition = "2021"
publish = false

[lib]
name = "{module}"
crate-type = ["cdylib"]

[dependencies]
{deps}
# Its own workspace: builds outside the dynamics workspace.
[workspace]

[profile.release]
debug = false
"#
    );
    let pyproject = format!(
        r#"[build-system]
requires = ["maturin>=1.5,<2"]
build-backend = "maturin"

[project]
name = "{package}"
version = "0.1.0"
description = "The dynamics of the robot of {urdf_file}, from NumPy (written by `dynamics new --python`)"
requires-python = ">=3.9"
dependencies = ["numpy>=1.21"]

[tool.maturin]
module-name = "{module}"
"#
    );
    let lib = format!(
        r#"//! The Python module `{module}` for the robot of `{urdf_file}` (written by
//! `dynamics new --python`): `{module}.Robot()` is this robot, with the API
//! of the package `dynamics` (docs/python.md of the dynamics workspace).

dynamics_macros::robot! {{
    /// The robot of `{urdf_file}`.
    {body}
}}

/// The module: the class `Robot`, whose `Robot()` is [`{name}`].
#[pyo3::pymodule]
fn {module}(m: &pyo3::Bound<'_, pyo3::types::PyModule>) -> pyo3::PyResult<()> {{
    _dynamics::add_robot_module(m, "{module}", || _dynamics::kernel({name}::default()), _dynamics::Limits::of({name}::LOWER, {name}::UPPER, {name}::VELOCITY, {name}::EFFORT))
}}
"#
    );
    vec![
        ("Cargo.toml".into(), cargo),
        ("pyproject.toml".into(), pyproject),
        ("src/lib.rs".into(), lib),
        (".gitignore".into(), "/target\n".into()),
    ]
}
