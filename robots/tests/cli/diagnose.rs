//! `dynamics diagnose` of data files (stated sensor noise, a file for
//! another robot), and the diagnosis the program runs: the report's
//! traces, a friction whose velocity never reverses.

use crate::{diagnose_arm3r, dynamics, fails_with, read_json, succeeds, tmp};

#[test]
fn synth_then_diagnose_from_files_writes_the_json_report() {
    let train = tmp("synth.csv");
    let truth = tmp("truth.json");
    succeeds(
        dynamics()
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
            .arg(&truth),
    );
    let holdout = train.with_file_name("synth-holdout.csv");
    let json = tmp("report.json");
    succeeds(diagnose_arm3r(&train, &holdout).arg("--json").arg(&json));
    let report = read_json(&json);
    assert_eq!(report["which"]["verdict"]["kind"], "viscous_friction");
    assert_eq!(report["which"]["verdict"]["joint"], "j3");
    assert!(report["shrink"]["fraction"].as_f64().expect("number") > 0.8);
    // Stated sensor noise: the truth file's effort noise (per joint) is
    // accepted and gives the same verdict; a wrong count is refused.
    let truth_json = read_json(&truth);
    let noise_tau: Vec<String> = truth_json["noise_tau"]
        .as_array()
        .expect("noise_tau")
        .iter()
        .map(|v| v.as_f64().expect("number").to_string())
        .collect();
    assert_eq!(noise_tau.len(), 3);
    let stated = |tau: &str| {
        diagnose_arm3r(&train, &holdout)
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
    fails_with(
        dynamics()
            .args(["diagnose", "--robot", "rrp", "--train"])
            .arg(&train)
            .arg("--holdout")
            .arg(&holdout),
        "q_q1",
    );
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
        (top.kind.name(), top.joint.as_deref()),
        ("coulomb_friction", Some("j3"))
    );
    let fc = top.parameters[0].value;
    let t = traces(&robot, &train, &holdout, Some(top), &Options::default()).expect("traces");
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
        let t = traces(&robot, &train, &holdout, Some(r), &Options::default())
            .expect("every ranked entry");
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
    let t = traces(&robot, &train, &holdout, None, &Options::default()).expect("traces");
    assert!(t.holdout.joints.iter().all(|j| j.corrected == j.nominal));
    // A ranked entry naming a joint the robot lacks is an error, not a panic.
    let mut wrong = top.clone();
    wrong.joint = Some("j9".into());
    let err =
        traces(&robot, &train, &holdout, Some(&wrong), &Options::default()).expect_err("no j9");
    assert!(err.to_string().contains("no joint `j9`"), "{err}");
}

/// 4 s of arm3r data where j3's training velocity never reverses: Coulomb
/// friction there is named, as ambiguous with an effort offset at j3 (these
/// data cannot tell them apart), never `unexplained`.
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
        (v.kind.name(), v.joint.as_deref(), v.status.name()),
        ("coulomb_friction", Some("j3"), "ambiguous")
    );
    let rival = v.rival.as_ref().expect("a rival");
    assert_eq!(
        (rival.kind.name(), rival.joint.as_deref()),
        ("effort_offset", Some("j3"))
    );
}
