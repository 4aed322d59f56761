//! `dynamics excite`: the motion file keeps the URDF's limits (read here
//! from the URDF itself, not through the program), starts and ends at
//! rest, carries the columns `simulate --motion` plays, and the program
//! prints the designed and the default condition numbers.

use std::path::Path;

use crate::{dynamics, fails_with, read_json, succeeds, tmp, workspace};

/// `(name, lower, upper, velocity)` of every joint of a URDF with a
/// `<limit>` (a plain reading of the file, independent of the program).
fn urdf_limits(urdf: &Path) -> Vec<(String, f64, f64, f64)> {
    let text = std::fs::read_to_string(urdf).expect("urdf");
    let attr = |s: &str, name: &str| -> Option<String> {
        let at = s.find(&format!(" {name}=\""))? + name.len() + 3;
        Some(s[at..at + s[at..].find('"')?].to_string())
    };
    let mut out = Vec::new();
    for part in text.split("<joint ").skip(1) {
        let body = &part[..part.find("</joint>").unwrap_or(part.len())];
        let Some(limit) = body.find("<limit").map(|i| &body[i..]) else {
            continue;
        };
        let name = attr(&format!(" {body}"), "name").expect("joint name");
        let num = |a: &str| attr(limit, a).expect(a).parse::<f64>().expect("number");
        out.push((name, num("lower"), num("upper"), num("velocity")));
    }
    out
}

/// The columns of a CSV file by header name.
fn columns(csv: &Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = std::fs::read_to_string(csv).expect("csv");
    let mut lines = text.lines();
    let header: Vec<String> = lines
        .next()
        .expect("header")
        .split(',')
        .map(String::from)
        .collect();
    let mut cols = vec![Vec::new(); header.len()];
    for l in lines {
        for (c, v) in l.split(',').enumerate() {
            cols[c].push(v.parse::<f64>().expect("number"));
        }
    }
    (header, cols)
}

/// Asserts that every `q_<joint>` and `qd_<joint>` of the motion `csv`
/// keeps the URDF's limits tightened by `margin`, and that the motion
/// starts and ends at rest at the same pose.
pub(crate) fn assert_within_urdf_limits(csv: &Path, urdf: &Path, margin: f64) {
    let (header, cols) = columns(csv);
    let col = |name: &str| {
        let i = header.iter().position(|h| h == name);
        &cols[i.unwrap_or_else(|| panic!("no column {name} in {header:?}"))]
    };
    let limits = urdf_limits(urdf);
    assert!(!limits.is_empty());
    for (j, lo, hi, v) in limits {
        let half = 0.5 * margin * (hi - lo);
        let (q, qd, qdd) = (
            col(&format!("q_{j}")),
            col(&format!("qd_{j}")),
            col(&format!("qdd_{j}")),
        );
        for &x in q {
            assert!(x >= lo + half - 1e-9 && x <= hi - half + 1e-9, "{j}: {x}");
        }
        for &x in qd {
            assert!(x.abs() <= (1.0 - margin) * v + 1e-9, "{j}: {x}");
        }
        let n = q.len() - 1;
        assert!((q[0] - q[n]).abs() < 1e-9, "{j}");
        assert!(qd[0].abs() < 1e-9 && qd[n].abs() < 1e-9, "{j}");
        assert!(qdd[0].abs() < 1e-8 && qdd[n].abs() < 1e-8, "{j}");
    }
}

#[test]
fn excite_writes_a_motion_within_the_urdf_limits_that_simulate_plays() {
    let (csv, json) = (tmp("excite-panda.csv"), tmp("excite-panda.json"));
    let said = succeeds(
        dynamics()
            .args([
                "excite",
                "--robot",
                "panda",
                "--duration",
                "10",
                "--rate",
                "200",
            ])
            .args(["--evaluations", "200", "--out"])
            .arg(&csv)
            .arg("--json")
            .arg(&json),
    );
    assert!(
        said.contains("designed") && said.contains("default sines"),
        "{said}"
    );
    assert_within_urdf_limits(&csv, &workspace().join("robots/data/urdf/panda.urdf"), 0.1);
    let (header, cols) = columns(&csv);
    assert_eq!(header[0], "t");
    assert_eq!(header.len(), 1 + 3 * 7);
    assert_eq!(cols[0].len(), 2001);
    let d = read_json(&json);
    assert_eq!(d["check"]["position"], true);
    assert_eq!(d["check"]["effort"], true);
    assert_eq!(d["sin"].as_array().expect("sin").len(), 5);
    assert!(d["figures"]["condition"].as_f64().expect("condition") > 1.0);
    let params = d["identifiability"]["parameters"]
        .as_array()
        .expect("params");
    assert_eq!(
        params.len() as u64,
        d["base_parameters"].as_u64().expect("k")
    );
    assert!(!d["identifiability"]["unidentifiable"]
        .as_array()
        .expect("unidentifiable")
        .is_empty());
    // `simulate --motion` follows it.
    let out = tmp("excite-sim");
    let sim = succeeds(
        dynamics()
            .args(["simulate", "--robot", "panda", "--rate", "200", "--motion"])
            .arg(&csv)
            .arg("--out")
            .arg(&out),
    );
    assert!(!sim.is_empty());
}

#[test]
fn excite_refuses_a_start_outside_the_limits() {
    fails_with(
        dynamics()
            .args(["excite", "--robot", "panda", "--duration", "5", "--from"])
            .arg("3,0,0,-2,0,1.7,0.8")
            .arg("--out")
            .arg(tmp("never.csv")),
        "start pose of joint `panda_joint1` (3)",
    );
}

#[test]
fn excite_separate_widens_the_smallest_angle_of_the_reports_pairs() {
    let report = tmp("excite-report.json");
    std::fs::write(
        &report,
        r#"{"which": {"verdict": {"kind": "coulomb_friction", "joint": "j2", "status": "ambiguous",
            "rival": {"kind": "stribeck_friction", "joint": "j2"}},
          "effects": [{"kind": "armature", "joint": "j3",
            "ambiguous_with": {"kind": "inertial_parameters", "point": "link3"}}]}}"#,
    )
    .expect("writes");
    let (csv, json) = (tmp("excite-sep.csv"), tmp("excite-sep.json"));
    let said = succeeds(
        dynamics()
            .args([
                "excite",
                "--robot",
                "arm3r",
                "--duration",
                "8",
                "--rate",
                "200",
            ])
            .args(["--evaluations", "300", "--separate"])
            .arg(&report)
            .arg("--out")
            .arg(&csv)
            .arg("--json")
            .arg(&json),
    );
    assert!(
        said.contains("coulomb_friction j2 vs stribeck_friction j2"),
        "{said}"
    );
    let rows = read_json(&json)["separation"]
        .as_array()
        .expect("rows")
        .clone();
    assert_eq!(rows.len(), 2);
    let min = |key: &str| {
        rows.iter()
            .map(|r| r[key].as_f64().expect("angle"))
            .fold(f64::INFINITY, f64::min)
    };
    assert!(min("angle_deg") > min("default_angle_deg"), "{rows:?}");
    // A payload against the distal link: no motion separates them.
    std::fs::write(
        &report,
        r#"{"which": {"verdict": {"kind": "payload_mass", "status": "ambiguous",
            "rival": {"kind": "inertial_parameters", "point": "link3"}}, "effects": []}}"#,
    )
    .expect("writes");
    fails_with(
        dynamics()
            .args([
                "excite",
                "--robot",
                "arm3r",
                "--duration",
                "4",
                "--separate",
            ])
            .arg(&report)
            .arg("--out")
            .arg(&csv),
        "no motion separates the two",
    );
}

#[test]
fn check_data_says_what_a_motion_cannot_identify() {
    // Joint j1 still, j2 one slow ramp, j3 swinging: written here.
    let data = tmp("check-data.csv");
    let mut text = String::from("t,q_j1,q_j2,q_j3\n");
    for k in 0..2000 {
        let t = k as f64 * 0.005;
        text.push_str(&format!("{t},0,{},{}\n", 0.01 * t, 0.5 * (2.0 * t).sin()));
    }
    std::fs::write(&data, text).expect("writes");
    let said = succeeds(
        dynamics()
            .args(["check-data", "--robot", "arm3r", "--data"])
            .arg(&data),
    );
    assert!(said.contains("joint j2 never reverses direction"), "{said}");
    assert!(said.contains("joint j2 never exceeds 0.20 rad/s"), "{said}");
    assert!(!said.contains("joint j3 never"), "{said}");
    assert!(said.contains("weak direction"), "{said}");
}

#[test]
fn excite_keeps_an_acceleration_limit_when_given() {
    let (csv, json) = (tmp("excite-acc.csv"), tmp("excite-acc.json"));
    succeeds(
        dynamics()
            .args([
                "excite",
                "--robot",
                "ur5",
                "--duration",
                "5",
                "--rate",
                "500",
            ])
            .args(["--evaluations", "100", "--acc-limit", "0.5", "--out"])
            .arg(&csv)
            .arg("--json")
            .arg(&json),
    );
    let d = read_json(&json);
    assert_eq!(d["check"]["acceleration"], true, "{d}");
    // Read back from the CSV: every qdd within (1 - margin) 0.5.
    let (header, cols) = columns(&csv);
    for (h, c) in header.iter().zip(&cols) {
        if h.starts_with("qdd_") {
            assert!(c.iter().all(|v| v.abs() <= 0.45 + 1e-9), "{h}");
        }
    }
}
