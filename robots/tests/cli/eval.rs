//! `dynamics check` and `dynamics eval`: the robots of the source works against their
//! reference values, every field at the states of a file, bad input named.

use crate::{dynamics, read_json, succeeds, tmp};

#[test]
fn check_compares_every_seed_robot() {
    let text = succeeds(dynamics().arg("check"));
    for name in ["arm3r", "rrp-rigid", "mar"] {
        assert!(text.contains(&format!("{name} (20 states): ok")), "{text}");
    }
}

#[test]
fn eval_writes_every_field_for_a_states_file() {
    let states = tmp("states.json");
    std::fs::write(
        &states,
        r#"{"states": [{"q": [0, 0, 0], "v": [0, 0, 0], "a": [0, 0, 0]}]}"#,
    )
    .expect("write");
    let out_file = tmp("out.json");
    succeeds(
        dynamics()
            .args(["eval", "--robot", "arm3r", "--states"])
            .arg(&states)
            .arg("--out")
            .arg(&out_file)
            .args(["--set", "m=0"]),
    );
    let doc = read_json(&out_file);
    let s = &doc["states"][0];
    for field in [
        "tau",
        "M",
        "g",
        "C",
        "nle",
        "ddq",
        "kinetic_energy",
        "potential_energy",
    ] {
        assert!(!s[field].is_null(), "missing {field}: {s}");
    }
    // Without the payload, g1 = (4.08*0.0635 + 2.34*0.27475 + 0.73*0.46067) * 9.8.
    let g1 = (4.08 * 0.0635 + 2.34 * 0.27475 + 0.73 * 0.46067) * 9.8;
    let ours = s["g"][0].as_f64().expect("number");
    assert!((ours - g1).abs() < 1e-9, "{ours} vs {g1}");
}

#[test]
fn bad_input_is_a_clear_error() {
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (vec!["eval", "--robot", "r2d2"], "unknown robot `r2d2`"),
        (
            vec!["eval", "--robot", "arm3r", "--set", "mass=1"],
            "no parameter `mass`; known: m, b1, b2, b3",
        ),
        (
            vec!["eval", "--robot", "arm3r", "--set", "m=abc"],
            "is not a number",
        ),
    ];
    for (args, expect) in cases {
        let out = dynamics().args(&args).output().expect("runs");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{args:?} should fail");
        assert!(err.contains(expect), "{args:?}: {err}");
    }
    let states = tmp("bad.json");
    std::fs::write(
        &states,
        r#"{"states": [{"q": [0, 0], "v": [0, 0, 0], "a": [0, 0, 0]}]}"#,
    )
    .expect("write");
    let out = dynamics()
        .args(["eval", "--robot", "mar", "--states"])
        .arg(&states)
        .output()
        .expect("runs");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("states[0].q") && err.contains("3 joints"),
        "{err}"
    );
}
