//! The runtime's typed errors.

use thiserror::Error;

/// What can go wrong when a generated model is evaluated at run time.
///
/// ```
/// use dynamics_runtime::DynamicsError;
/// let e = DynamicsError::NonFinite { quantity: "q", index: 2 };
/// assert_eq!(e.to_string(), "q[2] is not finite (NaN or infinite)");
/// ```
#[derive(Debug, Clone, PartialEq, Error)]
pub enum DynamicsError {
    /// An input vector holds NaN or an infinity.
    #[error("{quantity}[{index}] is not finite (NaN or infinite)")]
    NonFinite {
        /// Which input (`q`, `qd`, `u`, ...).
        quantity: &'static str,
        /// Index of the first offending entry.
        index: usize,
    },
    /// The inertia matrix A(q) is not positive definite at this configuration,
    /// so the accelerations cannot be solved for.
    #[error("the inertia matrix A(q) is not positive definite at q = {q:?}")]
    SingularMassMatrix {
        /// The configuration at which the factorisation failed.
        q: Vec<f64>,
    },
    /// A computed quantity came out NaN or infinite although the inputs were finite.
    #[error("{quantity}[{index}] came out NaN or infinite")]
    Diverged {
        /// Which output.
        quantity: &'static str,
        /// Index of the first offending entry.
        index: usize,
    },
    /// An output slice does not have the length the robot needs.
    #[error("{quantity} needs a slice of length {expected}, got {found}")]
    Length {
        /// Which output (`inertial_regressor`, ...).
        quantity: &'static str,
        /// The length it needs (e.g. `Robot::LINK_NAMES.len()`).
        expected: usize,
        /// The length given.
        found: usize,
    },
    /// No run-time parameter of this robot has that name.
    #[error("unknown parameter `{name}`; this robot has: {known}")]
    UnknownParameter {
        /// The name asked for.
        name: String,
        /// The names the robot has, comma separated.
        known: String,
    },
}
