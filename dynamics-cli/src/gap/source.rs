//! A data file and how to read it: our CSV, a Parquet file of the CSV's
//! columns, a ROS 2 bag (a topic of JointState messages, `--topic`), or a
//! recorded file in its own layout through a column map (`--columns`),
//! optionally cut to a time window (`--train-window`, `--holdout-window`).

use std::path::PathBuf;

use dynamics_sim2real::data::bag::{is_bag, read_bag, DEFAULT_TOPIC};
use dynamics_sim2real::data::import::{import, ColumnMap};
use dynamics_sim2real::data::parquet::{is_parquet, read_parquet};
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
///     topic: None,
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
    /// The topic of a ROS 2 bag (`None`: `/joint_states`).
    pub topic: Option<String>,
}

impl DataFile {
    /// A CSV file read whole.
    pub fn csv(path: impl Into<PathBuf>) -> Self {
        DataFile {
            path: path.into(),
            columns: None,
            window: None,
            topic: None,
        }
    }

    /// The measured data of a robot with joints `joints`.
    pub fn read<const N: usize>(&self, joints: &[&str; N]) -> Result<Measured<N>, GapError> {
        Ok(self.read_described(joints)?.0)
    }

    /// [`DataFile::read`], and for a bag what was read (file, topic, message
    /// count, time range: a line for the report's header).
    ///
    /// ```
    /// use dynamics_cli::gap::DataFile;
    /// let path = std::env::temp_dir().join("dynamics-doc-described.csv");
    /// let text: String = std::iter::once("t,q_j,tau_j\n".to_string())
    ///     .chain((0..300).map(|k| format!("{},0,1\n", k as f64 * 1e-3)))
    ///     .collect();
    /// std::fs::write(&path, text).unwrap();
    /// let (m, about) = DataFile::csv(&path).read_described(&["j"]).unwrap();
    /// assert_eq!((m.len(), about), (300, None));
    /// ```
    pub fn read_described<const N: usize>(
        &self,
        joints: &[&str; N],
    ) -> Result<(Measured<N>, Option<String>), GapError> {
        if let Some(map) = &self.columns {
            return Ok((import(&self.path, map, joints, self.window)?, None));
        }
        let (m, about) = if is_bag(&self.path) {
            let topic = self.topic.as_deref().unwrap_or(DEFAULT_TOPIC);
            let (m, summary) = read_bag(&self.path, joints, topic)?;
            (m, Some(summary.to_string()))
        } else if let Some(topic) = &self.topic {
            return Err(GapError::Request(format!(
                "--topic {topic}: {} is not a ROS 2 bag (a rosbag2 directory, .mcap or .db3)",
                self.path.display()
            )));
        } else if is_parquet(&self.path) {
            (read_parquet(&self.path, joints)?, None)
        } else {
            (read_csv(&self.path, joints)?, None)
        };
        Ok((
            match self.window {
                Some((a, b)) => m.window(a, b),
                None => m,
            },
            about,
        ))
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
