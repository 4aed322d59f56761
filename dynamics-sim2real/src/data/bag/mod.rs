//! ROS 2 bags: the `sensor_msgs/msg/JointState` messages of one topic of a
//! rosbag2 directory (`metadata.yaml` beside its `.mcap` or `.db3` files),
//! or of one `.mcap` or `.db3` file, as measured data.
//!
//! - `mcap.rs`: MCAP files (the `mcap` crate; chunks compressed with zstd
//!   or lz4), cargo feature `rosbag`;
//! - `sqlite.rs`: sqlite3 bags (`rusqlite`, SQLite bundled), feature `rosbag`;
//! - `cdr.rs`: the JointState message decoded from CDR (either byte order);
//! - `merge.rs`: messages into samples of the robot's joints;
//! - `error.rs`: [`BagError`].
//!
//! The samples then go through [`prepare`](crate::data::prepare) as every
//! log does (jitter, repeats, holes, glitches). A warning's line number
//! counts samples as the CSV of the same data would (sample `k` on line
//! `k + 2`).

pub mod cdr;
mod error;
#[cfg(feature = "rosbag")]
mod mcap;
// Without `rosbag` no reader feeds the collector: only its closing is reached.
#[cfg_attr(not(feature = "rosbag"), allow(dead_code))]
mod merge;
#[cfg(feature = "rosbag")]
mod sqlite;

pub use error::BagError;

use merge::Collector;

use std::path::{Path, PathBuf};

use super::{prepare, Measured};
use crate::Warning;

/// The message type read.
pub const JOINT_STATE: &str = "sensor_msgs/msg/JointState";
/// The topic read unless told otherwise.
pub const DEFAULT_TOPIC: &str = "/joint_states";
/// Fewest samples a bag must hold (as for the CSV reader).
pub const MIN_SAMPLES: usize = 200;

/// Where a message is in its file, for errors.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(not(feature = "rosbag"), allow(dead_code))]
pub(crate) enum Place {
    /// An MCAP message record outside chunks, at this byte.
    Record(u64),
    /// Record `index` (0-based) of the MCAP chunk at byte `chunk`.
    InChunk {
        /// The chunk record's offset.
        chunk: u64,
        /// The record's index in the chunk.
        index: usize,
    },
    /// The row id of an sqlite3 bag's `messages` table.
    Row(i64),
}

impl std::fmt::Display for Place {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Place::Record(at) => write!(f, "message at byte {at}"),
            Place::InChunk { chunk, index } => {
                write!(f, "record {} of the chunk at byte {chunk}", index + 1)
            }
            Place::Row(id) => write!(f, "message id {id}"),
        }
    }
}

/// What was read from a bag, for the report's header.
#[derive(Debug, Clone, PartialEq)]
pub struct BagSummary {
    /// The bag (directory or file) as given.
    pub file: String,
    /// The topic read.
    pub topic: String,
    /// Messages read on it.
    pub messages: usize,
    /// First and last stamp, ns since the epoch.
    pub first_ns: i64,
    /// See `first_ns`.
    pub last_ns: i64,
}

impl std::fmt::Display for BagSummary {
    /// `bag.mcap: topic /joint_states, 1001 messages, 2025-11-24 16:00:00.000 to 2025-11-24 16:00:04.000 UTC (4.000 s)`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{}: topic {}, {} messages, {} to {} UTC ({:.3} s)",
            self.file,
            self.topic,
            self.messages,
            utc(self.first_ns),
            utc(self.last_ns),
            (self.last_ns - self.first_ns) as f64 * 1e-9
        )
    }
}

/// `YYYY-MM-DD hh:mm:ss.mmm` of ns since the epoch (proleptic Gregorian).
fn utc(ns: i64) -> String {
    let secs = ns.div_euclid(1_000_000_000);
    let ms = ns.rem_euclid(1_000_000_000) / 1_000_000;
    let (days, day_s) = (secs.div_euclid(86_400), secs.rem_euclid(86_400));
    // Days to a civil date (H. Hinnant's algorithm).
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097);
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!(
        "{y:04}-{m:02}-{d:02} {:02}:{:02}:{:02}.{ms:03}",
        day_s / 3600,
        day_s % 3600 / 60,
        day_s % 60
    )
}

/// Whether `path` looks like a bag: a directory with `metadata.yaml` or an
/// `.mcap`/`.db3` file in it, or a file named `.mcap` or `.db3`, or one that
/// starts with the MCAP or SQLite magic bytes.
///
/// ```
/// use dynamics_sim2real::data::bag::is_bag;
/// assert!(is_bag(std::path::Path::new("run.mcap")));
/// assert!(!is_bag(std::path::Path::new("run.csv")));
/// ```
pub fn is_bag(path: &Path) -> bool {
    if path.is_dir() {
        return path.join("metadata.yaml").is_file() || !storage_files(path).is_empty();
    }
    match path.extension().and_then(|e| e.to_str()) {
        Some("mcap" | "db3") => true,
        _ => {
            let mut head = [0u8; 16];
            use std::io::Read;
            std::fs::File::open(path)
                .and_then(|mut f| f.read_exact(&mut head))
                .map(|_| {
                    head.starts_with(b"\x89MCAP0\r\n") || head.starts_with(b"SQLite format 3\0")
                })
                .unwrap_or(false)
        }
    }
}

/// The `.mcap` and `.db3` files of a rosbag2 directory: those its
/// `metadata.yaml` lists under `relative_file_paths`, else every one there,
/// in the order of their names' numbers (`bag_0`, `bag_1`, ..., `bag_10`).
fn storage_files(dir: &Path) -> Vec<PathBuf> {
    if let Ok(yaml) = std::fs::read_to_string(dir.join("metadata.yaml")) {
        let mut listed = Vec::new();
        let mut inside = false;
        for line in yaml.lines() {
            let trimmed = line.trim();
            if trimmed.starts_with("relative_file_paths:") {
                inside = true;
            } else if inside {
                match trimmed.strip_prefix("- ") {
                    Some(name) => listed.push(dir.join(name.trim().trim_matches(['"', '\'']))),
                    None => inside = false,
                }
            }
        }
        if !listed.is_empty() {
            return listed;
        }
    }
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .map(|d| {
            d.filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| {
                    p.is_file()
                        && matches!(p.extension().and_then(|e| e.to_str()), Some("mcap" | "db3"))
                })
                .collect()
        })
        .unwrap_or_default();
    let number = |p: &PathBuf| -> (String, u64) {
        let stem = p.file_stem().and_then(|s| s.to_str()).unwrap_or("");
        let digits: String = stem
            .chars()
            .rev()
            .take_while(char::is_ascii_digit)
            .collect::<Vec<_>>()
            .into_iter()
            .rev()
            .collect();
        (
            stem[..stem.len() - digits.len()].to_string(),
            digits.parse().unwrap_or(0),
        )
    };
    files.sort_by_key(number);
    files
}

/// The messages on `topic` of one storage file, into `out`; the warnings.
fn read_storage<const N: usize>(
    path: &Path,
    topic: &str,
    out: &mut Collector<'_, N>,
) -> Result<Vec<String>, BagError> {
    let file = path.display().to_string();
    let bytes = std::fs::read(path).map_err(|source| BagError::Io {
        file: file.clone(),
        source,
    })?;
    read_storage_bytes(&bytes, path, &file, topic, out)
}

#[cfg(feature = "rosbag")]
fn read_storage_bytes<const N: usize>(
    bytes: &[u8],
    path: &Path,
    file: &str,
    topic: &str,
    out: &mut Collector<'_, N>,
) -> Result<Vec<String>, BagError> {
    if mcap::is_mcap(bytes) {
        mcap::read(bytes, file, topic, out)
    } else if sqlite::is_sqlite(bytes) {
        sqlite::read(path, file, topic, out)
    } else {
        Err(BagError::NotABag {
            file: file.to_string(),
            message: "neither an MCAP file nor an sqlite3 database (by their first bytes)".into(),
        })
    }
}

#[cfg(not(feature = "rosbag"))]
fn read_storage_bytes<const N: usize>(
    _bytes: &[u8],
    _path: &Path,
    file: &str,
    _topic: &str,
    _out: &mut Collector<'_, N>,
) -> Result<Vec<String>, BagError> {
    Err(BagError::NotBuilt {
        file: file.to_string(),
        format: "rosbag2",
        feature: "rosbag",
    })
}

/// The messages of an MCAP file held in memory (what the fuzz target and
/// the benchmark read).
///
/// ```
/// use dynamics_sim2real::data::bag::read_mcap_bytes;
/// assert!(read_mcap_bytes::<1>(b"not an mcap", &["j"], "/joint_states", "x.mcap").is_err());
/// ```
#[cfg(feature = "rosbag")]
pub fn read_mcap_bytes<const N: usize>(
    bytes: &[u8],
    joints: &[&str; N],
    topic: &str,
    file: &str,
) -> Result<(Measured<N>, BagSummary), BagError> {
    let mut out = Collector::new(joints, file, topic);
    let warnings = mcap::read(bytes, file, topic, &mut out)?;
    finish(out, warnings, topic, file)
}

/// Reads the JointState messages on `topic` of the bag at `path` (a
/// rosbag2 directory, an `.mcap` file or a `.db3` file) for a robot with
/// joints `joints`, prepared as every log is; the summary says what was
/// read (for the report's header).
///
/// ```no_run
/// use dynamics_sim2real::data::bag::{read_bag, DEFAULT_TOPIC};
/// let (m, summary) = read_bag(std::path::Path::new("run"), &["j1", "j2", "j3"], DEFAULT_TOPIC).unwrap();
/// println!("{summary}: {} samples", m.len());
/// ```
pub fn read_bag<const N: usize>(
    path: &Path,
    joints: &[&str; N],
    topic: &str,
) -> Result<(Measured<N>, BagSummary), BagError> {
    let file = path.display().to_string();
    let files = if path.is_dir() {
        let files = storage_files(path);
        if files.is_empty() {
            return Err(BagError::NotABag {
                file,
                message:
                    "a directory without .mcap or .db3 files (rosbag2 files compressed whole, \
                          `.mcap.zstd`, are not read: `ros2 bag decompress` first)"
                        .into(),
            });
        }
        files
    } else {
        vec![path.to_path_buf()]
    };
    let mut out = Collector::new(joints, &file, topic);
    let mut warnings = Vec::new();
    for f in &files {
        warnings.extend(read_storage(f, topic, &mut out)?);
    }
    finish(out, warnings, topic, &file)
}

/// The samples of the messages collected, prepared.
fn finish<const N: usize>(
    out: Collector<'_, N>,
    read_warnings: Vec<String>,
    topic: &str,
    file: &str,
) -> Result<(Measured<N>, BagSummary), BagError> {
    let mut warnings: Vec<Warning> = read_warnings
        .into_iter()
        .map(|message| Warning::Imported { message })
        .collect();
    let messages = out.received();
    let (m, first_ns, last_ns) = out.finish(&mut warnings)?;
    if m.len() < MIN_SAMPLES {
        return Err(BagError::TooFewSamples {
            file: file.to_string(),
            topic: topic.to_string(),
            rows: m.len(),
            min: MIN_SAMPLES,
        });
    }
    let mut prepared = prepare(&m, file)?;
    warnings.append(&mut prepared.warnings);
    prepared.warnings = warnings;
    let summary = BagSummary {
        file: file.to_string(),
        topic: topic.to_string(),
        messages,
        first_ns,
        last_ns,
    };
    Ok((prepared, summary))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn utc_dates_match_known_instants() {
        assert_eq!(utc(0), "1970-01-01 00:00:00.000");
        // 2025-11-24 16:00:00 UTC is 1764000000 s since the epoch.
        assert_eq!(utc(1_764_000_000_123_000_000), "2025-11-24 16:00:00.123");
        // 2000-02-29 (a leap day of a century divisible by 400): 951782400 s.
        assert_eq!(utc(951_782_400_000_000_000), "2000-02-29 00:00:00.000");
    }
}
