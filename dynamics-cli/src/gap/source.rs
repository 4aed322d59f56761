//! A data file and how to read it: our CSV, or a recorded file in its own
//! layout through a column map (`--columns`), optionally cut to a time
//! window (`--train-window`, `--holdout-window`).

use std::path::PathBuf;

use dynamics_sim2real::data::import::{import, ColumnMap};
use dynamics_sim2real::data::{read_csv, Measured};

use super::GapError;

/// A data file (or directory of files) and how to read it.
///
/// ```
/// use dynamics_cli::gap::DataFile;
/// let path = std::env::temp_dir().join("dynamics-doc-datafile.txt");
/// let text: String = (0..500).map(|k| format!("{} {} 1.5\n", k as f64 * 1e-3, k as f64 * 1e-3)).collect();
/// std::fs::write(&path, text).unwrap();
/// let file = DataFile {
///     path,
///     columns: Some("t=:1,q=:2,tau=:3".parse().unwrap()),
///     window: Some((0.1, 0.4)),
/// };
/// let m = file.read(&["j"]).unwrap();
/// assert_eq!((m.len(), m.tau[0][0]), (300, 1.5));
/// ```
#[derive(Debug, Clone)]
pub struct DataFile {
    /// The file, or the directory of a record kept as one file per quantity.
    pub path: PathBuf,
    /// `None`: the trajectory CSV (docs/cli.md); else where `t`, `q`, `qd`, `tau` are.
    pub columns: Option<ColumnMap>,
    /// Seconds from the first sample, start inclusive, end exclusive.
    pub window: Option<(f64, f64)>,
}

impl DataFile {
    /// A CSV file read whole.
    pub fn csv(path: impl Into<PathBuf>) -> Self {
        DataFile {
            path: path.into(),
            columns: None,
            window: None,
        }
    }

    /// The measured data of a robot with joints `joints`.
    pub fn read<const N: usize>(&self, joints: &[&str; N]) -> Result<Measured<N>, GapError> {
        match &self.columns {
            Some(map) => Ok(import(&self.path, map, joints, self.window)?),
            None => {
                let m = read_csv(&self.path, joints)?;
                Ok(match self.window {
                    Some((a, b)) => m.window(a, b),
                    None => m,
                })
            }
        }
    }
}

/// Reads a window `A:B` (seconds from the first sample).
///
/// ```
/// assert_eq!(dynamics_cli::gap::parse_window("0:10.5").unwrap(), (0.0, 10.5));
/// assert!(dynamics_cli::gap::parse_window("10").is_err());
/// ```
pub fn parse_window(text: &str) -> Result<(f64, f64), GapError> {
    let bad = || {
        GapError::Request(format!(
            "window `{text}`: expected START:END in seconds from the first sample, START < END"
        ))
    };
    let (a, b) = text.split_once(':').ok_or_else(bad)?;
    let (a, b): (f64, f64) = (
        a.trim().parse().map_err(|_| bad())?,
        b.trim().parse().map_err(|_| bad())?,
    );
    if a.is_finite() && b.is_finite() && a < b {
        Ok((a, b))
    } else {
        Err(bad())
    }
}
