//! What the reader repaired and what the diagnosis could not see, each with
//! its place (file, line, column, joint) and the figure measured: carried by
//! [`crate::data::Measured`] and the diagnosis report (JSON, readable report,
//! command line).

use std::fmt;

use serde::Serialize;

/// One warning. `Display` gives the sentence the command line prints; the
/// JSON report carries the fields under `kind`.
///
/// ```
/// use dynamics_sim2real::Warning;
/// let w = Warning::Hole { file: "run.csv".into(), line: 812, start: 0.81, end: 0.93 };
/// assert_eq!(w.to_string(), "run.csv:812: hole of 0.120 s (0.810 to 0.930 s): the record is split there; nothing is interpolated or differentiated across it");
/// ```
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Warning {
    /// What the importer of a recorded file ([`crate::data::import`]) notes
    /// (a layout read sample by sample, a clock counted from its first
    /// sample), with its place.
    Imported {
        /// The sentence, beginning with the file.
        message: String,
    },
    /// A column of the file that no joint uses.
    ColumnIgnored {
        /// The file.
        file: String,
        /// The column.
        column: String,
    },
    /// The clock is irregular: the data were brought onto a uniform grid.
    Resampled {
        /// The file.
        file: String,
        /// The grid's interval (the median interval of the file), s.
        interval: f64,
        /// RMS relative deviation of the intervals from it.
        jitter: f64,
        /// Shortest interval, s.
        min: f64,
        /// Longest interval that is not a hole, s.
        max: f64,
    },
    /// Rows whose values of one quantity repeat the row before exactly
    /// (a logger writing the previous sample again): treated as missing.
    Repeated {
        /// The file.
        file: String,
        /// `q`, `qd`, `tau`, or `row` (the whole row, time included).
        quantity: String,
        /// Rows affected.
        rows: usize,
        /// Their fraction of the file's rows.
        fraction: f64,
        /// First such line.
        first_line: usize,
    },
    /// Samples missing for longer than a few periods.
    Hole {
        /// The file.
        file: String,
        /// Line of the first sample after the hole.
        line: usize,
        /// Last sample before the hole, s.
        start: f64,
        /// First sample after it, s.
        end: f64,
    },
    /// A sample far outside its signal's course: excluded from every fit.
    Glitch {
        /// The file.
        file: String,
        /// 1-based line.
        line: usize,
        /// The column.
        column: String,
        /// The value read.
        value: f64,
        /// Its departure from the local robust fit, in robust standard
        /// deviations of that departure.
        sigmas: f64,
    },
    /// Glitches beyond those listed one by one.
    MoreGlitches {
        /// The file.
        file: String,
        /// How many more.
        count: usize,
    },
    /// A joint that does not move in these data: nothing about it can be
    /// identified.
    NoMotion {
        /// Joint.
        joint: String,
        /// Largest smoothed speed, rad/s or m/s.
        peak_speed: f64,
    },
    /// A joint whose velocity never reverses: Coulomb friction and a
    /// constant effort offset cannot be told apart.
    NoReversal {
        /// Joint.
        joint: String,
    },
    /// An effect whose signature lies (partly) above what the sample rate
    /// shows: not identifiable there on these data, searched only below.
    RateTooLow {
        /// Vocabulary name of the effect.
        effect: String,
        /// The sample rate, Hz.
        rate: f64,
        /// Highest frequency these data show (a quarter of the rate), Hz.
        limit: f64,
        /// Where the effect's signature reaches, Hz.
        needs: f64,
    },
    /// The measured positions lag the integral of the measured velocities:
    /// the position stream is late (`time_delay`, channel `positions`).
    LatePositions {
        /// The delay from the kinematic consistency, s.
        delay: f64,
        /// Its standard deviation, s.
        std: f64,
    },
    /// The measured effort lags the model's effort along the measured
    /// motion, whose positions and velocities agree: the effort stream is
    /// late (`time_delay`, channel `effort`).
    LateEffort {
        /// The delay fitted, s.
        delay: f64,
        /// Its standard deviation, s.
        std: f64,
    },
    /// The motion lags the effort (`time_delay`, channel `all`) but the
    /// velocities are derived from the positions: whether the position
    /// stream alone is late or positions and velocities together cannot be
    /// told on these data.
    LateMotionUnresolved {
        /// The delay fitted, s.
        delay: f64,
        /// Its standard deviation, s.
        std: f64,
    },
    /// The effort and the motion are offset by less than half a sample
    /// interval: how the log samples its streams (an effort read at its
    /// sample's instant, or held over the interval after it), not a delay
    /// to name.
    WithinSample {
        /// The offset fitted, s (positive: the motion lags the effort).
        delay: f64,
        /// The sample interval, s.
        interval: f64,
    },
    /// The data ask for link corrections that leave no physical body on
    /// most of the links: the nominal model's inertial parameters are
    /// rough (a CAD model), and link corrections are held to the nearest
    /// physical body and named where they hold on the held-out record, as
    /// `--hold-links` asks.
    RoughInertials {
        /// Links whose correction leaves no body.
        links: usize,
        /// Links the diagnosis may correct.
        of: usize,
    },
    /// The short-horizon simulation of a model could not be made (a
    /// plant it cannot build, an integrator that stops): its figures are
    /// left out (`null` in the JSON report).
    SimulationNotMade {
        /// Which model: `the nominal model` or `the model with the explanation`.
        model: String,
        /// Why.
        reason: String,
    },
}

impl fmt::Display for Warning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Warning::Imported { message } => write!(f, "{message}"),
            Warning::ColumnIgnored { file, column } => write!(f, "{file}: column `{column}` ignored"),
            Warning::Resampled { file, interval, jitter, min, max } => write!(
                f,
                "{file}: irregular clock (intervals {min:.3e} to {max:.3e} s, RMS jitter {:.1} %): \
                 brought onto a uniform grid of {interval:.3e} s by linear interpolation at the true times",
                jitter * 100.0
            ),
            Warning::Repeated { file, quantity, rows, fraction, first_line } => write!(
                f,
                "{file}:{first_line}: {rows} rows ({:.1} %) repeat the previous row's `{quantity}` exactly: treated as missing",
                fraction * 100.0
            ),
            Warning::Hole { file, line, start, end } => write!(
                f,
                "{file}:{line}: hole of {:.3} s ({start:.3} to {end:.3} s): the record is split there; \
                 nothing is interpolated or differentiated across it",
                end - start
            ),
            Warning::Glitch { file, line, column, value, sigmas } => write!(
                f,
                "{file}:{line}: column `{column}`: glitch {value:.4e} ({} sigma off its course): excluded from every fit",
                if *sigmas < 1e6 { format!("{sigmas:.0}") } else { format!("{sigmas:.1e}") }
            ),
            Warning::MoreGlitches { file, count } => {
                let what = if *count == 1 { "glitch" } else { "glitches" };
                write!(f, "{file}: {count} more {what}, excluded from every fit")
            }
            Warning::NoMotion { joint, peak_speed } => write!(
                f,
                "joint {joint}: does not move (peak speed {peak_speed:.2e}): nothing about it can be identified from these data"
            ),
            Warning::SimulationNotMade { model, reason } => write!(
                f,
                "the 0.1 s simulations of {model} could not be made ({reason}): their figures are left out"
            ),
            Warning::NoReversal { joint } => write!(
                f,
                "joint {joint}: its velocity never reverses: Coulomb friction and an effort offset cannot be told apart on these data"
            ),
            Warning::RateTooLow { effect, rate, limit, needs } => write!(
                f,
                "`{effect}` (signatures up to {needs:.0} Hz) is not identifiable above {limit:.0} Hz on these data \
                 (sampled at {rate:.0} Hz; a signature needs four samples a period): searched only below, not guessed"
            ),
            Warning::LatePositions { delay, std } => write!(
                f,
                "the positions lag the measured velocities by {:.2} +- {:.2} ms: the position stream is late against velocity and effort",
                delay * 1e3,
                std * 1e3
            ),
            Warning::LateEffort { delay, std } => write!(
                f,
                "the effort lags the measured motion by {:.2} +- {:.2} ms (positions and velocities agree): the effort stream is late against position and velocity",
                delay * 1e3,
                std * 1e3
            ),
            Warning::RoughInertials { links, of } => write!(
                f,
                "the data ask for corrections that leave no physical body on {links} of the {of} links: the nominal inertial parameters are rough (a CAD model?), so link corrections are held to the nearest physical body and named where they hold on the held-out record (as --hold-links)"
            ),
            Warning::WithinSample { delay, interval } => write!(
                f,
                "the effort and the motion are offset by {:.2} ms, within half a sample ({:.2} ms at {:.0} Hz): how the log samples its streams (an effort read at its sample's instant or held over the interval after it), not a delay",
                delay * 1e3,
                interval * 0.5e3,
                1.0 / interval
            ),
            Warning::LateMotionUnresolved { delay, std } => write!(
                f,
                "the motion lags the effort by {:.2} +- {:.2} ms; the velocities are derived from the positions, so whether the position stream alone is late or positions and velocities together cannot be told on these data (channel `all`)",
                delay * 1e3,
                std * 1e3
            ),
        }
    }
}
