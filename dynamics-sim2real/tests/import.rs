//! Recorded layouts read through a column map: NumPy archives written by
//! NumPy itself, a directory of one-quantity text files with the joints
//! one after the other, a text matrix; and the errors that name the file.

use std::path::{Path, PathBuf};

use dynamics_sim2real::data::import::{import, ColumnMap};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

fn map(s: &str) -> ColumnMap {
    s.parse().expect("a column map")
}

/// A fresh empty directory under the system's temporary one.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("dynamics-import-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("a scratch directory");
    dir
}

#[test]
fn numpy_archives_compressed_and_stored_with_fortran_order() {
    let m = map("t=times,q=positions,qd=velocities,tau=torques");
    for file in ["synthetic-2joint.npz", "synthetic-2joint-stored.npz"] {
        let d = import(&data(file), &m, &["a", "b"], None).unwrap();
        assert_eq!(d.len(), 250, "{file}");
        assert!(d.qd_measured);
        for k in [0, 17, 249] {
            let kf = k as f64;
            assert!(
                (d.t[k] - kf * 0.005).abs() < 1e-6,
                "{file} t[{k}] = {}",
                d.t[k]
            );
            for j in 0..2 {
                let jf = j as f64;
                assert_eq!(d.q[k][j], (0.01 * kf + jf).sin(), "{file} q[{k}][{j}]");
                assert_eq!(d.qd[k][j], (0.01 * kf + jf).cos());
                assert_eq!(d.tau[k][j], kf * 0.5 + jf);
            }
        }
        assert!(
            d.warnings.iter().any(|w| w
                .to_string()
                .contains("times counted from the first sample")),
            "{:?}",
            d.warnings
        );
    }
    // A window in seconds from the first sample, and a scale.
    let d = import(
        &data("synthetic-2joint.npz"),
        &map("t=times,q=positions,tau=torques.npy*-2"),
        &["a", "b"],
        Some((0.25, 1.25)),
    )
    .unwrap();
    assert_eq!(d.len(), 200);
    assert!((d.t[0] - 0.25).abs() < 1e-6);
    assert_eq!(d.tau[0][1], -2.0 * (50.0 * 0.5 + 1.0));
    assert!(!d.qd_measured);
    // qd differentiated from q: d/dt sin(0.01 k) at 5 ms a step = 2 cos(.).
    assert!((d.qd[100][0] - 2.0 * (0.01f64 * 150.0).cos()).abs() < 1e-3);
}

#[test]
fn one_file_per_quantity_with_joints_one_after_the_other() {
    let dir = scratch("stacked");
    let n = 300;
    let mut t = String::new();
    let (mut q, mut qd, mut tau) = (String::new(), String::new(), String::new());
    for k in 0..n {
        // a jittered clock, as the controller logged it
        t.push_str(&format!(
            "{}\n",
            k as f64 * 1e-3 + if k % 3 == 1 { 3e-4 } else { 0.0 }
        ));
        for j in 0..3 {
            q.push_str(&format!("{}\n", k as f64 * 1e-3 * (j + 1) as f64));
            qd.push_str(&format!("{}\n", (j + 1) as f64));
            tau.push_str(&format!("{}\n", 10.0 * j as f64 + k as f64));
        }
    }
    for (f, s) in [
        ("time.txt", &t),
        ("pos.txt", &q),
        ("vel.txt", &qd),
        ("tau.txt", &tau),
    ] {
        std::fs::write(dir.join(f), s).unwrap();
    }
    let d = import(
        &dir,
        &map("t=time.txt,q=pos.txt,qd=vel.txt,tau=tau.txt"),
        &["j1", "j2", "j3"],
        None,
    )
    .unwrap();
    assert_eq!(d.len(), n);
    assert_eq!(
        (d.t[3], d.q[4][2], d.qd[7][1], d.tau[9][2]),
        (3e-3, 12e-3, 2.0, 29.0)
    );
    assert!((d.t[1] - 1.3e-3).abs() < 1e-15);
    assert_eq!(
        d.warnings
            .iter()
            .filter(|w| w.to_string().contains("read as 300 samples x 3 joints"))
            .count(),
        3,
        "{:?}",
        d.warnings
    );
    // A count that is not samples x joints, and a missing file, are named.
    let e = import(
        &dir,
        &map("t=time.txt,q=pos.txt,tau=tau.txt"),
        &["j1", "j2"],
        None,
    )
    .unwrap_err();
    assert!(
        e.to_string()
            .ends_with("pos.txt: 900 rows x 1 columns; `q` needs 2 (one column per joint)"),
        "{e}"
    );
    let e = import(
        &dir,
        &map("t=clock.txt,q=pos.txt,tau=tau.txt"),
        &["a", "b", "c"],
        None,
    )
    .unwrap_err();
    assert!(
        e.to_string()
            .ends_with("no file `clock.txt` (there are: pos.txt, tau.txt, time.txt, vel.txt)"),
        "{e}"
    );
}

#[test]
fn a_text_matrix_with_column_ranges() {
    let dir = scratch("matrix");
    let path = dir.join("log.csv");
    let mut s = String::from("time_ms,q1,q2,tau1,tau2,extra\n");
    for k in 0..250 {
        s.push_str(&format!(
            "{},{},{},{},{},7\n",
            k,
            k as f64 * 0.01,
            -1.0,
            0.5,
            -0.5
        ));
    }
    std::fs::write(&path, &s).unwrap();
    let d = import(&path, &map("t=:1*1e-3,q=:2-3,tau=:4-5"), &["a", "b"], None).unwrap();
    assert_eq!(
        (d.len(), d.t[249], d.q[3][0], d.tau[0][1]),
        (250, 0.249, 0.03, -0.5)
    );
    assert!(d
        .warnings
        .iter()
        .any(|w| w.to_string().ends_with("log.csv:1: header line skipped")));
    let e = import(&path, &map("t=:1,q=:2-8,tau=:4-5"), &["a", "b"], None).unwrap_err();
    assert!(
        e.to_string()
            .ends_with("log.csv: columns 2-8 asked for, the source has 6"),
        "{e}"
    );
    let e = import(
        &path,
        &map("t=:1*1e-3,q=:2-3,tau=:4-5"),
        &["a", "b"],
        Some((0.0, 0.1)),
    )
    .unwrap_err();
    assert!(
        e.to_string()
            .contains("log.csv: 100 samples in the window 0..0.1 s; at least 200"),
        "{e}"
    );
    std::fs::write(&path, s.replace("\n5,", "\n4,")).unwrap();
    let e = import(&path, &map("t=:1,q=:2-3,tau=:4-5"), &["a", "b"], None).unwrap_err();
    assert!(
        e.to_string()
            .ends_with("log.csv:7: time 4 does not increase (previous sample at 4)"),
        "{e}"
    );
}

#[test]
fn archive_errors_name_file_and_array() {
    let e = import(
        &data("synthetic-2joint.npz"),
        &map("t=time,q=positions,tau=torques"),
        &["a", "b"],
        None,
    )
    .unwrap_err();
    assert!(
        e.to_string().ends_with(
            "synthetic-2joint.npz: no array `time` (there are: positions, times, torques, velocities)"
        ),
        "{e}"
    );
    let e = import(
        &data("synthetic-2joint.npz"),
        &map("t=times,q=positions,tau=torques"),
        &["a"],
        None,
    )
    .unwrap_err();
    assert!(
        e.to_string().ends_with("synthetic-2joint.npz:positions: 250 rows x 2 columns; `q` needs 1 (one column per joint): say which (`:A-B`)"),
        "{e}"
    );
    let dir = scratch("broken");
    let bytes = std::fs::read(data("synthetic-2joint.npz")).unwrap();
    let cut = dir.join("cut.npz");
    std::fs::write(&cut, &bytes[..bytes.len() / 2]).unwrap();
    let e = import(
        &cut,
        &map("t=times,q=positions,tau=torques"),
        &["a", "b"],
        None,
    )
    .unwrap_err();
    assert!(
        e.to_string()
            .contains("cut.npz: not a readable .npz (zip) archive"),
        "{e}"
    );
}

#[test]
fn the_fewest_samples_are_the_csv_readers() {
    use dynamics_sim2real::data::import::MIN_SAMPLES;
    use dynamics_sim2real::data::read_csv_str;
    let dir = scratch("fewest");
    let path = dir.join("m.txt");
    for (rows, ok) in [(MIN_SAMPLES - 1, false), (MIN_SAMPLES, true)] {
        let body: String = (0..rows)
            .map(|k| format!("{},0,1\n", k as f64 * 1e-3))
            .collect();
        std::fs::write(&path, &body).unwrap();
        let imported = import(&path, &map("t=:1,q=:2,tau=:3"), &["j"], None);
        let csv = read_csv_str(&format!("t,q_j,tau_j\n{body}"), &["j"], "m.csv");
        assert_eq!((imported.is_ok(), csv.is_ok()), (ok, ok), "{rows} rows");
    }
}
