//! The Python package `dynamics` (module `dynamics._dynamics`): the
//! built-in robots with NumPy in and out (`robot.rs` over `kernel.rs`,
//! arguments in `arrays.rs`), and the gap diagnosis on files or data in
//! memory (`diagnose.rs`).
//!
//! A user's own robot gets the same class from a package of its own
//! (`dynamics new --python`): that crate depends on this one without the
//! built-in robots (`default-features = false`), and its module calls
//! [`add_robot_module`] with its robot:
//!
//! ```ignore
//! #[pyo3::pymodule]
//! fn my_arm(m: &pyo3::Bound<'_, pyo3::types::PyModule>) -> pyo3::PyResult<()> {
//!     _dynamics::add_robot_module(m, "my_arm", || _dynamics::kernel(MyArm::default()),
//!         _dynamics::Limits::of(MyArm::LOWER, MyArm::UPPER, MyArm::VELOCITY, MyArm::EFFORT))
//! }
//! ```

mod arrays;
#[cfg(feature = "builtin")]
mod builtin;
mod diagnose;
mod kernel;
mod robot;
mod tasks;

use std::sync::OnceLock;

use pyo3::prelude::*;

pub use kernel::{kernel, Kernel, Limits, Typed};
pub use robot::PyRobot;

/// The robot `Robot()` makes without a name: the one of a user's package.
struct Default {
    name: String,
    make: fn() -> Box<dyn Kernel>,
    limits: Limits,
}

static DEFAULT: OnceLock<Default> = OnceLock::new();

/// `Robot()` (no name) in this module.
pub(crate) fn default_robot() -> Option<PyRobot> {
    DEFAULT.get().map(|d| {
        PyRobot::new(
            &d.name,
            (d.make)(),
            d.limits.clone(),
            dynamics_cli::gap::Motion::default(),
        )
    })
}

/// Adds the class `Robot` to `m` with `Robot()` making the robot `make`
/// returns (a user's package: one robot, no built-in ones).
pub fn add_robot_module(
    m: &Bound<'_, PyModule>,
    name: &str,
    make: fn() -> Box<dyn Kernel>,
    limits: Limits,
) -> PyResult<()> {
    let _ = DEFAULT.set(Default {
        name: name.to_string(),
        make,
        limits,
    });
    m.add_class::<PyRobot>()?;
    m.add_function(wrap_pyfunction!(self::robots, m)?)?;
    Ok(())
}

/// The robots `Robot(name)` knows, name -> one line about it.
#[pyfunction]
fn robots() -> Vec<(String, String)> {
    let mut out: Vec<(String, String)> = Vec::new();
    if let Some(d) = DEFAULT.get() {
        out.push((d.name.clone(), "this package's robot".to_string()));
    }
    #[cfg(feature = "builtin")]
    out.extend(
        builtin::names()
            .into_iter()
            .map(|(n, d)| (n.to_string(), d.to_string())),
    );
    out
}

/// The robot called `name`: this package's own (no name), or a built-in one.
pub(crate) fn robot_by_name(name: Option<&str>) -> PyResult<PyRobot> {
    use pyo3::exceptions::PyKeyError;
    if let Some(d) = DEFAULT.get() {
        if name.is_none() || name == Some(d.name.as_str()) {
            return default_robot().ok_or_else(|| PyKeyError::new_err("no robot"));
        }
    }
    #[cfg(feature = "builtin")]
    if let Some(name) = name {
        return builtin::robot(name);
    }
    let known: Vec<String> = robots().into_iter().map(|r| r.0).collect();
    Err(PyKeyError::new_err(match name {
        None => format!("give a robot's name; known robots: {}", known.join(", ")),
        Some(n) => format!("unknown robot `{n}`; known robots: {}", known.join(", ")),
    }))
}

/// The extension module of the package `dynamics`.
#[cfg(feature = "builtin")]
#[pymodule]
fn _dynamics(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyRobot>()?;
    m.add_function(wrap_pyfunction!(self::robots, m)?)?;
    m.add("PARALLEL_FROM", kernel::PARALLEL_FROM)?;
    Ok(())
}
