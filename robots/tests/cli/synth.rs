//! `dynamics synth` of what real logs carry, found again by `dynamics
//! diagnose`: an effect that starts and stops, a late effort stream.

use crate::{diagnose_arm3r, dynamics, fails_with, read_json, succeeds, tmp};

/// An effect that starts and stops, from the command line to the JSON
/// report: `synth --window` limits the payload to [2, 4.5) s in training
/// (1.5 to 4 s held out), the truth file records both windows, and the
/// report's `which.effects[].window` has the training window found from
/// the data.
#[test]
fn a_windowed_effect_is_generated_and_found_with_its_window() {
    let train = tmp("window.csv");
    let truth = tmp("window-truth.json");
    succeeds(
        dynamics()
            .args([
                "synth",
                "--robot",
                "arm3r",
                "--effect",
                "payload_mass",
                "--magnitude",
                "0.5",
                "--duration",
                "6",
                "--seed",
                "7",
                "--window",
                "2:4.5",
                "--out",
            ])
            .arg(&train)
            .arg("--truth")
            .arg(&truth),
    );
    let t = read_json(&truth);
    assert_eq!(t["window"], serde_json::json!({"start": 2.0, "end": 4.5}));
    assert_eq!(
        t["holdout_window"],
        serde_json::json!({"start": 1.5, "end": 4.0})
    );
    let json = tmp("window-report.json");
    let text = succeeds(
        diagnose_arm3r(&train, &train.with_file_name("window-holdout.csv"))
            .arg("--json")
            .arg(&json),
    );
    let report = read_json(&json);
    let e = &report["which"]["effects"][0];
    assert_eq!(e["kind"], "payload_mass", "{report}");
    let (start, end) = (
        e["window"]["start"].as_f64().expect("window.start"),
        e["window"]["end"].as_f64().expect("window.end"),
    );
    assert!(
        (start - 2.0).abs() < 0.15 && (end - 4.5).abs() < 0.15,
        "[{start}, {end})"
    );
    assert!(
        text.contains("payload_mass") && text.contains(&format!("is on from {start:.3} s")),
        "{text}"
    );
    // A window on nothing, or on a motor side, is refused.
    fails_with(
        dynamics()
            .args(["synth", "--robot", "arm3r", "--effect", "none"])
            .args(["--window", "1:2", "--out"])
            .arg(tmp("none.csv")),
        "a window needs an effect",
    );
    fails_with(
        dynamics()
            .args(["synth", "--robot", "arm3r", "--window", "2", "--out"])
            .arg(tmp("bad.csv")),
        "--window: window `2`: expected START:END",
    );
}

/// `synth --tau-late`: the effort stream 12 ms late against position and
/// velocity; the truth names channel `effort`, and so does the diagnosis
/// of the files (JSON and the printed verdict); a negative delay is
/// refused.
#[test]
fn a_late_effort_stream_is_generated_and_named() {
    let train = tmp("tau-late.csv");
    let truth = tmp("tau-late-truth.json");
    succeeds(
        dynamics()
            .args(["synth", "--robot", "arm3r", "--effect", "none"])
            .args([
                "--duration",
                "6",
                "--seed",
                "3",
                "--tau-late",
                "0.012",
                "--out",
            ])
            .arg(&train)
            .arg("--truth")
            .arg(&truth),
    );
    let t = read_json(&truth);
    assert_eq!(t["late"], "effort");
    let json = tmp("tau-late-report.json");
    let text = succeeds(
        diagnose_arm3r(&train, &train.with_file_name("tau-late-holdout.csv"))
            .arg("--json")
            .arg(&json),
    );
    let report = read_json(&json);
    let v = &report["which"]["verdict"];
    assert_eq!(
        (&v["kind"], &v["channel"]),
        (&"time_delay".into(), &"effort".into()),
        "{v}"
    );
    let e = &report["which"]["effects"][0];
    let d = e["parameters"][0]["value"].as_f64().expect("delay");
    assert!((d - 0.012).abs() < 0.002, "delay {d}");
    assert!(text.contains("late channel: effort"), "{text}");
    assert!(
        report["warnings"]
            .as_array()
            .expect("warnings")
            .iter()
            .any(|w| w["kind"] == "late_effort"),
        "{report}"
    );
    fails_with(
        dynamics()
            .args([
                "synth",
                "--robot",
                "arm3r",
                "--effect",
                "none",
                "--tau-late=-0.01",
                "--out",
            ])
            .arg(tmp("bad-late.csv")),
        "tau-late must be a delay of at least 0 s, shorter than the record (8 s), got -0.01",
    );
}
