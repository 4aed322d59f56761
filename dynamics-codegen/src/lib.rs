//! The pipeline behind `dynamics_macros::robot!`, as a plain library: a
//! robot description in, straight-line Rust for its equations of motion out.
//!
//! One module per stage, chained in `expand.rs`: `parse` (tokens -> syntax
//! tree) -> `model` (validated kinematic tree; `urdf` feeds it) -> `derive`
//! (expression DAG of the dynamics, built with `dynamics-symbolic`) -> `emit`
//! (tokens). The grammar is documented on `dynamics_macros::robot!`, which
//! is a one-line wrapper around [`expand`]. Being a plain crate, the pipeline
//! can be unit-tested and benchmarked (`cargo bench -p dynamics-codegen`).

mod ctxt;
mod derive;
mod dump;
mod emit;
mod expand;
mod model;
mod parse;
mod rotation;
mod urdf;

use std::path::PathBuf;

use proc_macro2::TokenStream;

/// Where an expansion reads and writes files.
///
/// ```
/// let options = dynamics_codegen::Options {
///     base_dir: "robots".into(),
///     ir_dir: None,
/// };
/// assert!(options.base_dir.ends_with("robots"));
/// ```
#[derive(Clone, Debug, Default)]
pub struct Options {
    /// Folder that `urdf = "..."` paths are relative to (`robot!` passes the
    /// using crate's `CARGO_MANIFEST_DIR`).
    pub base_dir: PathBuf,
    /// When set, `<ir_dir>/<Robot>.ir.txt` receives the operation count of
    /// every output and its expression DAG as text (`robot!` sets it from the
    /// environment variable `DYNAMICS_IR_DIR`).
    pub ir_dir: Option<PathBuf>,
}

/// Expands the body of `robot! { ... }` into the items it stands for: the
/// robot type, its parameters and its `dynamics_runtime::Robot`
/// implementation. Never panics: errors in the input (each at the token at
/// fault) and internal failures come back as `compile_error!` invocations.
///
/// ```
/// use quote::quote;
///
/// let input = quote! {
///     pub robot Pendulum;
///     gravity = [0.0, -9.81, 0.0];
///     link base;
///     link bob { mass = 1.0; com = [0.5, 0.0, 0.0]; inertia = [1e-4, 1e-4, 1e-4]; }
///     joint hinge = revolute(base -> bob) { transfer = [rot_z(q)]; }
/// };
/// let out = dynamics_codegen::expand(input, &dynamics_codegen::Options::default()).to_string();
/// assert!(out.contains("Robot < 1usize > for Pendulum"));
/// assert!(!out.contains("compile_error"));
///
/// let wrong = quote! { pub robot Pendulum; gravity = [0.0]; };
/// let out = dynamics_codegen::expand(wrong, &dynamics_codegen::Options::default()).to_string();
/// assert!(out.contains("compile_error"));
/// ```
pub fn expand(input: TokenStream, options: &Options) -> TokenStream {
    expand::robot(input, options)
}

/// Reads and validates the body of `robot! { ... }` (including the URDF it
/// names) without deriving or emitting anything: the reader half of
/// [`expand`], for tools that check a description quickly (an editor, a
/// linter, a fuzzer). `Err` holds the same `compile_error!` invocations
/// `expand` would give.
///
/// ```
/// use quote::quote;
///
/// let input = quote! {
///     pub robot Pendulum;
///     gravity = [0.0, -9.81, 0.0];
///     link base;
///     link bob { mass = 1.0; com = [0.5, 0.0, 0.0]; inertia = [1e-4, 1e-4, 1e-4]; }
///     joint hinge = revolute(base -> bob) { transfer = [rot_z(q)]; }
/// };
/// assert!(dynamics_codegen::check(input, &dynamics_codegen::Options::default()).is_ok());
///
/// let wrong = quote! { pub robot Pendulum; gravity = [0.0]; };
/// let err = dynamics_codegen::check(wrong, &dynamics_codegen::Options::default()).unwrap_err();
/// assert!(err.to_string().contains("compile_error"));
/// ```
pub fn check(input: TokenStream, options: &Options) -> Result<(), TokenStream> {
    expand::check(input, options)
}
