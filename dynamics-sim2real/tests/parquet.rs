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
