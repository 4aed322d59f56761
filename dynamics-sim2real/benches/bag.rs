//! Reading and preparing a ROS 2 bag as a robot records it: 60 s of
//! `/joint_states` at 1 kHz, 7 joints (positions, velocities, efforts) plus
//! a gripper joint the robot does not have, beside a second topic; as an
//! MCAP file with zstd chunks (the `mcap` crate's writer) and as an sqlite3
//! bag (`rusqlite`). Measured in thread CPU time (as robots/benches do:
//! on a shared machine wall-clock time counts other processes too). Run:
//! `cargo bench -p dynamics-sim2real --features rosbag --bench bag`.

#[path = "../../robots/benches/support/cpu_time.rs"]
mod cpu_time;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use criterion::{criterion_group, criterion_main, Criterion};
use dynamics_sim2real::data::bag::{read_bag, DEFAULT_TOPIC};
use dynamics_sim2real::synth::Rng;

const JOINTS: [&str; 7] = [
    "panda_joint1",
    "panda_joint2",
    "panda_joint3",
    "panda_joint4",
    "panda_joint5",
    "panda_joint6",
    "panda_joint7",
];
const EPOCH_NS: u64 = 1_764_000_000_000_000_000;

/// A JointState in little-endian CDR.
fn joint_state(stamp: u64, names: &[&str], q: &[f64], qd: &[f64], tau: &[f64]) -> Vec<u8> {
    let mut b = vec![0, 1, 0, 0];
    let pad = |b: &mut Vec<u8>, n: usize| {
        while !(b.len() - 4).is_multiple_of(n) {
            b.push(0);
        }
    };
    b.extend(((stamp / 1_000_000_000) as i32).to_le_bytes());
    b.extend(((stamp % 1_000_000_000) as u32).to_le_bytes());
    b.extend(1u32.to_le_bytes());
    b.push(0);
    pad(&mut b, 4);
    b.extend((names.len() as u32).to_le_bytes());
    for n in names {
        pad(&mut b, 4);
        b.extend((n.len() as u32 + 1).to_le_bytes());
        b.extend(n.as_bytes());
        b.push(0);
    }
    for values in [q, qd, tau] {
        pad(&mut b, 4);
        b.extend((values.len() as u32).to_le_bytes());
        pad(&mut b, 8);
        for v in values {
            b.extend(v.to_le_bytes());
        }
    }
    b
}

/// The messages: (stamp ns, CDR bytes).
fn messages() -> Vec<(u64, Vec<u8>)> {
    let mut rng = Rng::new(42);
    let mut names: Vec<&str> = JOINTS.to_vec();
    names.push("panda_finger_joint1");
    (0..60_000u64)
        .map(|k| {
            let t = k as f64 * 1e-3;
            let (mut q, mut qd, mut tau) = (vec![], vec![], vec![]);
            for j in 0..8 {
                let w = 1.0 + 0.3 * j as f64;
                q.push(0.5 * (w * t).sin() + 2e-5 * rng.normal());
                qd.push(0.5 * w * (w * t).cos() + 2e-3 * rng.normal());
                tau.push(10.0 * (w * t).sin() + 0.02 * rng.normal());
            }
            let stamp = EPOCH_NS + k * 1_000_000;
            (stamp, joint_state(stamp, &names, &q, &qd, &tau))
        })
        .collect()
}

fn write_mcap(path: &Path, msgs: &[(u64, Vec<u8>)]) {
    let file = std::io::BufWriter::new(std::fs::File::create(path).expect("the benchmark's bag"));
    let mut w = mcap::Writer::new(file).expect("the benchmark's bag");
    let schema = w
        .add_schema("sensor_msgs/msg/JointState", "ros2msg", b"")
        .expect("the benchmark's bag");
    let other = w
        .add_schema("std_msgs/msg/String", "ros2msg", b"")
        .expect("the benchmark's bag");
    let none = BTreeMap::new();
    let js = w
        .add_channel(schema, "/joint_states", "cdr", &none)
        .expect("the benchmark's bag");
    let log = w
        .add_channel(other, "/rosout", "cdr", &none)
        .expect("the benchmark's bag");
    for (k, (stamp, data)) in msgs.iter().enumerate() {
        let header = |channel_id| mcap::records::MessageHeader {
            channel_id,
            sequence: k as u32,
            log_time: stamp + 200_000,
            publish_time: *stamp,
        };
        w.write_to_known_channel(&header(js), data)
            .expect("the benchmark's bag");
        if k % 100 == 0 {
            w.write_to_known_channel(&header(log), &[0, 1, 0, 0, 1, 0, 0, 0, 0])
                .expect("the benchmark's bag");
        }
    }
    w.finish().expect("the benchmark's bag");
}

fn write_db3(path: &Path, msgs: &[(u64, Vec<u8>)]) {
    let _ = std::fs::remove_file(path);
    let mut db = rusqlite::Connection::open(path).expect("the benchmark's bag");
    db.execute_batch(
        "CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL, \
         serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL);
         CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL, \
         timestamp INTEGER NOT NULL, data BLOB NOT NULL);
         CREATE INDEX timestamp_idx ON messages (timestamp ASC);
         INSERT INTO topics VALUES (1, '/joint_states', 'sensor_msgs/msg/JointState', 'cdr', '');",
    )
    .expect("the benchmark's bag");
    let tx = db.transaction().expect("the benchmark's bag");
    {
        let mut insert = tx
            .prepare("INSERT INTO messages (topic_id, timestamp, data) VALUES (1, ?1, ?2)")
            .expect("the benchmark's bag");
        for (stamp, data) in msgs {
            insert
                .execute(rusqlite::params![(*stamp + 200_000) as i64, data])
                .expect("the benchmark's bag");
        }
    }
    tx.commit().expect("the benchmark's bag");
}

fn bench(c: &mut Criterion<cpu_time::ThreadCpuTime>) {
    let msgs = messages();
    let dir = std::env::temp_dir();
    let files: [(&str, PathBuf); 2] = [
        ("mcap_zstd", dir.join("dynamics-bench-60s.mcap")),
        ("sqlite3", dir.join("dynamics-bench-60s.db3")),
    ];
    write_mcap(&files[0].1, &msgs);
    write_db3(&files[1].1, &msgs);
    let mut g = c.benchmark_group("read_and_prepare_bag_60s_1khz_7_joints");
    g.sample_size(10);
    for (name, path) in &files {
        let (m, summary) = read_bag(path, &JOINTS, DEFAULT_TOPIC).expect("the benchmark's bag");
        assert_eq!((m.len(), summary.messages), (60_000, 60_000));
        g.bench_function(*name, |b| {
            b.iter(|| read_bag(path, &JOINTS, DEFAULT_TOPIC).expect("the benchmark's bag"))
        });
    }
    g.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default().with_measurement(cpu_time::ThreadCpuTime);
    targets = bench
}
criterion_main!(benches);
