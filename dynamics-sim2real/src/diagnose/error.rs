//! Why a diagnosis could not run: data too short, unusable or
//! inconsistent with the model, each naming the data set and the cause.

use thiserror::Error;

use crate::data::DataError;

/// Why a diagnosis could not run.
#[derive(Debug, Error)]
pub enum DiagnoseError {
    /// A data set is too short for the filter.
    #[error(
        "{which} data: {samples} samples over {duration:.3} s are too few (need at least {need})"
    )]
    TooShort {
        /// `training` or `held-out`.
        which: &'static str,
        /// Samples.
        samples: usize,
        /// Duration.
        duration: f64,
        /// Samples needed.
        need: usize,
    },
    /// Stated sensor noise that cannot be used.
    #[error("sensor noise `{sensor}`: {reason}")]
    Noise {
        /// `q`, `qd` or `tau`.
        sensor: &'static str,
        /// Why.
        reason: String,
    },
    /// The data could not be prepared (too many glitches, time in
    /// milliseconds, ...).
    #[error(transparent)]
    Data(#[from] DataError),
    /// The worker threads could not be started.
    #[error("could not start the diagnosis's threads: {0}")]
    Threads(String),
    /// No joint moves: there is nothing to identify.
    #[error("training data: no joint moves; nothing about the robot can be identified from them")]
    NoMotion,
    /// The effort column of a joint has the wrong sign.
    #[error("{which} data: joint {joint}: the measured effort correlates negatively with the nominal model's (r = {correlation:.2}): is the effort column's sign flipped?")]
    EffortSign {
        /// `training` or `held-out`.
        which: &'static str,
        /// The joint.
        joint: String,
        /// Correlation of the measured and the model's smoothed efforts.
        correlation: f64,
    },
}
