//! What can be wrong with a data file, each error naming the file, and the
//! limits of what a data file may be.

use thiserror::Error;

/// Fewest samples a data file must hold.
pub const MIN_SAMPLES: usize = 200;

/// Largest fraction of a column's rows that may be glitches before the
/// file is refused.
pub const MAX_GLITCH_FRACTION: f64 = 0.01;

/// A column is refused only beyond this many glitches, however short the
/// file (a 6 s log at 100 Hz has 600 rows: 1 % would be 6).
pub const MIN_GLITCHES_REFUSED: usize = 10;

/// What is wrong with a data file. Every variant names the file.
///
/// ```
/// use dynamics_sim2real::data::{read_csv_str, DataError};
/// let mut text = String::from("t,q_j,tau_j\n");
/// for k in 0..300 { text.push_str(&format!("{},0,0\n", k as f64 * 1e-3)); }
/// let bad = text.replacen("0.005,0,0", "0.005,NaN,0", 1);
/// match read_csv_str(&bad, &["j"], "run.csv") {
///     Err(e @ DataError::BadNumber { line: 7, .. }) => {
///         assert_eq!(e.to_string(), "run.csv:7: column `q_j`: `NaN` is not a finite number");
///     }
///     other => panic!("{other:?}"),
/// }
/// ```
#[derive(Debug, Error)]
pub enum DataError {
    /// The file could not be opened or read.
    #[error("{file}: {source}")]
    Io {
        /// The file.
        file: String,
        /// The cause.
        source: std::io::Error,
    },
    /// The CSV syntax is broken.
    #[error("{file}: {message}")]
    Csv {
        /// The file.
        file: String,
        /// What the CSV reader said.
        message: String,
    },
    /// A needed column is missing.
    #[error("{file}: no column `{column}`{hint}")]
    MissingColumn {
        /// The file.
        file: String,
        /// The column.
        column: String,
        /// ` (did you mean ...?)` or the joints the robot has.
        hint: String,
    },
    /// A column names a joint the robot does not have.
    #[error("{file}: column `{column}` names no joint of this robot (its joints: {joints})")]
    UnknownJoint {
        /// The file.
        file: String,
        /// The column.
        column: String,
        /// The robot's joints.
        joints: String,
    },
    /// A cell is not a finite number.
    #[error("{file}:{line}: column `{column}`: `{value}` is not a finite number")]
    BadNumber {
        /// The file.
        file: String,
        /// 1-based line.
        line: usize,
        /// The column.
        column: String,
        /// The cell.
        value: String,
    },
    /// Time does not increase.
    #[error("{file}:{line}: time {t} does not increase (previous sample at {previous})")]
    TimeNotIncreasing {
        /// The file.
        file: String,
        /// 1-based line.
        line: usize,
        /// Time at the line.
        t: f64,
        /// Time at the line before.
        previous: f64,
    },
    /// A row with more or fewer fields than the header.
    #[error("{file}:{line}: {fields} fields where the header has {expected}{}", if *last { " (the file ends in the middle of a row)" } else { "" })]
    RowLength {
        /// The file.
        file: String,
        /// 1-based line.
        line: usize,
        /// Fields in the row.
        fields: usize,
        /// Fields in the header.
        expected: usize,
        /// Whether it is the last row.
        last: bool,
    },
    /// The time column looks like milliseconds.
    #[error("{file}: time looks like milliseconds ({}); write `t` in seconds", ms_reason(*interval, *ratio))]
    Milliseconds {
        /// The file.
        file: String,
        /// Median interval in the file's unit.
        interval: f64,
        /// The positions' rate of change per unit of `t` over the recorded
        /// velocity (1 if `t` were in seconds), when velocities are recorded.
        ratio: Option<f64>,
    },
    /// Too many samples of a column are glitches.
    #[error("{file}: column `{column}`: {count} of {rows} samples are glitches (far off their signal's course); more than {} % (and {}) is not a log to diagnose", MAX_GLITCH_FRACTION * 100.0, MIN_GLITCHES_REFUSED)]
    TooManyGlitches {
        /// The file.
        file: String,
        /// The column.
        column: String,
        /// Glitches found.
        count: usize,
        /// Rows.
        rows: usize,
    },
    /// The record's gaps are so long that its uniform grid would hold far
    /// more samples than were recorded ([`crate::data::max_grid_samples`]).
    #[error("{file}: the samples span {span} s at an interval of {interval} s: a uniform grid of {grid} samples for {rows} recorded (at most 4 x the recorded + 1000000); its gaps are too long: cut the record with a time window")]
    GridTooLong {
        /// The file.
        file: String,
        /// From the first sample to the last, s.
        span: f64,
        /// The grid's interval, s.
        interval: f64,
        /// Samples the grid would hold.
        grid: f64,
        /// Samples recorded.
        rows: usize,
    },
    /// Too few rows.
    #[error("{file}: {rows} samples; at least {MIN_SAMPLES} are needed")]
    TooFewSamples {
        /// The file.
        file: String,
        /// Rows read.
        rows: usize,
    },
}

fn ms_reason(interval: f64, ratio: Option<f64>) -> String {
    match ratio {
        Some(r) if (3e-4..3e-3).contains(&r) => format!(
            "the positions change {:.0} times slower per unit of `t` than the recorded velocities say",
            1.0 / r
        ),
        _ => format!("the median interval is {interval} of its unit, a rate of {:.2} samples per unit", 1.0 / interval),
    }
}
