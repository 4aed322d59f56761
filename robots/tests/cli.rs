//! The `dynamics` program as a user runs it.

use std::process::Command;

fn dynamics() -> Command {
    Command::new(env!("CARGO_BIN_EXE_dynamics"))
}

fn tmp(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("dynamics-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir.join(name)
}

#[test]
fn default_command_diagnoses_the_built_in_case() {
    let out = dynamics().output().expect("runs");
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{text}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(text.contains("verdict: coulomb_friction j2"), "{text}");
    assert!(
        text.contains(
            "truth of the built-in case (read after the verdict): coulomb_friction at j2"
        ),
        "{text}"
    );
}

#[test]
fn synth_then_diagnose_from_files_writes_the_json_report() {
    let train = tmp("synth.csv");
    let truth = tmp("truth.json");
    let out = dynamics()
        .args([
            "synth",
            "--robot",
            "arm3r",
            "--effect",
            "viscous_friction",
            "--joint",
            "j3",
            "--magnitude",
            "0.3",
            "--duration",
            "4",
            "--seed",
            "5",
            "--out",
        ])
        .arg(&train)
        .arg("--truth")
        .arg(&truth)
        .output()
        .expect("runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let holdout = train.with_file_name("synth-holdout.csv");
    let json = tmp("report.json");
    let out = dynamics()
        .args(["diagnose", "--robot", "arm3r", "--train"])
        .arg(&train)
        .arg("--holdout")
        .arg(&holdout)
        .arg("--json")
        .arg(&json)
        .output()
        .expect("runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).expect("report")).expect("json");
    assert_eq!(report["which"]["verdict"]["kind"], "viscous_friction");
    assert_eq!(report["which"]["verdict"]["joint"], "j3");
    assert!(report["shrink"]["fraction"].as_f64().expect("number") > 0.8);
    // Stated sensor noise: the truth file's effort noise (per joint) is
    // accepted and gives the same verdict; a wrong count is refused.
    let truth_json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&truth).expect("truth")).expect("json");
    let noise_tau: Vec<String> = truth_json["noise_tau"]
        .as_array()
        .expect("noise_tau")
        .iter()
        .map(|v| v.as_f64().expect("number").to_string())
        .collect();
    assert_eq!(noise_tau.len(), 3);
    let stated = |tau: &str| {
        dynamics()
            .args(["diagnose", "--robot", "arm3r", "--train"])
            .arg(&train)
            .arg("--holdout")
            .arg(&holdout)
            .args([
                "--noise-q",
                "2e-5",
                "--noise-qd",
                "2e-3",
                "--noise-tau",
                tau,
            ])
            .output()
            .expect("runs")
    };
    let out = stated(&noise_tau.join(","));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success() && text.contains("verdict: viscous_friction j3"),
        "{text}"
    );
    let out = stated("0.1,0.2");
    assert!(!out.status.success());
    assert!(
        String::from_utf8_lossy(&out.stderr).contains("sensor noise `tau`: 2 values given"),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // A file for another robot is refused with the column named.
    let out = dynamics()
        .args(["diagnose", "--robot", "rrp", "--train"])
        .arg(&train)
        .arg("--holdout")
        .arg(&holdout)
        .output()
        .expect("runs");
    assert!(!out.status.success());
    assert!(
        String::from_utf8_lossy(&out.stderr).contains("q_q1"),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn check_compares_every_seed_robot() {
    let out = dynamics().arg("check").output().expect("runs");
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{text}{}",
        String::from_utf8_lossy(&out.stderr)
    );
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
    let out = dynamics()
        .args(["eval", "--robot", "arm3r", "--states"])
        .arg(&states)
        .arg("--out")
        .arg(&out_file)
        .args(["--set", "m=0"])
        .output()
        .expect("runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let doc: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&out_file).expect("read")).expect("json");
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

#[test]
fn scenarios_run_by_name_and_write_csv_and_svg() {
    let dir = tmp("rrp-line");
    let out = dynamics()
        .args(["scenario", "rrp-line", "--out"])
        .arg(&dir)
        .output()
        .expect("runs");
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{text}{}",
        String::from_utf8_lossy(&out.stderr)
    );
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
    let bad = dynamics()
        .args(["scenario", "nope"])
        .output()
        .expect("runs");
    assert!(
        !bad.status.success() && String::from_utf8_lossy(&bad.stderr).contains("unknown scenario")
    );
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

/// A minimal well-formedness check of an SVG document: it is one `<svg>`
/// element, every tag opened is closed in order, every polyline's points
/// are finite numbers, and no NaN or infinity is written anywhere; returns
/// the number of polylines.
fn check_svg(name: &str, text: &str) -> usize {
    assert!(
        text.starts_with("<svg ") && text.trim_end().ends_with("</svg>"),
        "{name}"
    );
    for bad in ["NaN", "inf"] {
        assert!(!text.contains(bad), "{name} contains {bad}");
    }
    let mut stack: Vec<String> = Vec::new();
    let mut rest = text;
    let mut polylines = 0;
    while let Some(open) = rest.find('<') {
        let close = rest[open..].find('>').map(|c| open + c);
        let close = close.unwrap_or_else(|| panic!("{name}: unclosed tag"));
        let tag = &rest[open + 1..close];
        assert!(!tag.contains('<'), "{name}: `<` inside a tag: {tag}");
        if let Some(closing) = tag.strip_prefix('/') {
            assert_eq!(
                stack.pop().as_deref(),
                Some(closing),
                "{name}: </{closing}>"
            );
        } else {
            let element = tag.split_whitespace().next().unwrap_or("").to_string();
            if element == "polyline" {
                polylines += 1;
                let points = tag
                    .split("points=\"")
                    .nth(1)
                    .and_then(|p| p.split('"').next())
                    .unwrap_or_else(|| panic!("{name}: a polyline without points"));
                for pair in points.split_whitespace() {
                    let (x, y) = pair.split_once(',').expect("x,y");
                    for v in [x, y] {
                        let v: f64 = v.parse().unwrap_or_else(|_| panic!("{name}: `{v}`"));
                        assert!(v.is_finite(), "{name}: {v}");
                    }
                }
            }
            if !tag.ends_with('/') {
                stack.push(element);
            }
        }
        rest = &rest[close + 1..];
    }
    assert!(stack.is_empty(), "{name}: unclosed {stack:?}");
    polylines
}

#[test]
fn diagnose_writes_a_readable_report() {
    use dynamics_sim2real::effects::EffectKind;
    for (case, kind, joint) in [
        ("report-coulomb", EffectKind::CoulombFriction, Some("j1")),
        ("report-none", EffectKind::None, None),
    ] {
        let data = robots::builtin::synth(&dynamics_cli::gap::SynthRequest {
            robot: "arm3r".into(),
            kind: Some(kind),
            joint: joint.map(Into::into),
            magnitude: Some(0.4),
            seed: 11,
            excitation: "sines".parse().expect("an excitation"),
            duration: 4.0,
            noise: Default::default(),
        })
        .expect("synthesised");
        let (train, holdout, dir) = (
            tmp(&format!("{case}.csv")),
            tmp(&format!("{case}-holdout.csv")),
            tmp(case),
        );
        std::fs::write(&train, &data.train).expect("write");
        std::fs::write(&holdout, &data.holdout).expect("write");
        let out = dynamics()
            .args(["diagnose", "--robot", "arm3r", "--train"])
            .arg(&train)
            .arg("--holdout")
            .arg(&holdout)
            .arg("--report")
            .arg(&dir)
            .output()
            .expect("runs");
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let read = |f: &str| std::fs::read_to_string(dir.join(f)).expect(f);
        let report: serde_json::Value = serde_json::from_str(&read("report.json")).expect("json");
        let verdict = &report["which"]["verdict"];
        assert_eq!(verdict["kind"], kind.name(), "{case}");
        let md = read("report.md");
        match joint {
            Some(j) => {
                assert_eq!(verdict["joint"], j);
                assert!(md.contains(&format!("**{} at {j}**", kind.name())), "{md}");
                assert!(md.contains(&format!("The gap is at {j} (")), "{md}");
                let fraction = report["shrink"]["fraction"].as_f64().expect("a number");
                assert!(
                    md.contains(&format!("`shrink.fraction` = {fraction:.3}")),
                    "{md}"
                );
            }
            None => assert!(
                md.contains("**none**: the nominal model explains the data within noise"),
                "{md}"
            ),
        }
        // Lines: nominal (+ corrected with an effect); before and after;
        // measured, nominal, corrected.
        let mut svgs = vec![("ranking.svg".to_string(), 0)];
        for j in ["j1", "j2", "j3"] {
            let corrected = usize::from(joint.is_some());
            for (what, lines) in [("residual", 1 + corrected), ("shrink", 2), ("effort", 3)] {
                svgs.push((format!("{what}-{j}.svg"), lines));
            }
        }
        for (f, lines) in &svgs {
            assert!(
                md.contains(&format!("]({f})")),
                "report.md does not show {f}"
            );
            assert_eq!(check_svg(f, &read(f)), *lines, "{f}");
        }
        let ranked = report["which"]["ranked"].as_array().expect("ranked").len();
        let bars = read("ranking.svg").matches("<rect").count() - 1;
        assert_eq!(bars, ranked.min(12));
        // The prediction error's yardstick is what an exact model shows:
        // without an effect the ratio is about 1, with one far above.
        for j in report["where"]["joints"].as_array().expect("joints") {
            let ratio = j["prediction_ratio"].as_f64().expect("a number");
            match joint {
                None => assert!((0.3..2.0).contains(&ratio), "{case}: {j}"),
                Some(name) if j["joint"] == name => assert!(ratio > 10.0, "{case}: {j}"),
                Some(_) => {}
            }
        }
        // The gap windows of the JSON are the bands of the residual plots.
        for j in report["where"]["joints"].as_array().expect("joints") {
            let name = j["joint"].as_str().expect("a name");
            let svg = read(&format!("residual-{name}.svg"));
            let bands = svg.matches("fill=\"#ff7f0e\"").count();
            assert_eq!(
                bands,
                j["windows"].as_array().expect("windows").len(),
                "{name}"
            );
        }
    }
}

/// `duration` s of arm3r training and held-out data (seed 21, sines) with
/// Coulomb friction of 0.2 N m at j3, as the CSVs `synth` writes.
fn arm3r_coulomb_j3(
    duration: f64,
) -> (
    dynamics_sim2real::data::Measured<3>,
    dynamics_sim2real::data::Measured<3>,
) {
    use dynamics_runtime::Robot;
    use dynamics_sim2real::data::read_csv_str;
    use dynamics_sim2real::effects::EffectKind;
    let data = robots::builtin::synth(&dynamics_cli::gap::SynthRequest {
        robot: "arm3r".into(),
        kind: Some(EffectKind::CoulombFriction),
        joint: Some("j3".into()),
        magnitude: Some(0.2),
        seed: 21,
        excitation: "sines".parse().expect("an excitation"),
        duration,
        noise: Default::default(),
    })
    .expect("synthesised");
    let read = |text: &str| read_csv_str(text, &robots::Arm3r::JOINT_NAMES, "synth").expect("CSV");
    (read(&data.train), read(&data.holdout))
}

#[test]
fn report_traces_carry_the_fitted_effect() {
    use dynamics_sim2real::diagnose::{diagnose, traces::traces, Options};
    use robots::Arm3r;
    let (train, holdout) = arm3r_coulomb_j3(8.0);
    let robot = Arm3r::default();
    let report =
        diagnose(&robot, &train, &holdout, &Options::default(), &|_, _| {}).expect("diagnosed");
    let top = &report.which.ranked[0];
    assert_eq!(
        (top.kind.as_str(), top.joint.as_deref()),
        ("coulomb_friction", Some("j3"))
    );
    let fc = top.parameters[0].value;
    let t = traces(&robot, &train, &holdout, Some(top), None).expect("traces");
    for data in [&t.train, &t.holdout] {
        for (j, jt) in data.joints.iter().enumerate() {
            assert_eq!(jt.measured.len(), data.t.len());
            for k in 0..data.t.len() {
                // The definitions: residuals are measured minus each model.
                assert!((jt.residual[k] - (jt.measured[k] - jt.nominal[k])).abs() < 1e-9);
                assert!((jt.residual_after[k] - (jt.measured[k] - jt.corrected[k])).abs() < 1e-9);
                // Coulomb friction at j3 changes j3's effort only, by at most
                // fc (the friction column is a smoothed sign, and the
                // Savitzky-Golay fit of a step overshoots it by a few per cent).
                let added = jt.corrected[k] - jt.nominal[k];
                if j == 2 {
                    assert!(added.abs() <= fc * 1.05, "{added} vs fc {fc}");
                } else {
                    assert_eq!(added, 0.0);
                }
            }
            if j == 2 {
                // Moving fast, the added effort is the whole fitted fc.
                let peak = (0..data.t.len())
                    .map(|k| (jt.corrected[k] - jt.nominal[k]).abs())
                    .fold(0.0, f64::max);
                assert!(peak > 0.98 * fc, "{peak} vs {fc}");
                let rms =
                    |v: &[f64]| (v.iter().map(|x| x * x).sum::<f64>() / v.len() as f64).sqrt();
                assert!(rms(&jt.residual_after) < 0.6 * rms(&jt.residual));
            }
        }
    }
    // Every ranked entry (every kind of the vocabulary, with its grid
    // parameter) maps back to a candidate whose series are finite.
    for r in &report.which.ranked {
        let t = traces(&robot, &train, &holdout, Some(r), None).expect("every ranked entry");
        for jt in t.train.joints.iter().chain(&t.holdout.joints) {
            assert!(
                jt.corrected.iter().all(|x| x.is_finite()),
                "{} {:?}",
                r.kind,
                r.joint
            );
        }
    }
    // Without an effect, "corrected" is the nominal model.
    let t = traces(&robot, &train, &holdout, None, None).expect("traces");
    assert!(t.holdout.joints.iter().all(|j| j.corrected == j.nominal));
    // A ranked entry naming a joint the robot lacks is an error, not a panic.
    let mut wrong = top.clone();
    wrong.joint = Some("j9".into());
    let err = traces(&robot, &train, &holdout, Some(&wrong), None).expect_err("no j9");
    assert!(err.to_string().contains("no joint `j9`"), "{err}");
}

/// An effect that starts and stops, from the command line to the JSON
/// report: `synth --window` limits the payload to [2, 4.5) s in training
/// (1.5 to 4 s held out), the truth file records both windows, and the
/// report's `which.effects[].window` has the training window found from
/// the data.
#[test]
fn a_windowed_effect_is_generated_and_found_with_its_window() {
    let train = tmp("window.csv");
    let truth = tmp("window-truth.json");
    let out = dynamics()
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
        .arg(&truth)
        .output()
        .expect("runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let t: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&truth).expect("truth")).expect("json");
    assert_eq!(t["window"], serde_json::json!({"start": 2.0, "end": 4.5}));
    assert_eq!(
        t["holdout_window"],
        serde_json::json!({"start": 1.5, "end": 4.0})
    );
    let json = tmp("window-report.json");
    let out = dynamics()
        .args(["diagnose", "--robot", "arm3r", "--train"])
        .arg(&train)
        .arg("--holdout")
        .arg(train.with_file_name("window-holdout.csv"))
        .arg("--json")
        .arg(&json)
        .output()
        .expect("runs");
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{text}");
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).expect("report")).expect("json");
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
    let out = dynamics()
        .args(["synth", "--robot", "arm3r", "--effect", "none"])
        .args(["--window", "1:2", "--out"])
        .arg(tmp("none.csv"))
        .output()
        .expect("runs");
    assert!(!out.status.success());
    assert!(
        String::from_utf8_lossy(&out.stderr).contains("a window needs an effect"),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let out = dynamics()
        .args(["synth", "--robot", "arm3r", "--window", "2", "--out"])
        .arg(tmp("bad.csv"))
        .output()
        .expect("runs");
    assert!(
        String::from_utf8_lossy(&out.stderr).contains("--window: window `2`: expected START:END"),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// The regression of the last commit on main: 4 s of arm3r data where j3's
/// training velocity never reverses. Coulomb friction there is named, as
/// ambiguous with an effort offset at j3 (these data cannot tell them
/// apart), never `unexplained`.
#[test]
fn coulomb_friction_where_the_velocity_never_reverses_is_ambiguous() {
    use dynamics_sim2real::diagnose::{diagnose, Options};
    use robots::Arm3r;
    let (train, holdout) = arm3r_coulomb_j3(4.0);
    let report = diagnose(
        &Arm3r::default(),
        &train,
        &holdout,
        &Options::default(),
        &|_, _| {},
    )
    .expect("diagnosed");
    let v = &report.which.verdict;
    eprintln!("{v:?}");
    assert_eq!(
        (v.kind.as_str(), v.joint.as_deref(), v.status.as_str()),
        ("coulomb_friction", Some("j3"), "ambiguous")
    );
    let rival = v.rival.as_ref().expect("a rival");
    assert_eq!(
        (rival.kind.as_str(), rival.joint.as_deref()),
        ("effort_offset", Some("j3"))
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
    let out = dynamics()
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
        .arg(&truth)
        .output()
        .expect("runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let t: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&truth).expect("truth")).expect("json");
    assert_eq!(t["late"], "effort");
    let json = tmp("tau-late-report.json");
    let out = dynamics()
        .args(["diagnose", "--robot", "arm3r", "--train"])
        .arg(&train)
        .arg("--holdout")
        .arg(train.with_file_name("tau-late-holdout.csv"))
        .arg("--json")
        .arg(&json)
        .output()
        .expect("runs");
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{text}");
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).expect("report")).expect("json");
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
    let out = dynamics()
        .args([
            "synth",
            "--robot",
            "arm3r",
            "--effect",
            "none",
            "--tau-late=-0.01",
            "--out",
        ])
        .arg(tmp("bad-late.csv"))
        .output()
        .expect("runs");
    assert!(!out.status.success());
    assert!(
        String::from_utf8_lossy(&out.stderr).contains(
            "tau-late must be a delay of at least 0 s, shorter than the record (8 s), got -0.01"
        ),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}
