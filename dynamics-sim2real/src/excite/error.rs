//! What designing an exciting motion can fail with.

use thiserror::Error;

/// An error of [`crate::excite`], naming the place and the cause.
///
/// ```
/// use dynamics_sim2real::excite::ExciteError;
/// let e = ExciteError::Unbounded { joint: "j1".into(), what: "position" };
/// assert!(e.to_string().contains("j1"));
/// ```
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ExciteError {
    /// A joint has no finite limit of this kind and the design needs one.
    #[error("joint `{joint}` has no finite {what} limit: give one (the design fills the room the limits leave)")]
    Unbounded {
        /// The joint.
        joint: String,
        /// `position` or `velocity`.
        what: &'static str,
    },
    /// The start pose lies outside the limits (margin included).
    #[error("start pose of joint `{joint}` ({value}) is outside its limits [{lower}, {upper}] (margin included)")]
    StartOutside {
        /// The joint.
        joint: String,
        /// Its start position.
        value: f64,
        /// Lower limit with the margin.
        lower: f64,
        /// Upper limit with the margin.
        upper: f64,
    },
    /// Holding the start pose already needs more effort than allowed.
    #[error("joint `{joint}` needs {need:.4} at rest at the start pose, more than its effort limit {limit:.4} (margin included)")]
    StartEffort {
        /// The joint.
        joint: String,
        /// Effort needed at rest.
        need: f64,
        /// The limit with the margin.
        limit: f64,
    },
    /// An option is out of range.
    #[error("option `{option}`: {cause}")]
    Options {
        /// The option.
        option: &'static str,
        /// Why it is refused.
        cause: String,
    },
    /// The robot's regressor could not be evaluated.
    #[error("the inertial regressor of `{robot}` failed: {cause}")]
    Regressor {
        /// The robot.
        robot: &'static str,
        /// The runtime's message.
        cause: String,
    },
    /// A numerical step gave no finite answer.
    #[error("{place}: {cause}")]
    Numeric {
        /// Where.
        place: &'static str,
        /// What went wrong.
        cause: String,
    },
}
