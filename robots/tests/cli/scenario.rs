//! `dynamics scenario`: the scenarios by name, their CSV and SVG files,
//! and every controller following the circle.

use crate::{dynamics, fails_with, succeeds, tmp};

#[test]
fn scenarios_run_by_name_and_write_csv_and_svg() {
    let dir = tmp("rrp-line");
    let text = succeeds(dynamics().args(["scenario", "rrp-line", "--out"]).arg(&dir));
    for f in [
        "rrp-line.csv",
        "q.svg",
        "qd.svg",
        "tau.svg",
        "path.svg",
        "lambda.svg",
    ] {
        assert!(dir.join(f).exists(), "missing {f}");
    }
    // The program holds: the reported violation is tiny.
    let line = text
        .lines()
        .find(|l| l.contains("violation"))
        .expect("a violation line");
    let v: f64 = line
        .rsplit('=')
        .next()
        .and_then(|s| s.trim().trim_end_matches(" m").parse().ok())
        .expect("a number");
    assert!(v < 1e-8, "{line}");
    let list = dynamics().args(["scenario"]).output().expect("runs");
    assert!(String::from_utf8_lossy(&list.stdout).contains("arm3r-free"));
    fails_with(dynamics().args(["scenario", "nope"]), "unknown scenario");
}

#[test]
fn every_controller_follows_the_circle() {
    let dir = tmp("circle");
    let lines = robots::scenarios::run("arm3r-circle", &dir).expect("runs");
    let rms = |name: &str| -> f64 {
        let line = lines
            .iter()
            .find(|l| l.starts_with(name))
            .expect("a line per controller");
        let after = line.split("RMS ").nth(1).expect("an RMS figure");
        after
            .split(' ')
            .next()
            .and_then(|v| v.parse().ok())
            .expect("a number")
    };
    // PD with gravity compensation lags; the model-based ones track.
    assert!(rms("pd-gravity") < 2e-3);
    assert!(rms("computed-torque") < 1e-4);
    assert!(rms("sliding-mode") < 1e-4);
    assert!(dir.join("path.svg").exists() && dir.join("arm3r-circle-sliding-mode.csv").exists());
}
