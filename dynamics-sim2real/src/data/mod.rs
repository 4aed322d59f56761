//! Measured data: joint positions, velocities and efforts sampled over time,
//! in the trajectory CSV format (docs/cli.md) (`t`, `q_<joint>`, `qd_<joint>`,
//! `tau_<joint>`, matched by name; `.csv.gz` read as well), and recorded
//! files in other layouts (text matrices, one file per quantity, NumPy
//! `.npz`) through a column map ([`import`]), ROS 2 bags ([`bag`]) and
//! Parquet files of the CSV's columns ([`parquet`]).

pub mod bag;
mod error;
pub mod import;
pub mod parquet;
mod prepare;
mod read;
mod window;
mod write;

pub use error::{DataError, MAX_GLITCH_FRACTION, MIN_GLITCHES_REFUSED};
pub use prepare::{max_grid_samples, prepare, GLITCH_THRESHOLD, HOLE_PERIODS};
pub use read::{read_csv, read_csv_bytes, read_csv_str};
pub use write::write_csv;

use crate::Warning;

use nalgebra::SVector;

/// Samples of a robot's motion as measured.
///
/// ```
/// use dynamics_sim2real::data::Measured;
/// let m = Measured::<1> {
///     t: vec![0.0, 0.001],
///     q: vec![[0.0].into(), [0.001].into()],
///     qd: vec![[1.0].into(), [1.0].into()],
///     tau: vec![[0.5].into(), [0.5].into()],
///     qd_measured: true,
///     ..Default::default()
/// };
/// assert_eq!(m.len(), 2);
/// assert!((m.duration() - 0.001).abs() < 1e-15);
/// ```
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Measured<const N: usize> {
    /// Sample times, strictly increasing, s.
    pub t: Vec<f64>,
    /// Link-side positions.
    pub q: Vec<SVector<f64, N>>,
    /// Velocities (measured, or differentiated from q when the file has none).
    pub qd: Vec<SVector<f64, N>>,
    /// Efforts applied, held from each sample to the next.
    pub tau: Vec<SVector<f64, N>>,
    /// Whether `qd` came from the file.
    pub qd_measured: bool,
    /// What the reader ignored or repaired (extra columns, glitches, holes, ...).
    pub warnings: Vec<Warning>,
    /// Per sample, whether it was not measured but filled ([`prepare`]:
    /// repeated, glitched, or in a hole); empty when every sample was.
    pub missing: Vec<bool>,
    /// Index ranges `[start, end)` of the holes ([`prepare`]): the record's
    /// segments lie between them.
    pub holes: Vec<(usize, usize)>,
    /// The joints' names in column order, when known (the reader sets them).
    pub joints: Vec<String>,
    /// Whether [`prepare`] made these samples (the reader's output is).
    pub prepared: bool,
    /// By how much the grid's linear interpolation scaled the variance of
    /// white sensor noise, on average over the grid (`(1 - a)^2 + a^2` at
    /// fraction `a` between two samples; 1 when nothing was interpolated,
    /// 0 read as 1): the noise-level estimate is divided by it.
    pub interpolation_variance: f64,
}

impl<const N: usize> Measured<N> {
    /// Number of samples.
    pub fn len(&self) -> usize {
        self.t.len()
    }

    /// Whether there are no samples.
    pub fn is_empty(&self) -> bool {
        self.t.is_empty()
    }

    /// Time from the first sample to the last.
    pub fn duration(&self) -> f64 {
        match (self.t.first(), self.t.last()) {
            (Some(a), Some(b)) => b - a,
            _ => 0.0,
        }
    }

    /// Whether sample `k` was measured (not filled by [`prepare`]).
    pub fn measured(&self, k: usize) -> bool {
        !self.missing.get(k).copied().unwrap_or(false)
    }

    /// [`Measured::interpolation_variance`], 0 read as 1.
    pub fn noise_variance_factor(&self) -> f64 {
        if self.interpolation_variance > 0.0 {
            self.interpolation_variance
        } else {
            1.0
        }
    }

    /// Mean sample interval.
    pub fn sample_interval(&self) -> f64 {
        if self.len() < 2 {
            0.0
        } else {
            self.duration() / (self.len() - 1) as f64
        }
    }
}

/// Central differences (one-sided at the ends) of `q` over `t`.
pub(crate) fn differentiate<const N: usize>(
    t: &[f64],
    q: &[SVector<f64, N>],
) -> Vec<SVector<f64, N>> {
    let n = t.len();
    (0..n)
        .map(|k| {
            let (a, b) = (k.saturating_sub(1), (k + 1).min(n - 1));
            if a == b {
                SVector::zeros()
            } else {
                (q[b] - q[a]) / (t[b] - t[a])
            }
        })
        .collect()
}
