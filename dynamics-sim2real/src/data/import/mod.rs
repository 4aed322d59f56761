//! Recorded files in other layouts than our CSV, read as recorded and named
//! by a [`ColumnMap`]:
//!
//! - a text matrix (one sample a line; commas, semicolons, tabs or spaces);
//! - a directory of text files, one per quantity (`t=time.txt,q=pos.txt,...`);
//!   a file of one column holding `N` values per sample one after the other
//!   (sample-major, as MATLAB's `dlmwrite(f, X(:))` of an `N x samples`
//!   matrix writes them) is read as `N` columns;
//! - a NumPy `.npz` archive (`t=times,q=positions,...`) or one `.npy` array.
//!
//! Files: `map.rs` (the column map), `text.rs`, `npy.rs`, `zip.rs` (the
//! formats), `table.rs` (what each of them yields), `error.rs`.

mod error;
mod map;
mod npy;
mod table;
mod text;
mod zip;

pub use error::ImportError;
pub use map::{ColumnMap, Source};

use std::collections::BTreeMap;
use std::path::Path;

use nalgebra::SVector;

use super::{differentiate, Measured};
use crate::Warning;
use table::Table;

/// Fewest samples a record must hold (as for the CSV reader).
pub const MIN_SAMPLES: usize = 200;

/// Reads the record at `path` (a text file, a `.npz` or `.npy` file, or a
/// directory of text files) for a robot with joints `joints`, its parts
/// named by `map`, keeping the samples whose time from the first sample
/// lies in `window` (s, start inclusive, end exclusive) when given.
///
/// Times are counted from the record's first sample (a clock since an epoch
/// becomes seconds from the start; a warning says so).
///
/// ```
/// use dynamics_sim2real::data::import::{import, ColumnMap};
/// let path = std::env::temp_dir().join("dynamics-doc-import.txt");
/// let mut text = String::from("% t q tau\n");
/// for k in 0..400 { text.push_str(&format!("{} {} 0.5\n", 100.0 + k as f64 * 1e-3, k as f64 * 2e-3)); }
/// std::fs::write(&path, text).unwrap();
/// let map: ColumnMap = "t=:1,q=:2,tau=:3".parse().unwrap();
/// let m = import(&path, &map, &["j"], Some((0.0995, 0.3995))).unwrap();
/// assert_eq!(m.len(), 300);
/// assert!((m.t[0] - 0.1).abs() < 1e-9 && (m.qd[10][0] - 2.0).abs() < 1e-9);
/// ```
pub fn import<const N: usize>(
    path: &Path,
    map: &ColumnMap,
    joints: &[&str; N],
    window: Option<(f64, f64)>,
) -> Result<Measured<N>, ImportError> {
    let file = path.display().to_string();
    let mut warnings = Vec::new();
    let sources = Sources::open(path, &file, &mut warnings)?;
    import_from(sources, file, warnings, map, joints, window)
}

/// [`import`] of the bytes of one file named `file` (a text matrix, a
/// `.npz` or a `.npy`; what the fuzz target reads).
///
/// ```
/// use dynamics_sim2real::data::import::{import_bytes, ColumnMap};
/// let text: String = (0..300).map(|k| format!("{} {} 0.5\n", k as f64 * 1e-3, k as f64 * 2e-3)).collect();
/// let map: ColumnMap = "t=:1,q=:2,tau=:3".parse().unwrap();
/// let m = import_bytes(text.as_bytes(), "m.txt", &map, &["j"], None).unwrap();
/// assert_eq!(m.len(), 300);
/// assert!(import_bytes(b"PK\x03\x04 broken", "m.npz", &map, &["j"], None).is_err());
/// ```
pub fn import_bytes<const N: usize>(
    bytes: &[u8],
    file: &str,
    map: &ColumnMap,
    joints: &[&str; N],
    window: Option<(f64, f64)>,
) -> Result<Measured<N>, ImportError> {
    let mut warnings = Vec::new();
    let sources = Sources::from_bytes(bytes, file, &mut warnings)?;
    import_from(sources, file.to_string(), warnings, map, joints, window)
}

/// The record of `sources` (named `file`), as [`import`] says.
fn import_from<const N: usize>(
    mut sources: Sources,
    file: String,
    mut warnings: Vec<String>,
    map: &ColumnMap,
    joints: &[&str; N],
    window: Option<(f64, f64)>,
) -> Result<Measured<N>, ImportError> {
    let t = sources.column(&map.t, "t", 1, None)?;
    let n = t.rows;
    let q = sources.column(&map.q, "q", N, Some(n))?;
    let tau = sources.column(&map.tau, "tau", N, Some(n))?;
    let qd = match &map.qd {
        Some(s) => Some(sources.column(s, "qd", N, Some(n))?),
        None => None,
    };
    warnings.append(&mut sources.warnings);
    let t0 = t.get(0, 0);
    if t0 != 0.0 {
        warnings.push(format!(
            "{file}: times counted from the first sample (the recorded clock reads {t0} s there)"
        ));
    }
    let mut m = Measured::<N> {
        qd_measured: qd.is_some(),
        warnings: warnings
            .into_iter()
            .map(|message| Warning::Imported { message })
            .collect(),
        ..Default::default()
    };
    for k in 0..n {
        let time = t.get(k, 0) - t0;
        finite(&t, k, 0, "t", "")?;
        if let Some(&previous) = m.t.last() {
            if time <= previous {
                return Err(ImportError::TimeNotIncreasing {
                    place: t.place(k),
                    t: t.get(k, 0),
                    previous: previous + t0,
                });
            }
        }
        let vec = |table: &Table, quantity: &'static str| -> Result<SVector<f64, N>, ImportError> {
            let mut v = SVector::zeros();
            for (i, joint) in joints.iter().enumerate() {
                v[i] = finite(table, k, i, quantity, joint)?;
            }
            Ok(v)
        };
        m.t.push(time);
        m.q.push(vec(&q, "q")?);
        m.tau.push(vec(&tau, "tau")?);
        if let Some(qd) = &qd {
            m.qd.push(vec(qd, "qd")?);
        }
    }
    if !m.qd_measured && m.len() > 1 {
        m.qd = differentiate(&m.t, &m.q);
    }
    if let Some((start, end)) = window {
        m = m.window(start, end);
    }
    if m.len() < MIN_SAMPLES {
        return Err(ImportError::TooFewSamples {
            file,
            rows: m.len(),
            window: window
                .map(|(a, b)| format!(" in the window {a}..{b} s"))
                .unwrap_or_default(),
            min: MIN_SAMPLES,
        });
    }
    Ok(m)
}

/// The value at `row`, `col`, refused if not finite.
fn finite(
    table: &Table,
    row: usize,
    col: usize,
    quantity: &'static str,
    joint: &str,
) -> Result<f64, ImportError> {
    let value = table.get(row, col);
    if value.is_finite() {
        Ok(value)
    } else {
        Err(ImportError::NotFinite {
            place: table.place(row),
            quantity,
            joint: joint.to_string(),
            value,
        })
    }
}

/// The tables of a record, each read once.
struct Sources {
    file: String,
    kind: Kind,
    tables: BTreeMap<String, Table>,
    warnings: Vec<String>,
}

/// What the data path is.
enum Kind {
    /// One text or `.npy` file: its table is under the empty name.
    Single,
    /// A directory of text files.
    Directory(std::path::PathBuf),
    /// A `.npz`: every array, read up front (names without `.npy`).
    Archive,
}

fn read_bytes(path: &Path) -> Result<Vec<u8>, ImportError> {
    std::fs::read(path).map_err(|source| ImportError::Io {
        file: path.display().to_string(),
        source,
    })
}

/// A text file's table.
fn read_text(path: &Path, warnings: &mut Vec<String>) -> Result<Table, ImportError> {
    let file = path.display().to_string();
    let bytes = read_bytes(path)?;
    let text = String::from_utf8(bytes).map_err(|e| ImportError::Io {
        file: file.clone(),
        source: std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!("not UTF-8 text ({e})"),
        ),
    })?;
    text::parse(&text, &file, warnings)
}

impl Sources {
    fn open(path: &Path, file: &str, warnings: &mut Vec<String>) -> Result<Self, ImportError> {
        if path.is_dir() {
            return Ok(Sources {
                file: file.to_string(),
                kind: Kind::Directory(path.to_path_buf()),
                tables: BTreeMap::new(),
                warnings: Vec::new(),
            });
        }
        Self::from_bytes(&read_bytes(path)?, file, warnings)
    }

    /// The tables of one file's bytes.
    fn from_bytes(
        bytes: &[u8],
        file: &str,
        warnings: &mut Vec<String>,
    ) -> Result<Self, ImportError> {
        let mut tables = BTreeMap::new();
        let npy_err = |array: &str, message: String| ImportError::Npy {
            file: file.to_string(),
            array: array.to_string(),
            message,
        };
        let kind = if bytes.starts_with(b"PK") {
            let entries = zip::entries(bytes).map_err(|message| ImportError::Zip {
                file: file.to_string(),
                message,
            })?;
            for (name, data) in entries {
                let name = name.strip_suffix(".npy").unwrap_or(&name).to_string();
                let table =
                    npy::parse(&data, &format!("{file}:{name}")).map_err(|m| npy_err(&name, m))?;
                tables.insert(name, table);
            }
            Kind::Archive
        } else if bytes.starts_with(b"\x93NUMPY") {
            tables.insert(
                String::new(),
                npy::parse(bytes, file).map_err(|m| npy_err("", m))?,
            );
            Kind::Single
        } else {
            let text = std::str::from_utf8(bytes).map_err(|e| ImportError::Io {
                file: file.to_string(),
                source: std::io::Error::new(
                    std::io::ErrorKind::InvalidData,
                    format!("not UTF-8 text ({e})"),
                ),
            })?;
            tables.insert(String::new(), text::parse(text, file, warnings)?);
            Kind::Single
        };
        Ok(Sources {
            file: file.to_string(),
            kind,
            tables,
            warnings: Vec::new(),
        })
    }

    /// The table `entry` names.
    fn table(&mut self, entry: &str) -> Result<&Table, ImportError> {
        let missing = |what: &'static str, available: Vec<String>| ImportError::Missing {
            file: self.file.clone(),
            what,
            name: entry.to_string(),
            available: if available.is_empty() {
                "nothing".into()
            } else {
                available.join(", ")
            },
        };
        match &self.kind {
            Kind::Single if !entry.is_empty() => {
                return Err(ImportError::Map {
                    map: entry.to_string(),
                    message: format!(
                        "{} is one file, not a directory or .npz: give columns only (`t=:1`)",
                        self.file
                    ),
                })
            }
            Kind::Archive => {
                let key = entry.strip_suffix(".npy").unwrap_or(entry);
                if !self.tables.contains_key(key) {
                    return Err(missing("array", self.tables.keys().cloned().collect()));
                }
                return Ok(&self.tables[key]);
            }
            Kind::Directory(dir) => {
                if !self.tables.contains_key(entry) {
                    let path = dir.join(entry);
                    if entry.is_empty() || !path.is_file() {
                        let mut names: Vec<String> = std::fs::read_dir(dir)
                            .map(|d| {
                                d.filter_map(|e| e.ok())
                                    .filter(|e| e.path().is_file())
                                    .map(|e| e.file_name().to_string_lossy().into_owned())
                                    .collect()
                            })
                            .unwrap_or_default();
                        names.sort();
                        return Err(missing("file", names));
                    }
                    let table = read_text(&path, &mut self.warnings)?;
                    self.tables.insert(entry.to_string(), table);
                }
            }
            Kind::Single => {}
        }
        Ok(&self.tables[entry])
    }

    /// The `width` columns `source` names, scaled, as a table of `samples`
    /// rows when known (a one-column source of `width * samples` values is
    /// read sample-major).
    fn column(
        &mut self,
        source: &Source,
        quantity: &str,
        width: usize,
        samples: Option<usize>,
    ) -> Result<Table, ImportError> {
        let table = self.table(&source.entry)?.clone();
        let shape = |message: String| ImportError::Shape {
            source_name: table.source.clone(),
            message,
        };
        let (first, count) = match source.columns {
            Some((a, b)) => {
                if b > table.cols {
                    return Err(shape(format!(
                        "columns {a}-{b} asked for, the source has {}",
                        table.cols
                    )));
                }
                (a - 1, b - a + 1)
            }
            None => (0, table.cols),
        };
        let mut out = Table {
            source: table.source.clone(),
            rows: table.rows,
            cols: width,
            values: Vec::with_capacity(table.rows * width),
            lines: table.lines.clone(),
        };
        if count == width {
            for r in 0..table.rows {
                for c in first..first + width {
                    out.values.push(table.get(r, c) * source.scale);
                }
            }
        } else if count == 1 && width > 1 && samples.map(|n| n * width) == Some(table.rows) {
            // One column, `width` values per sample one after the other.
            out.rows = table.rows / width;
            out.values = (0..table.rows)
                .map(|r| table.get(r, first) * source.scale)
                .collect();
            out.lines = table.lines.iter().step_by(width).copied().collect();
            self.warnings.push(format!(
                "{}: one column of {} values read as {} samples x {width} joints (sample after sample)",
                table.source, table.rows, out.rows
            ));
        } else {
            let need = if quantity == "t" {
                "the time needs 1 column".to_string()
            } else {
                format!("`{quantity}` needs {width} (one column per joint)")
            };
            return Err(shape(format!(
                "{} rows x {count} columns; {need}{}",
                table.rows,
                if source.columns.is_none() && count > width {
                    ": say which (`:A-B`)"
                } else {
                    ""
                }
            )));
        }
        if let Some(n) = samples {
            if out.rows != n {
                return Err(shape(format!("{} samples, the time has {n}", out.rows)));
            }
        }
        Ok(out)
    }
}
