//! Preparing measured data as recorded for the diagnosis: the clock, the
//! repeated samples, the glitches and the holes of a real log.
//!
//! - `clock.rs`: median interval, jitter, holes, milliseconds;
//! - `repeats.rs`: a logger writing the previous values again;
//! - `glitch.rs`: samples far off their course (a robust local test);
//! - here: the uniform grid.
//!
//! The grid: the file's median interval from its first sample. Each
//! channel is brought onto it by linear interpolation at the true times
//! between its two neighbouring samples that are valid (neither repeated
//! nor glitched). That interpolation shifts nothing in time (it is exact
//! for straight lines, so a signal's phase is kept to second order) and
//! smooths far less than the analysis does: at frequency `f` and interval
//! `dt` it scales a sine by at least `cos(pi f dt)`, 0.9989 for 15 Hz (the
//! pass band of the 40 ms smoother) at 1 kHz, 0.89 at 100 Hz where only
//! motion below a few Hz is usable anyway. A grid sample
//! whose neighbours are further apart than the clock's ordinary intervals
//! (a repeated or glitched sample was skipped) is marked missing; one
//! whose neighbours are [`HOLE_PERIODS`] intervals or more apart lies in a
//! hole: the record is split there. Values in a hole are filled (linearly)
//! only to keep the arrays finite; the diagnosis uses no row whose filter
//! window reaches a missing sample's hole and no missing sample as a row.

mod clock;
mod glitch;
mod grid;
mod repeats;

pub use clock::HOLE_PERIODS;
pub use glitch::THRESHOLD as GLITCH_THRESHOLD;

use nalgebra::SVector;

use super::error::{DataError, MAX_GLITCH_FRACTION, MIN_GLITCHES_REFUSED};
use super::Measured;
use crate::Warning;
use clock::{speed_ratio, Clock};
use grid::grid;

/// The most samples the uniform grid of `n` recorded samples may hold:
/// `4 n + 10^6` (a record whose gaps are longer is refused rather than
/// filled: a stamp off by years asked for terabytes).
///
/// ```
/// assert_eq!(dynamics_sim2real::data::max_grid_samples(1000), 1_004_000);
/// ```
pub fn max_grid_samples(n: usize) -> usize {
    n.saturating_mul(4).saturating_add(1_000_000)
}

/// Glitch warnings listed one by one per file; the rest are counted.
const GLITCHES_LISTED: usize = 20;

/// Prepares data as recorded (`m.t` increasing, possibly irregular; row `k`
/// on line `k + 2` of `file`): repeated samples and glitches marked
/// missing, the samples brought onto a uniform grid, holes marked, each
/// with a [`Warning`] appended to `m.warnings`. Data on a uniform clock
/// without damage come back unchanged.
///
/// ```
/// use dynamics_sim2real::data::{prepare, Measured};
/// use dynamics_sim2real::Warning;
/// let n = 400;
/// // A 1 kHz clock with +-30 % jitter, a smooth motion, one glitch.
/// let mut t: Vec<f64> = vec![0.0];
/// for k in 1..n { t.push(t[k - 1] + 1e-3 * [0.7, 1.0, 1.3][k % 3]); }
/// let mut m = Measured::<1> {
///     q: t.iter().map(|&t| [t.sin()].into()).collect(),
///     qd: t.iter().map(|&t| [t.cos()].into()).collect(),
///     tau: t.iter().map(|&t| [2.0 * t].into()).collect(),
///     t,
///     qd_measured: true,
///     ..Default::default()
/// };
/// m.tau[200][0] = 1e300;
/// let p = prepare(&m, "log.csv").unwrap();
/// assert!((p.t[1] - p.t[0] - 1e-3).abs() < 1e-12); // the median interval
/// assert!((p.q[100][0] - (0.1f64).sin()).abs() < 1e-6);
/// assert!(p.tau.iter().all(|v| v[0].abs() < 1.0)); // the glitch is gone
/// assert!(matches!(&p.warnings[0], Warning::Resampled { .. }));
/// assert!(matches!(&p.warnings[1], Warning::Glitch { line: 202, .. }));
/// ```
pub fn prepare<const N: usize>(m: &Measured<N>, file: &str) -> Result<Measured<N>, DataError> {
    let n = m.len();
    let mut warnings = m.warnings.clone();
    if n < 2 {
        return Ok(m.clone());
    }
    let clock = Clock::of(&m.t);
    check_seconds(m, &clock, file)?;
    if !clock.uniform && clock.jitter > 1e-3 {
        warnings.push(Warning::Resampled {
            file: file.to_string(),
            interval: clock.interval,
            jitter: clock.jitter,
            min: clock.min,
            max: clock.max,
        });
    }
    // Per channel (q, qd, tau of each joint), the samples not to be used.
    let channels = if m.qd_measured { 3 * N } else { 2 * N };
    let mut bad = vec![vec![false; n]; channels];
    for (q, quantity) in [(0, "q"), (1, "qd"), (2, "tau")] {
        let rows = match q {
            0 => repeats::repeated(&m.q),
            1 if m.qd_measured => repeats::repeated(&m.qd),
            1 => vec![],
            _ => repeats::repeated(&m.tau),
        };
        if let Some(&first) = rows.first() {
            warnings.push(Warning::Repeated {
                file: file.to_string(),
                quantity: quantity.to_string(),
                rows: rows.len(),
                fraction: rows.len() as f64 / n as f64,
                first_line: first + 2,
            });
            for c in channel_range::<N>(q, m.qd_measured) {
                for &k in &rows {
                    bad[c][k] = true;
                }
            }
        }
    }
    let mut found = Vec::new();
    for (c, flags) in bad.iter_mut().enumerate() {
        let x = channel(m, c);
        // The glitch test on the samples not already marked (a repeated
        // sample is off its course by the motion of one interval).
        let kept: Vec<usize> = (0..n).filter(|&k| !flags[k]).collect();
        let sub = |v: &[f64]| -> Vec<f64> { kept.iter().map(|&k| v[k]).collect() };
        let g: Vec<(usize, f64)> = glitch::glitches(&sub(&m.t), &sub(&x))
            .into_iter()
            .map(|(i, s)| (kept[i], s))
            .collect();
        if g.len() as f64 > (MAX_GLITCH_FRACTION * n as f64).max(MIN_GLITCHES_REFUSED as f64) {
            return Err(DataError::TooManyGlitches {
                file: file.to_string(),
                column: column_name(m, c, N),
                count: g.len(),
                rows: n,
            });
        }
        for (k, sigmas) in g {
            flags[k] = true;
            found.push((k, c, x[k], sigmas));
        }
    }
    found.sort_by_key(|g| (g.0, g.1));
    for &(k, c, value, sigmas) in found.iter().take(GLITCHES_LISTED) {
        warnings.push(Warning::Glitch {
            file: file.to_string(),
            line: k + 2,
            column: column_name(m, c, N),
            value,
            sigmas,
        });
    }
    if found.len() > GLITCHES_LISTED {
        warnings.push(Warning::MoreGlitches {
            file: file.to_string(),
            count: found.len() - GLITCHES_LISTED,
        });
    }
    let damaged = bad.iter().any(|b| b.iter().any(|&x| x));
    if !clock.uniform || damaged {
        let span = m.t[n - 1] - m.t[0];
        let samples = span / clock.interval + 1.0;
        if samples.is_nan() || samples > max_grid_samples(n) as f64 {
            return Err(DataError::GridTooLong {
                file: file.to_string(),
                span,
                interval: clock.interval,
                grid: samples.floor(),
                rows: n,
            });
        }
    }
    if clock.uniform && !damaged {
        return Ok(Measured {
            warnings,
            prepared: true,
            ..m.clone()
        });
    }
    Ok(grid(m, &bad, &clock, file, warnings))
}

/// Refuses a time column that looks like milliseconds.
fn check_seconds<const N: usize>(
    m: &Measured<N>,
    clock: &Clock,
    file: &str,
) -> Result<(), DataError> {
    let ratio = if m.qd_measured {
        speed_ratio(&m.t, &m.q, &m.qd)
    } else {
        None
    };
    let ms_ratio = ratio.is_some_and(|r| (3e-4..3e-3).contains(&r));
    if ms_ratio || clock.interval >= 0.5 {
        return Err(DataError::Milliseconds {
            file: file.to_string(),
            interval: clock.interval,
            ratio,
        });
    }
    Ok(())
}

/// Channel indices of quantity `q` (0 = q, 1 = qd, 2 = tau).
fn channel_range<const N: usize>(q: usize, qd_measured: bool) -> std::ops::Range<usize> {
    match (q, qd_measured) {
        (0, _) => 0..N,
        (1, true) => N..2 * N,
        (1, false) => 0..0,
        (_, true) => 2 * N..3 * N,
        (_, false) => N..2 * N,
    }
}

/// The series behind channel `c`: q of every joint, then qd (if measured), then tau.
pub(super) fn series<const N: usize>(m: &Measured<N>, c: usize) -> (&[SVector<f64, N>], usize) {
    let per = c / N;
    let v = match (per, m.qd_measured) {
        (0, _) => &m.q,
        (1, true) => &m.qd,
        _ => &m.tau,
    };
    (v, c % N)
}

pub(super) fn channel<const N: usize>(m: &Measured<N>, c: usize) -> Vec<f64> {
    let (v, j) = series(m, c);
    v.iter().map(|x| x[j]).collect()
}

/// The column's name, `q_3` style when the joints' names are not known here.
fn column_name<const N: usize>(m: &Measured<N>, c: usize, n: usize) -> String {
    let prefix = match (c / n, m.qd_measured) {
        (0, _) => "q",
        (1, true) => "qd",
        _ => "tau",
    };
    match m.joints.get(c % n) {
        Some(name) => format!("{prefix}_{name}"),
        None => format!("{prefix}_{}", c % n),
    }
}
