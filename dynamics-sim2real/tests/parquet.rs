//! A Parquet file written by pyarrow (snappy pages, row groups of 128 rows,
//! the columns in another order than ours and one more:
//! scripts/make-bag-fixtures.py) read back to the very numbers of the same
//! data as our CSV.
#![cfg(feature = "parquet")]

use std::path::{Path, PathBuf};

use dynamics_sim2real::data::parquet::{read_parquet, read_parquet_bytes};
use dynamics_sim2real::data::read_csv;
use dynamics_sim2real::Warning;

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/bags")
        .join(name)
}

#[test]
fn pyarrows_parquet_reads_the_csvs_numbers() {
    let joints = ["j1", "j2", "j3"];
    let m = read_parquet(&data("motion.parquet"), &joints).expect("the Parquet file");
    let truth = read_csv(&data("motion.csv.gz"), &joints).expect("the CSV twin");
    assert_eq!(m.t, truth.t);
    assert_eq!(m.q, truth.q);
    assert_eq!(m.qd, truth.qd);
    assert_eq!(m.tau, truth.tau);
    assert!(m.qd_measured);
    assert_eq!(
        m.warnings,
        vec![Warning::ColumnIgnored {
            file: data("motion.parquet").display().to_string(),
            column: "temperature_j1".into()
        }]
    );
    // A joint the file does not have is named as for a CSV.
    let e = read_parquet(&data("motion.parquet"), &["j1", "j2", "elbow"]).unwrap_err();
    assert!(e.to_string().contains("no column `q_elbow`"), "{e}");
    // Cut short: the footer is missing.
    let bytes = std::fs::read(data("motion.parquet")).unwrap();
    let e =
        read_parquet_bytes(bytes[..bytes.len() / 2].to_vec(), &joints, "cut.parquet").unwrap_err();
    assert!(e.to_string().starts_with("cut.parquet: "), "{e}");
}

/// A file written here: `t` required, the positions FLOAT and optional,
/// the efforts optional DOUBLE, in two row groups, with an INT64 column
/// `step` or without it.
fn written(with_step: bool, null_at: Option<usize>) -> Vec<u8> {
    use parquet::basic::{Repetition, Type as Physical};
    use parquet::data_type::{DoubleType, FloatType, Int64Type};
    use parquet::file::properties::WriterProperties;
    use parquet::file::writer::SerializedFileWriter;
    use parquet::schema::types::Type;
    use std::sync::Arc;
    let field = |name: &str, ty, rep| {
        Arc::new(
            Type::primitive_type_builder(name, ty)
                .with_repetition(rep)
                .build()
                .expect("writes"),
        )
    };
    let mut fields = vec![
        field("t", Physical::DOUBLE, Repetition::REQUIRED),
        field("q_j", Physical::FLOAT, Repetition::OPTIONAL),
        field("tau_j", Physical::DOUBLE, Repetition::OPTIONAL),
    ];
    if with_step {
        fields.push(field("step", Physical::INT64, Repetition::REQUIRED));
    }
    let schema = Arc::new(
        Type::group_type_builder("m")
            .with_fields(fields)
            .build()
            .expect("writes"),
    );
    let mut out = Vec::new();
    let props = Arc::new(WriterProperties::builder().build());
    let mut writer = SerializedFileWriter::new(&mut out, schema, props).expect("writes");
    for rows in [0..150usize, 150..300] {
        let mut group = writer.next_row_group().expect("writes");
        let mut c = 0;
        while let Some(mut column) = group.next_column().expect("writes") {
            let defs: Vec<i16> = rows
                .clone()
                .map(|k| i16::from(Some(k) != null_at))
                .collect();
            let kept = rows.clone().filter(|&k| Some(k) != null_at);
            match c {
                0 => {
                    let t: Vec<f64> = rows.clone().map(|k| k as f64 * 1e-3).collect();
                    column
                        .typed::<DoubleType>()
                        .write_batch(&t, None, None)
                        .expect("writes");
                }
                1 => {
                    let q: Vec<f32> = kept.map(|k| (k as f32 * 0.01).sin()).collect();
                    column
                        .typed::<FloatType>()
                        .write_batch(&q, Some(&defs), None)
                        .expect("writes");
                }
                2 => {
                    let tau: Vec<f64> = kept.map(|k| 1.0 + (k as f64 * 0.02).cos()).collect();
                    column
                        .typed::<DoubleType>()
                        .write_batch(&tau, Some(&defs), None)
                        .expect("writes");
                }
                _ => {
                    let step: Vec<i64> = rows.clone().map(|k| k as i64).collect();
                    column
                        .typed::<Int64Type>()
                        .write_batch(&step, None, None)
                        .expect("writes");
                }
            }
            column.close().expect("writes");
            c += 1;
        }
        group.close().expect("writes");
    }
    writer.close().expect("writes");
    out
}

/// A file of numbers alone (read a column at a time) gives the numbers of
/// the same file with one more column of another type (read row by row),
/// across row groups, FLOAT widened as the row reader widens it; a null
/// is named at its row's line either way.
#[test]
fn a_file_of_numbers_reads_as_the_row_reader_reads_it() {
    let joints = ["j"];
    let fast = read_parquet_bytes(written(false, None), &joints, "a.parquet").unwrap();
    let rows = read_parquet_bytes(written(true, None), &joints, "b.parquet").unwrap();
    assert_eq!(fast.t.len(), 300);
    assert_eq!((&fast.t, &fast.q, &fast.tau), (&rows.t, &rows.q, &rows.tau));
    assert_eq!(fast.q[200][0], f64::from((200f32 * 0.01).sin()));
    for with_step in [false, true] {
        let e = read_parquet_bytes(written(with_step, Some(170)), &joints, "n.parquet")
            .unwrap_err()
            .to_string();
        assert!(e.contains("172") && e.contains("null"), "{e}");
    }
}
