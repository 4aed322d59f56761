//! Parquet files with the CSV's columns (`t`, `q_<joint>`, `qd_<joint>`,
//! `tau_<joint>`, matched by name, other columns ignored with a warning),
//! read and written through the `parquet` crate (without Arrow; snappy and
//! zstd pages) under the cargo feature `parquet`. The rows then go through
//! the CSV reader's checks and [`prepare`](crate::data::prepare); a row's
//! place is given as the line it would have in the CSV of the same data
//! (row `k`, from 0, on line `k + 2`).

use std::path::Path;

use super::bag::BagError;
use super::Measured;

/// Reads the Parquet file at `path` for a robot with joints `joints`.
///
/// ```
/// # #[cfg(feature = "parquet")] {
/// use dynamics_sim2real::data::parquet::{read_parquet, write_parquet};
/// use dynamics_sim2real::data::Measured;
/// let m = Measured::<1> {
///     t: (0..300).map(|k| k as f64 * 1e-3).collect(),
///     q: (0..300).map(|k| [k as f64 * 1e-3].into()).collect(),
///     tau: vec![[1.5].into(); 300],
///     ..Default::default()
/// };
/// let path = std::env::temp_dir().join("dynamics-doc-read.parquet");
/// write_parquet(std::fs::File::create(&path).unwrap(), &m, &["j"]).unwrap();
/// let back = read_parquet(&path, &["j"]).unwrap();
/// assert_eq!((back.t, back.q, back.tau), (m.t, m.q, m.tau));
/// assert!(!back.qd_measured && (back.qd[100][0] - 1.0).abs() < 1e-9);
/// # }
/// ```
pub fn read_parquet<const N: usize>(
    path: &Path,
    joints: &[&str; N],
) -> Result<Measured<N>, BagError> {
    let file = path.display().to_string();
    let io = |source| BagError::Io {
        file: file.clone(),
        source,
    };
    // Read from the file page by page, not copied into memory whole.
    let source = std::fs::File::open(path).map_err(io)?;
    let size = source.metadata().map_err(io)?.len();
    #[cfg(feature = "parquet")]
    {
        guarded(|| imp::read(source, size, joints, &file), &file)
    }
    #[cfg(not(feature = "parquet"))]
    {
        let _ = (source, size, joints);
        Err(BagError::NotBuilt {
            file,
            format: "Parquet",
            feature: "parquet",
        })
    }
}

/// Whether `path` is named `.parquet` or starts with Parquet's magic bytes.
///
/// ```
/// assert!(dynamics_sim2real::data::parquet::is_parquet(std::path::Path::new("run.parquet")));
/// ```
pub fn is_parquet(path: &Path) -> bool {
    if path.extension().and_then(|e| e.to_str()) == Some("parquet") {
        return true;
    }
    use std::io::Read;
    let mut head = [0u8; 4];
    std::fs::File::open(path)
        .and_then(|mut f| f.read_exact(&mut head))
        .map(|_| &head == b"PAR1")
        .unwrap_or(false)
}

#[cfg(feature = "parquet")]
mod imp {
    use std::sync::Arc;

    use parquet::basic::{Compression, Repetition, Type as PhysicalType};
    use parquet::data_type::DoubleType;
    use parquet::file::properties::WriterProperties;
    use parquet::file::reader::{ChunkReader, FileReader, SerializedFileReader};
    use parquet::file::writer::SerializedFileWriter;
    use parquet::record::Field;
    use parquet::schema::types::Type;

    use super::super::read::{read_rows, Row};
    use super::super::Measured;
    use crate::data::bag::BagError;

    /// One row: its numbers (or what a cell holds instead) and its line.
    struct ParquetRow {
        cells: Vec<Result<f64, String>>,
        line: usize,
    }

    impl Row for ParquetRow {
        fn len(&self) -> usize {
            self.cells.len()
        }
        fn line(&self) -> usize {
            self.line
        }
        fn cell(&self, c: usize) -> Result<f64, String> {
            match self.cells.get(c) {
                Some(Ok(v)) if v.is_finite() => Ok(*v),
                Some(Ok(v)) => Err(v.to_string()),
                Some(Err(e)) => Err(e.clone()),
                None => Err(String::new()),
            }
        }
    }

    fn number(field: &Field) -> Result<f64, String> {
        Ok(match field {
            Field::Double(v) => *v,
            Field::Float(v) => f64::from(*v),
            Field::Byte(v) => f64::from(*v),
            Field::Short(v) => f64::from(*v),
            Field::Int(v) => f64::from(*v),
            Field::Long(v) => *v as f64,
            Field::UByte(v) => f64::from(*v),
            Field::UShort(v) => f64::from(*v),
            Field::UInt(v) => f64::from(*v),
            Field::ULong(v) => *v as f64,
            Field::Null => return Err("null".into()),
            other => return Err(format!("{other}")),
        })
    }

    /// The file `file` of `size` bytes, read from `source`.
    pub(super) fn read<const N: usize, C: ChunkReader + 'static>(
        source: C,
        size: u64,
        joints: &[&str; N],
        file: &str,
    ) -> Result<Measured<N>, BagError> {
        let err = |e: parquet::errors::ParquetError| BagError::Parquet {
            file: file.to_string(),
            message: e.to_string(),
        };
        let size = i64::try_from(size).unwrap_or(i64::MAX);
        let reader = SerializedFileReader::new(source).map_err(err)?;
        // Every column chunk inside the file: the crate asserts (panics on)
        // a negative offset or length in the footer it has just parsed.
        for (g, group) in reader.metadata().row_groups().iter().enumerate() {
            for col in group.columns() {
                let start = col
                    .dictionary_page_offset()
                    .unwrap_or(col.data_page_offset());
                let len = col.compressed_size();
                if start < 0 || len < 0 || start.checked_add(len).is_none_or(|end| end > size) {
                    return Err(BagError::Parquet {
                        file: file.to_string(),
                        message: format!(
                            "row group {g}, column `{}`: its chunk ({len} bytes at {start}) lies outside the file ({size} bytes)",
                            col.column_path()
                        ),
                    });
                }
            }
        }
        let header: Vec<String> = reader
            .metadata()
            .file_metadata()
            .schema()
            .get_fields()
            .iter()
            .map(|f| f.name().to_string())
            .collect();
        if let Some(columns) = columns_of_numbers(&reader).map_err(err)? {
            // The cells straight from the columns' values, row by row (the
            // columns dropped with the rows, once read).
            drop(reader);
            let rows = (0..columns.first().map_or(0, |c| c.values.len())).map(move |k| {
                Ok(ParquetRow {
                    cells: columns.iter().map(|c| c.cell(k)).collect(),
                    line: k + 2,
                })
            });
            return Ok(read_rows(&header, rows, joints, file)?);
        }
        let rows = reader.get_row_iter(None).map_err(err)?;
        let rows = rows.enumerate().map(|(k, row)| {
            let row = row.map_err(|e| crate::data::DataError::Csv {
                file: file.to_string(),
                message: format!("Parquet row {}: {e}", k + 1),
            })?;
            Ok(ParquetRow {
                cells: row.get_column_iter().map(|(_, f)| number(f)).collect(),
                line: k + 2,
            })
        });
        Ok(read_rows(&header, rows, joints, file)?)
    }

    /// One column of numbers read whole: its values, each row's (NaN in
    /// a null's place), and which rows are null (none when the column is
    /// required).
    struct Numbers {
        values: Vec<f64>,
        nulls: Option<Vec<bool>>,
    }

    impl Numbers {
        /// Row `k`'s cell as the record reader gives it ([`number`]).
        fn cell(&self, k: usize) -> Result<f64, String> {
            match (&self.nulls, self.values.get(k)) {
                (Some(nulls), _) if nulls.get(k).copied().unwrap_or(true) => Err("null".into()),
                (_, Some(v)) => Ok(*v),
                (_, None) => Err("null".into()),
            }
        }
    }

    /// Every column of a flat file whose columns are all DOUBLE or FLOAT
    /// (required or optional, no logical type), read a column at a time:
    /// the values the record reader gives row by row, at a small part of
    /// its cost (it builds every row's named fields). `None` for any other
    /// schema, which is read row by row.
    fn columns_of_numbers(
        reader: &SerializedFileReader<impl ChunkReader + 'static>,
    ) -> parquet::errors::Result<Option<Vec<Numbers>>> {
        use parquet::column::reader::ColumnReader;
        let meta = reader.metadata();
        let schema = meta.file_metadata().schema_descr();
        let flat = schema.root_schema().get_fields().len() == schema.num_columns();
        let numbers = schema.columns().iter().all(|c| {
            matches!(
                c.physical_type(),
                PhysicalType::DOUBLE | PhysicalType::FLOAT
            ) && c.max_rep_level() == 0
                && c.max_def_level() <= 1
                && c.logical_type_ref().is_none()
        });
        if !flat || !numbers {
            return Ok(None);
        }
        let rows: usize = meta
            .row_groups()
            .iter()
            .map(|g| usize::try_from(g.num_rows()).unwrap_or(0))
            .sum();
        let mut columns: Vec<Numbers> = schema
            .columns()
            .iter()
            .map(|c| Numbers {
                values: Vec::with_capacity(rows),
                nulls: (c.max_def_level() == 1).then(|| Vec::with_capacity(rows)),
            })
            .collect();
        const BATCH: usize = 1 << 16;
        // Rows of the groups read so far.
        let mut done = 0;
        for g in 0..meta.num_row_groups() {
            let group = reader.get_row_group(g)?;
            done += usize::try_from(group.metadata().num_rows()).unwrap_or(0);
            for (c, column) in columns.iter_mut().enumerate() {
                let nullable = column.nulls.is_some();
                let mut defs: Vec<i16> = Vec::new();
                let mut present: Vec<f64> = Vec::new();
                match group.get_column_reader(c)? {
                    ColumnReader::DoubleColumnReader(mut r) => {
                        let defs = &mut defs;
                        while r
                            .read_records(
                                BATCH,
                                nullable.then_some(&mut *defs),
                                None,
                                &mut present,
                            )?
                            .0
                            > 0
                        {}
                    }
                    ColumnReader::FloatColumnReader(mut r) => {
                        let (defs, mut floats) = (&mut defs, Vec::<f32>::new());
                        while r
                            .read_records(BATCH, nullable.then_some(&mut *defs), None, &mut floats)?
                            .0
                            > 0
                        {}
                        present.extend(floats.into_iter().map(f64::from));
                    }
                    _ => return Ok(None),
                }
                match &mut column.nulls {
                    None => column.values.extend(present),
                    Some(nulls) => {
                        let mut values = present.into_iter();
                        for d in &defs {
                            let null = *d < 1;
                            nulls.push(null);
                            let v = if null { None } else { values.next() };
                            column.values.push(v.unwrap_or(f64::NAN));
                        }
                    }
                }
                // A column whose values do not fill its rows: read row by
                // row, which says where.
                if column.values.len() != done {
                    return Ok(None);
                }
            }
        }
        Ok(Some(columns))
    }

    pub(super) fn write(
        out: impl std::io::Write + Send,
        header: &[String],
        columns: &[Vec<f64>],
    ) -> Result<(), parquet::errors::ParquetError> {
        let fields = header
            .iter()
            .map(|name| {
                Type::primitive_type_builder(name, PhysicalType::DOUBLE)
                    .with_repetition(Repetition::REQUIRED)
                    .build()
                    .map(Arc::new)
            })
            .collect::<Result<Vec<_>, _>>()?;
        let schema = Arc::new(
            Type::group_type_builder("measured")
                .with_fields(fields)
                .build()?,
        );
        let props = Arc::new(
            WriterProperties::builder()
                .set_compression(Compression::SNAPPY)
                .build(),
        );
        let mut writer = SerializedFileWriter::new(out, schema, props)?;
        let mut group = writer.next_row_group()?;
        let mut k = 0;
        while let Some(mut column) = group.next_column()? {
            let values = columns.get(k).map(Vec::as_slice).unwrap_or(&[]);
            column
                .typed::<DoubleType>()
                .write_batch(values, None, None)?;
            column.close()?;
            k += 1;
        }
        group.close()?;
        writer.close()?;
        Ok(())
    }
}

/// [`read_parquet`] of the bytes of a file named `file` (what the fuzz
/// target reads).
///
/// ```
/// use dynamics_sim2real::data::parquet::read_parquet_bytes;
/// assert!(read_parquet_bytes::<1>(b"PAR1 not really".to_vec(), &["j"], "x.parquet").is_err());
/// ```
pub fn read_parquet_bytes<const N: usize>(
    bytes: Vec<u8>,
    joints: &[&str; N],
    file: &str,
) -> Result<Measured<N>, BagError> {
    #[cfg(feature = "parquet")]
    {
        let size = bytes.len() as u64;
        guarded(
            || imp::read(bytes::Bytes::from(bytes), size, joints, file),
            file,
        )
    }
    #[cfg(not(feature = "parquet"))]
    {
        let _ = (bytes, joints);
        Err(BagError::NotBuilt {
            file: file.to_string(),
            format: "Parquet",
            feature: "parquet",
        })
    }
}

/// `read`, a panic of the `parquet` crate on some malformed pages (an
/// index out of bounds in its byte-stream-split decoder, found by fuzzing)
/// told as an error of `file`: a hostile file is an error here, never a
/// crash.
#[cfg(feature = "parquet")]
fn guarded<const N: usize>(
    read: impl FnOnce() -> Result<Measured<N>, BagError>,
    file: &str,
) -> Result<Measured<N>, BagError> {
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(read)).unwrap_or_else(|_| {
        Err(BagError::Parquet {
            file: file.to_string(),
            message: "malformed data: the Parquet decoder failed on a page".into(),
        })
    })
}

/// Writes columns of numbers, each named by `header`, as one row group of
/// required DOUBLE columns, snappy-compressed.
///
/// ```
/// # #[cfg(feature = "parquet")] {
/// use dynamics_sim2real::data::parquet::{read_parquet_bytes, write_parquet_table};
/// let header = ["t", "q_j", "tau_j"].map(String::from);
/// let t: Vec<f64> = (0..250).map(|k| k as f64 * 0.01).collect();
/// let columns = [t.clone(), t.iter().map(|x| x.sin()).collect(), vec![2.0; 250]];
/// let mut out = Vec::new();
/// write_parquet_table(&mut out, &header, &columns).unwrap();
/// let m = read_parquet_bytes(out, &["j"], "x.parquet").unwrap();
/// assert_eq!(m.t, t);
/// # }
/// ```
pub fn write_parquet_table(
    out: impl std::io::Write + Send,
    header: &[String],
    columns: &[Vec<f64>],
) -> Result<(), BagError> {
    #[cfg(feature = "parquet")]
    {
        imp::write(out, header, columns).map_err(|e| BagError::Parquet {
            file: "the Parquet output".into(),
            message: e.to_string(),
        })
    }
    #[cfg(not(feature = "parquet"))]
    {
        let _ = (out, header, columns);
        Err(BagError::NotBuilt {
            file: "the Parquet output".into(),
            format: "Parquet",
            feature: "parquet",
        })
    }
}

/// Writes `m` as Parquet with the CSV's columns ([`crate::data::write_csv`]'s:
/// `t`, `q_<joint>`, `qd_<joint>` when measured, `tau_<joint>`).
///
/// ```
/// # #[cfg(feature = "parquet")] {
/// use dynamics_sim2real::data::parquet::{read_parquet_bytes, write_parquet};
/// use dynamics_sim2real::data::Measured;
/// let m = Measured::<1> {
///     t: (0..300).map(|k| k as f64 * 1e-3).collect(),
///     q: vec![[0.25].into(); 300],
///     qd: vec![[0.0].into(); 300],
///     tau: vec![[1.5].into(); 300],
///     qd_measured: true,
///     ..Default::default()
/// };
/// let mut out = Vec::new();
/// write_parquet(&mut out, &m, &["j"]).unwrap();
/// let back = read_parquet_bytes(out, &["j"], "m.parquet").unwrap();
/// assert_eq!((back.t, back.q, back.qd, back.tau), (m.t, m.q, m.qd, m.tau));
/// # }
/// ```
pub fn write_parquet<const N: usize>(
    out: impl std::io::Write + Send,
    m: &Measured<N>,
    joints: &[&str; N],
) -> Result<(), BagError> {
    let mut header = vec!["t".to_string()];
    let mut columns = vec![m.t.clone()];
    let mut quantities: Vec<(&str, &Vec<nalgebra::SVector<f64, N>>)> = vec![("q", &m.q)];
    if m.qd_measured {
        quantities.push(("qd", &m.qd));
    }
    quantities.push(("tau", &m.tau));
    for (prefix, values) in quantities {
        for (i, j) in joints.iter().enumerate() {
            header.push(format!("{prefix}_{j}"));
            columns.push(values.iter().map(|v| v[i]).collect());
        }
    }
    write_parquet_table(out, &header, &columns)
}
