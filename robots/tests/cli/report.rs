//! `dynamics diagnose --report`: the readable report, its plots checked
//! as well-formed SVG with the lines and bands the JSON report implies.

use crate::{diagnose_arm3r, succeeds, tmp};

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
        succeeds(diagnose_arm3r(&train, &holdout).arg("--report").arg(&dir));
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
