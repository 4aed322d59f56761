//! Reading measured data from CSV (plain or gzip), matching columns to the
//! robot's joints by name and saying exactly what is wrong otherwise.
//!
//! - `columns.rs`: the header matched to the joints;
//! - here: the text read (gzip or not) and its rows parsed and checked.

mod columns;

use std::io::Read;
use std::path::Path;

use nalgebra::SVector;

use super::error::{DataError, MIN_SAMPLES};
use super::{differentiate, prepare, Measured};
use crate::Warning;
use columns::Columns;

/// Reads a CSV file (`.csv` or `.csv.gz`) for a robot with joints `joints`.
///
/// ```
/// use dynamics_sim2real::data::read_csv;
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
    let bytes = std::fs::read(path).map_err(|source| DataError::Io {
        file: file.clone(),
        source,
    })?;
    read_csv_bytes(&bytes, joints, &file)
}

/// Reads the bytes of a CSV file (gzip-compressed or not) named `file`.
///
/// ```
/// use dynamics_sim2real::data::read_csv_bytes;
/// let mut text = String::from("t,q_j,tau_j\n");
/// for k in 0..300 { text.push_str(&format!("{},0,1\n", k as f64 * 1e-3)); }
/// assert_eq!(read_csv_bytes(text.as_bytes(), &["j"], "m.csv").unwrap().len(), 300);
/// assert!(read_csv_bytes(&[0xff, 0xfe], &["j"], "m.csv").is_err());
/// ```
pub fn read_csv_bytes<const N: usize>(
    bytes: &[u8],
    joints: &[&str; N],
    file: &str,
) -> Result<Measured<N>, DataError> {
    let io = |source| DataError::Io {
        file: file.to_string(),
        source,
    };
    let decoded;
    let text = if bytes.starts_with(&[0x1f, 0x8b]) {
        let mut s = String::new();
        flate2::read::MultiGzDecoder::new(bytes)
            .read_to_string(&mut s)
            .map_err(io)?;
        decoded = s;
        decoded.as_str()
    } else {
        std::str::from_utf8(bytes).map_err(|e| {
            io(std::io::Error::new(
                std::io::ErrorKind::InvalidData,
                format!("not UTF-8 text ({e}); a gzip file must start with the gzip magic bytes"),
            ))
        })?
    };
    read_csv_str(text, joints, file)
}

/// Reads CSV text; `file` names it in errors.
///
/// ```
/// use dynamics_sim2real::data::{read_csv_str, DataError};
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
        .flexible(true)
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
    let rows = reader.records().enumerate().map(|(row, record)| {
        let record = record.map_err(csv_err)?;
        let line = record.position().map_or(row + 2, |p| p.line() as usize);
        Ok(CsvRow { record, line })
    });
    read_rows(&header, rows, joints, file)
}

/// One row of a table: its cells as numbers on request, and its line.
pub(crate) trait Row {
    /// Cells in the row.
    fn len(&self) -> usize;
    /// The 1-based line of the row (a binary table: row `k` counts as line `k + 2`, as in
    /// the CSV of the same data).
    fn line(&self) -> usize;
    /// Cell `c` as a finite number, or what it holds instead.
    fn cell(&self, c: usize) -> Result<f64, String>;
}

/// A CSV record and its line.
struct CsvRow {
    record: csv::StringRecord,
    line: usize,
}

impl Row for CsvRow {
    fn len(&self) -> usize {
        self.record.len()
    }
    fn line(&self) -> usize {
        self.line
    }
    fn cell(&self, c: usize) -> Result<f64, String> {
        let value = self.record.get(c).unwrap_or("");
        value
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| value.to_string())
    }
}

/// The rows of a table with columns `header` (our CSV's: `t`, `q_<joint>`,
/// ...), checked and prepared as [`read_csv_str`] says.
pub(crate) fn read_rows<const N: usize, R: Row>(
    header: &[String],
    rows: impl Iterator<Item = Result<R, DataError>>,
    joints: &[&str; N],
    file: &str,
) -> Result<Measured<N>, DataError> {
    let Columns {
        t: t_col,
        q: q_cols,
        tau: tau_cols,
        qd: qd_cols,
        warnings,
    } = Columns::find(header, joints, file)?;
    let mut m = Measured::<N> {
        qd_measured: qd_cols.is_some(),
        joints: joints.iter().map(|j| j.to_string()).collect(),
        ..Default::default()
    };
    let mut records = rows.peekable();
    // Whole rows written twice (time included), and the first such line.
    let (mut twice, mut twice_line) = (0usize, 0usize);
    // Line of each row kept (rows written twice are dropped).
    let mut lines = Vec::new();
    while let Some(record) = records.next() {
        let record = record?;
        let line = record.line();
        if record.len() != header.len() {
            return Err(DataError::RowLength {
                file: file.to_string(),
                line,
                fields: record.len(),
                expected: header.len(),
                last: records.peek().is_none(),
            });
        }
        let cell = |c: usize| -> Result<f64, DataError> {
            record.cell(c).map_err(|value| DataError::BadNumber {
                file: file.to_string(),
                line,
                column: header[c].clone(),
                value,
            })
        };
        let t = cell(t_col)?;
        if let Some(&previous) = m.t.last() {
            if t == previous && record_repeats(&m, &q_cols, &tau_cols, qd_cols.as_ref(), &cell)? {
                twice += 1;
                if twice_line == 0 {
                    twice_line = line;
                }
                continue;
            }
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
        lines.push(line);
        m.t.push(t);
        m.q.push(vec(&q_cols)?);
        m.tau.push(vec(&tau_cols)?);
        if let Some(c) = &qd_cols {
            m.qd.push(vec(c)?);
        }
    }
    // (What the rows were read from is not held while they are prepared.)
    drop(records);
    if m.len() < MIN_SAMPLES {
        return Err(DataError::TooFewSamples {
            file: file.to_string(),
            rows: m.len(),
        });
    }
    if !m.qd_measured {
        m.qd = differentiate(&m.t, &m.q);
    }
    let mut prepared = prepare(&m, file)?;
    // Lines as in the file, where rows written twice were dropped.
    if twice > 0 {
        for w in &mut prepared.warnings {
            let line = match w {
                Warning::Repeated { first_line: l, .. }
                | Warning::Glitch { line: l, .. }
                | Warning::Hole { line: l, .. } => l,
                _ => continue,
            };
            *line = lines.get(line.saturating_sub(2)).copied().unwrap_or(*line);
        }
        prepared.warnings.push(Warning::Repeated {
            file: file.to_string(),
            quantity: "row".into(),
            rows: twice,
            fraction: twice as f64 / (m.len() + twice) as f64,
            first_line: twice_line,
        });
    }
    let mut all = warnings;
    all.append(&mut prepared.warnings);
    prepared.warnings = all;
    Ok(prepared)
}

/// Whether `record` (at the time of the last row read) repeats that row.
fn record_repeats<const N: usize>(
    m: &Measured<N>,
    q_cols: &[usize; N],
    tau_cols: &[usize; N],
    qd_cols: Option<&[usize; N]>,
    cell: &dyn Fn(usize) -> Result<f64, DataError>,
) -> Result<bool, DataError> {
    let k = m.len() - 1;
    for j in 0..N {
        if cell(q_cols[j])? != m.q[k][j] || cell(tau_cols[j])? != m.tau[k][j] {
            return Ok(false);
        }
        if let Some(c) = qd_cols {
            if cell(c[j])? != m.qd[k][j] {
                return Ok(false);
            }
        }
    }
    Ok(true)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rows(n: usize, f: impl Fn(usize) -> String) -> String {
        (0..n).map(f).collect()
    }

    #[test]
    fn every_kind_of_bad_row_is_named() {
        let ok = |k: usize| format!("{},0,0,1\n", k as f64 * 1e-3);
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
    }

    #[test]
    fn a_gap_of_years_is_refused_not_filled() {
        // 300 rows at 1 kHz, then one a million seconds later: a grid of 10^9
        // samples would be filled; the reader names the span instead.
        let ok = |k: usize| format!("{},{},0,1\n", k as f64 * 1e-3, k as f64 * 1e-4);
        let text = format!("t,q_j,qd_j,tau_j\n{}1000000,0.03,0,1\n", rows(300, ok));
        let e = read_csv_str::<1>(&text, &["j"], "a.csv").unwrap_err();
        assert!(matches!(e, DataError::GridTooLong { rows: 301, .. }), "{e}");
        assert!(
            e.to_string()
                .starts_with("a.csv: the samples span 1000000 s at an interval of 0.001"),
            "{e}"
        );
    }
}
