//! The fuzz targets' seeds (fuzz/seeds/, and the fixtures the fuzz runs
//! start from: tests/data/) fed to every reader, whole, cut at 16 places
//! and with bytes flipped at 16 places: each reader answers with samples or
//! an error, never a panic (the fuzz targets' property, run in CI over a
//! fixed set of inputs; fuzz/README.md runs them for millions).

use std::path::{Path, PathBuf};

use dynamics_sim2real::data::import::{import_bytes, ColumnMap};
use dynamics_sim2real::data::read_csv_bytes;

const ARM: [&str; 3] = ["j1", "j2", "j3"];

fn files() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut out = Vec::new();
    let mut dirs = vec![
        root.join("tests/data"),
        root.join("../fuzz/seeds/csv"),
        root.join("../fuzz/seeds/npz"),
        // Inputs the fuzz targets found harmful once (each a regression test).
        root.join("../fuzz/seeds/mcap"),
        root.join("../fuzz/seeds/parquet"),
    ];
    while let Some(dir) = dirs.pop() {
        for entry in std::fs::read_dir(&dir).expect("a seed directory") {
            let path = entry.expect("an entry").path();
            if path.is_dir() {
                dirs.push(path);
            } else if path.extension().and_then(|e| e.to_str()) != Some("md") {
                out.push(path);
            }
        }
    }
    out.sort();
    out
}

/// The inputs made of `bytes`: whole, cut, with a byte flipped.
fn variants(bytes: &[u8]) -> Vec<Vec<u8>> {
    let mut out = vec![bytes.to_vec()];
    for k in 1..=16 {
        let at = bytes.len() * k / 17;
        out.push(bytes[..at].to_vec());
        let mut flipped = bytes.to_vec();
        if let Some(b) = flipped.get_mut(at) {
            *b ^= 0x5a;
        }
        out.push(flipped);
    }
    out
}

fn every_reader(bytes: &[u8]) {
    let _ = read_csv_bytes(bytes, &ARM, "x.csv");
    let archive: ColumnMap = "t=times,q=positions,qd=velocities,tau=torques"
        .parse()
        .expect("a map");
    let single: ColumnMap = "t=:1,q=:2-3,tau=:4-5".parse().expect("a map");
    let _ = import_bytes(bytes, "x.npz", &archive, &["a", "b"], None);
    let _ = import_bytes(bytes, "x.txt", &single, &["a", "b"], None);
    #[cfg(feature = "rosbag")]
    {
        let _ =
            dynamics_sim2real::data::bag::read_mcap_bytes(bytes, &ARM, "/joint_states", "x.mcap");
    }
    #[cfg(feature = "parquet")]
    {
        let _ =
            dynamics_sim2real::data::parquet::read_parquet_bytes(bytes.to_vec(), &ARM, "x.parquet");
    }
}

#[test]
fn every_reader_answers_every_seed_whole_cut_and_flipped() {
    let files = files();
    assert!(files.len() >= 20, "{files:?}");
    for path in &files {
        let bytes = std::fs::read(path).expect("a seed");
        for input in variants(&bytes) {
            every_reader(&input);
        }
    }
}

/// SQLite reads files: the sqlite3 fixtures, cut and flipped, as files.
#[cfg(feature = "rosbag")]
#[test]
fn the_sqlite3_reader_answers_damaged_bags() {
    let dir = std::env::temp_dir().join(format!("dynamics-corpus-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a scratch directory");
    let path = dir.join("x.db3");
    for seed in files()
        .iter()
        .filter(|p| p.extension().and_then(|e| e.to_str()) == Some("db3"))
    {
        let bytes = std::fs::read(seed).expect("a seed");
        for input in variants(&bytes) {
            std::fs::write(&path, &input).expect("written");
            let _ = dynamics_sim2real::data::bag::read_bag(&path, &ARM, "/joint_states");
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}
