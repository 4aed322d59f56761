//! ROS 2 bags written by independent writers (the Python `rosbags` package,
//! and `mcap` with `mcap-ros2-support`: scripts/make-bag-fixtures.py) read
//! back to the very numbers of the same data as our CSV (read by the CSV
//! reader), and every kind of damage named.
#![cfg(feature = "rosbag")]

use std::path::{Path, PathBuf};

use dynamics_sim2real::data::bag::{read_bag, read_mcap_bytes, BagError, DEFAULT_TOPIC};
use dynamics_sim2real::data::{read_csv, Measured};

const ARM: [&str; 3] = ["j1", "j2", "j3"];

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/bags")
        .join(name)
}

fn bag(name: &str) -> Measured<3> {
    match read_bag(&data(name), &ARM, DEFAULT_TOPIC) {
        Ok((m, _)) => m,
        Err(e) => panic!("{name}: {e}"),
    }
}

fn bag_err(name: &str) -> BagError {
    match read_bag(&data(name), &ARM, DEFAULT_TOPIC) {
        Ok((m, _)) => panic!("{name}: read {} samples, expected an error", m.len()),
        Err(e) => e,
    }
}

fn csv(name: &str) -> Measured<3> {
    read_csv(&data(name), &ARM).expect("the CSV twin")
}

/// The samples are the CSV's, bit for bit.
fn same_samples(a: &Measured<3>, b: &Measured<3>, what: &str) {
    assert_eq!(a.len(), b.len(), "{what}: samples");
    assert_eq!(a.t, b.t, "{what}: t");
    assert_eq!(a.q, b.q, "{what}: q");
    assert_eq!(a.tau, b.tau, "{what}: tau");
    assert_eq!(a.qd_measured, b.qd_measured, "{what}: qd measured");
    assert_eq!(a.qd, b.qd, "{what}: qd");
}

fn said(m: &Measured<3>, text: &str) -> bool {
    m.warnings.iter().any(|w| w.to_string().contains(text))
}

#[test]
fn mcap_chunks_of_zstd_and_lz4_read_the_csvs_numbers() {
    let truth = csv("motion.csv.gz");
    for name in [
        "motion-zstd.mcap",
        "motion-lz4.mcap",
        "motion-rosbags-zstd.mcap",
    ] {
        let m = bag(name);
        same_samples(&m, &truth, name);
        assert!(m.warnings.is_empty(), "{name}: {:?}", m.warnings);
    }
}

#[test]
fn a_rosbag2_directory_with_an_extra_joint_and_topic_and_a_big_endian_db3() {
    let (m, summary) = read_bag(&data("arm3r-train"), &ARM, DEFAULT_TOPIC).expect("the bag");
    same_samples(&m, &csv("arm3r-train.csv.gz"), "arm3r-train");
    assert!(
        said(
            &m,
            "joints on `/joint_states` that the robot does not have, ignored: gripper"
        ),
        "{:?}",
        m.warnings
    );
    assert_eq!(summary.messages, 1001);
    assert_eq!(summary.first_ns, 1_764_000_000 * 1_000_000_000);
    assert!(
        summary
            .to_string()
            .ends_with("topic /joint_states, 1001 messages, 2025-11-24 16:00:00.000 to 2025-11-24 16:00:04.000 UTC (4.000 s)"),
        "{summary}"
    );
    // The held-out run: sqlite3 storage, CDR big-endian, joints j2, j1, j3.
    same_samples(
        &bag("arm3r-holdout.db3"),
        &csv("arm3r-holdout.csv.gz"),
        "arm3r-holdout",
    );
}

#[test]
fn zero_stamps_partial_messages_and_missing_velocities() {
    let truth = csv("motion.csv.gz");
    // Every stamp zero: the receive times (0.25 ms after the stamps) are used.
    let m = bag("motion-zero-stamps.db3");
    same_samples(&m, &truth, "zero stamps");
    assert!(
        said(
            &m,
            "300 of 300 messages on `/joint_states` have a zero header.stamp"
        ),
        "{:?}",
        m.warnings
    );
    // Two publishers, j3 + j1 and j2, sharing stamps: merged.
    same_samples(&bag("motion-partial.mcap"), &truth, "partial");
    // No velocities: differentiated from the positions, as for a CSV without qd.
    let m = bag("motion-no-velocity.mcap");
    assert!(!m.qd_measured);
    assert_eq!(
        (m.t.clone(), m.q.clone()),
        (truth.t.clone(), truth.q.clone())
    );
    let k = 150;
    let central = (truth.q[k + 1] - truth.q[k - 1]) / (truth.t[k + 1] - truth.t[k - 1]);
    assert_eq!(m.qd[k], central);
    assert!(said(&m, "carry no velocities"), "{:?}", m.warnings);
}

#[test]
fn what_cannot_be_read_is_named() {
    let e = bag_err("motion-no-effort.db3");
    assert!(matches!(e, BagError::NoEffort { .. }), "{e}");
    assert!(
        e.to_string()
            .contains("motion-no-effort.db3: message id 1: no efforts"),
        "{e}"
    );
    let e = bag_err("motion-missing-joint.mcap");
    assert!(
        e.to_string().ends_with(
            "topic `/joint_states` has no joint `j3` of this robot (its messages name: j1, j2)"
        ),
        "{e}"
    );
    for name in ["motion-wrong-type.mcap", "motion-wrong-type.db3"] {
        let e = bag_err(name);
        assert!(
            e.to_string().ends_with(
                "topic `/joint_states` carries `std_msgs/msg/String` messages (encoded `cdr`), not sensor_msgs/msg/JointState in CDR"
            ),
            "{e}"
        );
    }
    // Another topic: absent, or of another type.
    let e = read_bag(&data("arm3r-train"), &ARM, "/joints").unwrap_err();
    assert!(
        e.to_string()
            .contains("no topic `/joints` (the bag has: /chatter (std_msgs/msg/String), /joint_states (sensor_msgs/msg/JointState))"),
        "{e}"
    );
    let e = read_bag(&data("arm3r-train"), &ARM, "/chatter").unwrap_err();
    assert!(matches!(e, BagError::WrongType { .. }), "{e}");
    // Not a bag at all.
    let e = read_bag(&data("motion.csv.gz"), &ARM, DEFAULT_TOPIC).unwrap_err();
    assert!(matches!(e, BagError::NotABag { .. }), "{e}");
}

#[test]
fn a_bag_cut_inside_a_chunk() {
    // The file was cut at byte 25628, inside the chunk at byte 24607: the
    // messages of the chunks before it are read, with a warning naming it.
    let truth = csv("motion.csv.gz");
    let m = bag("motion-cut.mcap");
    assert!(m.len() >= 200 && m.len() < 300, "{}", m.len());
    assert_eq!(m.q[..], truth.q[..m.len()]);
    assert!(
        said(&m, "motion-cut.mcap: at byte 24607: a record (opcode 0x06)"),
        "{:?}",
        m.warnings
    );
    // Cut inside the first chunk: nothing before it, an error naming the offset.
    let bytes = std::fs::read(data("motion-zstd.mcap")).unwrap();
    let e = read_mcap_bytes(&bytes[..2000], &ARM, DEFAULT_TOPIC, "first.mcap").unwrap_err();
    assert!(matches!(e, BagError::Mcap { .. }), "{e}");
    assert!(e.to_string().starts_with("first.mcap: at byte "), "{e}");
}
