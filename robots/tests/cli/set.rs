//! `--set NAME=VALUE` on a built-in robot: the parameters changed, wrong
//! names and values named.

use crate::{dynamics, fails, fresh_dir, read_json, succeeds};

/// `--set` on a built-in robot: the RRP arm with its spring and drag set
/// to zero is the rigid arm, to the last bit; wrong names and values are
/// clear errors.
#[test]
fn set_changes_a_built_in_robot_and_refuses_what_it_does_not_know() {
    let dir = fresh_dir("set");
    let (a, b, c) = (dir.join("a.json"), dir.join("b.json"), dir.join("c.json"));
    succeeds(dynamics().args(["eval", "--robot", "rrp", "--out"]).arg(&a));
    succeeds(
        dynamics()
            .args(["eval", "--robot", "rrp", "--set", "c=0", "--set", "b1=0"])
            .args(["--set", "b2=0", "--set", "b3=0", "--out"])
            .arg(&b),
    );
    succeeds(
        dynamics()
            .args(["eval", "--robot", "rrp-rigid", "--out"])
            .arg(&c),
    );
    let (a, b, c) = (read_json(&a), read_json(&b), read_json(&c));
    assert_eq!(b["states"], c["states"]);
    assert_ne!(a["states"], c["states"]);
    let err = fails(dynamics().args(["eval", "--robot", "rrp", "--set", "k=0"]));
    assert!(
        err.contains("--set `k=0`: the robot has no parameter `k`; known: m, c, l0, b1, b2, b3"),
        "{err}"
    );
    let err = fails(dynamics().args(["synth", "--robot", "rrp", "--set", "c=x", "--out", "x.csv"]));
    assert!(err.contains("--set `c=x`: `x` is not a number"), "{err}");
    let err = fails(dynamics().args([
        "diagnose",
        "--robot",
        "rrp",
        "--set",
        "c=inf",
        "--train",
        "a",
        "--holdout",
        "b",
    ]));
    assert!(
        err.contains("--set `c=inf`: `inf` is not a finite number"),
        "{err}"
    );
    let err = fails(dynamics().args(["eval", "--robot", "rrp", "--set", "c"]));
    assert!(err.contains("expected NAME=VALUE"), "{err}");
    let err = fails(dynamics().args(["eval", "--robot", "r2d2"]));
    assert!(
        err.contains("unknown robot `r2d2`; known robots: arm3r, rrp"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
