//! What can be wrong with a recorded file or with the column map that
//! names its parts; every variant names the file (and the line, array or
//! entry where there is one).

use thiserror::Error;

/// What is wrong with an imported file or its column map.
///
/// ```
/// use dynamics_sim2real::data::import::{ColumnMap, ImportError};
/// let err = "q=positions,tau=torques".parse::<ColumnMap>().unwrap_err();
/// assert!(matches!(err, ImportError::Map { .. }));
/// assert_eq!(err.to_string(), "column map `q=positions,tau=torques`: no `t=` (the time)");
/// ```
#[derive(Debug, Error)]
pub enum ImportError {
    /// The column map (`--columns`) cannot be read.
    #[error("column map `{map}`: {message}")]
    Map {
        /// The map as given.
        map: String,
        /// What is wrong.
        message: String,
    },
    /// A file could not be opened or read.
    #[error("{file}: {source}")]
    Io {
        /// The file.
        file: String,
        /// The cause.
        source: std::io::Error,
    },
    /// A text cell is not a finite number.
    #[error("{file}:{line}: column {column}: `{value}` is not a finite number")]
    BadNumber {
        /// The file.
        file: String,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// The cell.
        value: String,
    },
    /// A text row has another number of columns than the first.
    #[error("{file}:{line}: {found} columns, the first row has {expected}")]
    Ragged {
        /// The file.
        file: String,
        /// 1-based line.
        line: usize,
        /// Columns on this line.
        found: usize,
        /// Columns on the first data line.
        expected: usize,
    },
    /// The zip container of a `.npz` is broken or uses what we do not read.
    #[error("{file}: not a readable .npz (zip) archive: {message}")]
    Zip {
        /// The file.
        file: String,
        /// What is wrong.
        message: String,
    },
    /// An array of a `.npz` (or a `.npy` file) cannot be read.
    #[error("{file}: array `{array}`: {message}")]
    Npy {
        /// The file.
        file: String,
        /// The array.
        array: String,
        /// What is wrong.
        message: String,
    },
    /// The map names an array or file that is not there.
    #[error("{file}: no {what} `{name}` (there are: {available})")]
    Missing {
        /// The archive or directory.
        file: String,
        /// `array` or `file`.
        what: &'static str,
        /// The name looked for.
        name: String,
        /// What there is.
        available: String,
    },
    /// A source does not have the shape the map and the robot need.
    #[error("{source_name}: {message}")]
    Shape {
        /// The source (`file` or `file:array`).
        source_name: String,
        /// What is wrong.
        message: String,
    },
    /// Time does not increase.
    #[error("{place}: time {t} does not increase (previous sample at {previous})")]
    TimeNotIncreasing {
        /// `file:line` or `file row k`.
        place: String,
        /// Time there.
        t: f64,
        /// Time of the sample before.
        previous: f64,
    },
    /// A value read from a binary array is not finite.
    #[error("{place}: {quantity} of joint `{joint}` is {value}, not a finite number")]
    NotFinite {
        /// `file:line` or `file row k`.
        place: String,
        /// `t`, `q`, `qd` or `tau`.
        quantity: &'static str,
        /// The joint (empty for `t`).
        joint: String,
        /// The value.
        value: f64,
    },
    /// Too few samples (after the time window).
    #[error("{file}: {rows} samples{window}; at least {min} are needed")]
    TooFewSamples {
        /// The file.
        file: String,
        /// Samples kept.
        rows: usize,
        /// ` in the window a..b s` when a window was applied.
        window: String,
        /// The least number.
        min: usize,
    },
}
