//! Recorded data as robots record them: the diagnosis of ROS 2 bags (an
//! MCAP rosbag2 directory and an sqlite3 file, written by the Python
//! `rosbags` package: scripts/make-bag-fixtures.py) equals the diagnosis of
//! the same samples as CSV; `--topic`; identify on bags; `synth --out
//! x.parquet` diagnosed as its CSV twin.

use std::path::PathBuf;

use crate::{diagnose_arm3r, dynamics, fails_with, read_json, succeeds, tmp, workspace};

fn fixture(name: &str) -> PathBuf {
    workspace()
        .join("dynamics-sim2real/tests/data/bags")
        .join(name)
}

/// The JSON report without its warnings (which name the files read).
fn report_of(cmd: &mut std::process::Command, name: &str) -> serde_json::Value {
    let json = tmp(name);
    succeeds(cmd.arg("--json").arg(&json));
    let mut report = read_json(&json);
    report
        .as_object_mut()
        .expect("an object")
        .remove("warnings");
    report
}

#[test]
fn the_diagnosis_of_bags_equals_that_of_the_same_data_as_csv() {
    let (train, holdout) = (fixture("arm3r-train"), fixture("arm3r-holdout.db3"));
    let bag = report_of(&mut diagnose_arm3r(&train, &holdout), "bag.json");
    let csv = report_of(
        &mut diagnose_arm3r(
            &fixture("arm3r-train.csv.gz"),
            &fixture("arm3r-holdout.csv.gz"),
        ),
        "bag-csv.json",
    );
    assert_eq!(bag, csv);
    assert_eq!(bag["which"]["verdict"]["kind"], "viscous_friction");
    // The header names what was read; the gripper joint is ignored with a warning.
    let out = diagnose_arm3r(&train, &holdout).output().expect("runs");
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.starts_with("training data: ")
            && text.contains(
                "arm3r-train: topic /joint_states, 1001 messages, 2025-11-24 16:00:00.000 to 2025-11-24 16:00:04.000 UTC (4.000 s)"
            ),
        "{text}"
    );
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("ignored: gripper"), "{err}");
    // Another topic: of another type, or absent.
    fails_with(
        diagnose_arm3r(&train, &holdout).args(["--topic", "/chatter"]),
        "topic `/chatter` carries `std_msgs/msg/String` messages",
    );
    fails_with(
        diagnose_arm3r(&train, &holdout).args(["--topic", "/nothing"]),
        "no topic `/nothing` (the bag has: /chatter (std_msgs/msg/String), /joint_states (sensor_msgs/msg/JointState)); choose one with --topic",
    );
    // A bag for another robot: the joints it lacks and the names it has.
    fails_with(
        dynamics()
            .args(["diagnose", "--robot", "rrp", "--train"])
            .arg(&train)
            .arg("--holdout")
            .arg(&holdout),
        "of this robot (its messages name: gripper, j1, j2, j3)",
    );
}

#[test]
fn identify_reads_bags_as_their_csv() {
    let run = |train: PathBuf, holdout: PathBuf| {
        let text = succeeds(
            dynamics()
                .args(["identify", "--robot", "arm3r", "--train"])
                .arg(train)
                .arg("--holdout")
                .arg(holdout),
        );
        // Without the header lines naming the files.
        text.lines()
            .filter(|l| !l.starts_with("data: "))
            .collect::<Vec<_>>()
            .join("\n")
    };
    assert_eq!(
        run(fixture("arm3r-train"), fixture("arm3r-holdout.db3")),
        run(
            fixture("arm3r-train.csv.gz"),
            fixture("arm3r-holdout.csv.gz")
        )
    );
}

#[test]
fn synth_writes_parquet_that_diagnoses_as_its_csv() {
    let synth = |out: &PathBuf| {
        succeeds(
            dynamics()
                .args([
                    "synth",
                    "--robot",
                    "arm3r",
                    "--effect",
                    "coulomb_friction",
                    "--joint",
                    "j2",
                    "--duration",
                    "3",
                    "--seed",
                    "3",
                    "--out",
                ])
                .arg(out),
        );
    };
    let (csv, parquet) = (tmp("twin.csv"), tmp("twin.parquet"));
    synth(&csv);
    synth(&parquet);
    let hold = |p: &PathBuf, ext: &str| p.with_file_name(format!("twin-holdout.{ext}"));
    assert!(std::fs::read(&parquet)
        .expect("written")
        .starts_with(b"PAR1"));
    let a = report_of(
        &mut diagnose_arm3r(&csv, &hold(&csv, "csv")),
        "twin-csv.json",
    );
    let b = report_of(
        &mut diagnose_arm3r(&parquet, &hold(&parquet, "parquet")),
        "twin-parquet.json",
    );
    assert_eq!(a, b);
}
