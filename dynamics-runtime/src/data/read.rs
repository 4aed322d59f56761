//! Reading measured data from CSV (plain or gzip), matching columns to the
//! robot's joints by name and saying exactly what is wrong otherwise.

use std::io::Read;
use std::path::Path;

use nalgebra::SVector;
use thiserror::Error;

use super::{differentiate, Measured};

/// Fewest samples a data file must hold.
pub const MIN_SAMPLES: usize = 200;

/// What is wrong with a data file. Every variant names the file.
///
/// ```
/// use dynamics_runtime::data::{read_csv_str, DataError};
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
    /// Too few rows.
    #[error("{file}: {rows} samples; at least {MIN_SAMPLES} are needed")]
    TooFewSamples {
        /// The file.
        file: String,
        /// Rows read.
        rows: usize,
    },
}

/// Reads a CSV file (`.csv` or `.csv.gz`) for a robot with joints `joints`.
///
/// ```
/// use dynamics_runtime::data::read_csv;
/// let dir = std::env::temp_dir();
/// let path = dir.join("dynamics-doc-read.csv");
/// let mut text = String::from("t,q_j,tau_j\n");
/// for k in 0..300 { text.push_str(&format!("{},{},1\n", k as f64 * 1e-3, k as f64 * 1e-3)); }
/// std::fs::write(&path, text).unwrap();
/// let m = read_csv(&path, &["j"]).unwrap();
/// assert!((m.qd[100][0] - 1.0).abs() < 1e-9); // differentiated from q
/// assert!(!m.qd_measured);
/// ```
pub fn read_csv<const N: usize>(path: &Path, joints: &[&str; N]) -> Result<Measured<N>, DataError> {
    let file = path.display().to_string();
    let io = |source| DataError::Io {
        file: file.clone(),
        source,
    };
    let bytes = std::fs::read(path).map_err(io)?;
    let text = if bytes.starts_with(&[0x1f, 0x8b]) {
        let mut s = String::new();
        flate2::read::MultiGzDecoder::new(&bytes[..])
            .read_to_string(&mut s)
            .map_err(io)?;
        s
    } else {
        String::from_utf8(bytes).map_err(|e| {
            io(std::io::Error::new(
                std::io::ErrorKind::InvalidData,
                format!("not UTF-8 text ({e}); a gzip file must start with the gzip magic bytes"),
            ))
        })?
    };
    read_csv_str(&text, joints, &file)
}

/// Reads CSV text; `file` names it in errors.
///
/// ```
/// use dynamics_runtime::data::{read_csv_str, DataError};
/// let mut text = String::from("t,q_elbow,qd_elbow,tau_elbow\n");
/// for k in 0..300 { text.push_str(&format!("{},0.1,0,2.5\n", k as f64 * 1e-3)); }
/// let m = read_csv_str(&text, &["elbow"], "inline").unwrap();
/// assert_eq!((m.len(), m.qd_measured, m.tau[0][0]), (300, true, 2.5));
/// // A joint the file does not have is named, with the columns it would need.
/// let err = read_csv_str(&text, &["wrist"], "inline").unwrap_err();
/// assert!(matches!(err, DataError::MissingColumn { ref column, .. } if column == "q_wrist"));
/// ```
pub fn read_csv_str<const N: usize>(
    text: &str,
    joints: &[&str; N],
    file: &str,
) -> Result<Measured<N>, DataError> {
    let mut reader = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .from_reader(text.as_bytes());
    let csv_err = |e: csv::Error| DataError::Csv {
        file: file.to_string(),
        message: e.to_string(),
    };
    let header: Vec<String> = reader
        .headers()
        .map_err(csv_err)?
        .iter()
        .map(str::to_string)
        .collect();
    let find = |name: &str| header.iter().position(|h| h == name);
    let joint_list = joints.join(", ");
    let missing = |column: String| {
        let hint = header
            .iter()
            .find(|h| h.eq_ignore_ascii_case(&column) || close(h, &column))
            .map(|h| format!(" (there is `{h}`: did you mean `{column}`?)"))
            .unwrap_or_else(|| format!(" (the robot's joints: {joint_list})"));
        DataError::MissingColumn {
            file: file.to_string(),
            column,
            hint,
        }
    };
    let t_col = find("t").ok_or_else(|| missing("t".into()))?;
    let cols = |prefix: &str, required: bool| -> Result<Option<[usize; N]>, DataError> {
        let mut out = [0; N];
        for (i, j) in joints.iter().enumerate() {
            let name = format!("{prefix}_{j}");
            match find(&name) {
                Some(c) => out[i] = c,
                None if required => return Err(missing(name)),
                None => return Ok(None),
            }
        }
        Ok(Some(out))
    };
    let q_cols = cols("q", true)?.unwrap_or([0; N]);
    let tau_cols = cols("tau", true)?.unwrap_or([0; N]);
    let qd_cols = cols("qd", false)?;
    let mut warnings = Vec::new();
    for h in &header {
        let used = h == "t"
            || joints
                .iter()
                .any(|j| ["q", "qd", "tau"].iter().any(|p| *h == format!("{p}_{j}")));
        if used {
            continue;
        }
        if let Some(rest) = ["q_", "qd_", "tau_"].iter().find_map(|p| h.strip_prefix(p)) {
            if !rest.is_empty() && !h.starts_with("qdd_") {
                return Err(DataError::UnknownJoint {
                    file: file.to_string(),
                    column: h.clone(),
                    joints: joint_list,
                });
            }
        }
        warnings.push(format!("{file}: column `{h}` ignored"));
    }
    let mut m = Measured::<N> {
        qd_measured: qd_cols.is_some(),
        warnings,
        ..Default::default()
    };
    for (row, record) in reader.records().enumerate() {
        let record = record.map_err(csv_err)?;
        let line = row + 2;
        let cell = |c: usize| -> Result<f64, DataError> {
            let value = record.get(c).unwrap_or("");
            value
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| DataError::BadNumber {
                    file: file.to_string(),
                    line,
                    column: header[c].clone(),
                    value: value.to_string(),
                })
        };
        let t = cell(t_col)?;
        if let Some(&previous) = m.t.last() {
            if t <= previous {
                return Err(DataError::TimeNotIncreasing {
                    file: file.to_string(),
                    line,
                    t,
                    previous,
                });
            }
        }
        let vec = |cs: &[usize; N]| -> Result<SVector<f64, N>, DataError> {
            let mut v = SVector::zeros();
            for i in 0..N {
                v[i] = cell(cs[i])?;
            }
            Ok(v)
        };
        m.t.push(t);
        m.q.push(vec(&q_cols)?);
        m.tau.push(vec(&tau_cols)?);
        if let Some(c) = &qd_cols {
            m.qd.push(vec(c)?);
        }
    }
    if m.len() < MIN_SAMPLES {
        return Err(DataError::TooFewSamples {
            file: file.to_string(),
            rows: m.len(),
        });
    }
    if !m.qd_measured {
        m.qd = differentiate(&m.t, &m.q);
    }
    Ok(m)
}

/// One edit apart (a typo), for "did you mean".
fn close(a: &str, b: &str) -> bool {
    let (a, b): (Vec<char>, Vec<char>) = (a.chars().collect(), b.chars().collect());
    if a.len().abs_diff(b.len()) > 1 {
        return false;
    }
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    for i in 1..=a.len() {
        let mut cur = vec![i; b.len() + 1];
        for j in 1..=b.len() {
            let sub = prev[j - 1] + usize::from(a[i - 1] != b[j - 1]);
            cur[j] = sub.min(prev[j] + 1).min(cur[j - 1] + 1);
        }
        prev = cur;
    }
    prev[b.len()] <= 1
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rows(n: usize, f: impl Fn(usize) -> String) -> String {
        (0..n).map(f).collect()
    }

    #[test]
    fn every_kind_of_bad_file_is_named() {
        let ok = |k: usize| format!("{},0,0,1\n", k as f64 * 1e-3);
        let e = read_csv_str::<1>(
            &format!("t,q_j,qd_j,torque_j\n{}", rows(300, ok)),
            &["j"],
            "a.csv",
        )
        .unwrap_err();
        assert!(e.to_string().contains("no column `tau_j`"), "{e}");
        let e = read_csv_str::<1>(
            &format!("t,q_J,qd_j,tau_j\n{}", rows(300, ok)),
            &["j"],
            "a.csv",
        )
        .unwrap_err();
        assert!(e.to_string().contains("did you mean `q_j`"), "{e}");
        let e = read_csv_str::<1>(
            &format!(
                "t,q_j,qd_j,tau_j,q_k\n{}",
                rows(300, |k| format!("{},0,0,1,0\n", k))
            ),
            &["j"],
            "a.csv",
        )
        .unwrap_err();
        assert!(e.to_string().contains("`q_k` names no joint"), "{e}");
        let e = read_csv_str::<1>(
            &format!("t,q_j,qd_j,tau_j\n{}0.5,NaN,0,1\n", rows(3, ok)),
            &["j"],
            "a.csv",
        )
        .unwrap_err();
        assert_eq!(
            e.to_string(),
            "a.csv:5: column `q_j`: `NaN` is not a finite number"
        );
        let e = read_csv_str::<1>(
            &format!("t,q_j,qd_j,tau_j\n{}0.001,0,0,1\n", rows(3, ok)),
            &["j"],
            "a.csv",
        )
        .unwrap_err();
        assert!(
            e.to_string()
                .starts_with("a.csv:5: time 0.001 does not increase"),
            "{e}"
        );
        let e = read_csv_str::<1>(
            &format!("t,q_j,qd_j,tau_j\n{}", rows(10, ok)),
            &["j"],
            "a.csv",
        )
        .unwrap_err();
        assert!(e.to_string().contains("10 samples; at least 200"), "{e}");
        let m = read_csv_str::<1>(
            &format!(
                "t,q_j,qd_j,tau_j,temp\n{}",
                rows(300, |k| format!("{},0,0,1,20\n", k))
            ),
            &["j"],
            "a.csv",
        )
        .unwrap();
        assert_eq!(m.warnings, vec!["a.csv: column `temp` ignored"]);
    }
}
