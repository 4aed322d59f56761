//! Damage to a log's values: glitches (and too many of them), a file that
//! ends in the middle of a row, an effort column of the wrong sign (and one
//! that only looks so).

use dynamics_runtime::Robot;
use dynamics_sim2real::data::Measured;
use dynamics_sim2real::effects::Effect;
use dynamics_sim2real::synth::Damage;

use crate::common::Arm2;
use crate::{diagnosed, log, messages, read};

#[test]
fn glitches_are_found_with_file_line_and_column() {
    let text = log(&[], 1000.0, Damage::default(), 7);
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    // Columns: t, q_j1, q_j2, qd_j1, qd_j2, tau_j1, tau_j2.
    let set = |lines: &mut Vec<String>, line: usize, col: usize, f: &dyn Fn(f64) -> f64| {
        let mut cells: Vec<String> = lines[line - 1].split(',').map(str::to_string).collect();
        cells[col] = format!("{}", f(cells[col].parse().expect("number")));
        lines[line - 1] = cells.join(",");
    };
    set(&mut lines, 1000, 5, &|_| 1e300);
    set(&mut lines, 2000, 6, &|x| x + 50.0 * 0.02); // effort noise ~0.2 % of ~10 N m
    set(&mut lines, 3000, 2, &|x| -x);
    let m = read(&(lines.join("\n") + "\n"), "a.csv").expect("reads");
    let said = messages(&m.warnings);
    assert_eq!(said.len(), 3, "{said:?}");
    assert!(
        said[0].starts_with("a.csv:1000: column `tau_j1`: glitch 1.0000e300 ("),
        "{said:?}"
    );
    assert!(
        said[1].starts_with("a.csv:2000: column `tau_j2`: glitch "),
        "{said:?}"
    );
    assert!(
        said[2].starts_with("a.csv:3000: column `q_j2`: glitch -"),
        "{said:?}"
    );
    assert!(said
        .iter()
        .all(|s| s.ends_with("sigma off its course): excluded from every fit")));
    assert!(m.tau.iter().all(|v| v.iter().all(|x| x.abs() < 1e3)));
    // Line 1000 is sample 998; each glitch is the only sample missing.
    let missing: Vec<usize> = (0..m.len()).filter(|&k| m.missing[k]).collect();
    assert_eq!(missing, vec![998, 1998, 2998]);
}

#[test]
fn too_many_glitches_are_an_error() {
    let text = log(&[], 1000.0, Damage::default(), 8);
    let lines: Vec<String> = text
        .lines()
        .enumerate()
        .map(|(i, l)| {
            if i > 10 && i % 50 == 0 {
                let mut c: Vec<&str> = l.split(',').collect();
                c[5] = "1e300";
                c.join(",")
            } else {
                l.to_string()
            }
        })
        .collect();
    // 80 rows set to 1e300; the last row's has no samples after it to tell
    // a spike from a step, and is not tested.
    let e = read(&(lines.join("\n") + "\n"), "a.csv").unwrap_err();
    assert_eq!(
        e.to_string(),
        "a.csv: column `tau_j1`: 79 of 4001 samples are glitches (far off their signal's course); more than 1 % (and 10) is not a log to diagnose"
    );
}

#[test]
fn a_file_that_ends_in_the_middle_of_a_row_names_its_line() {
    let text = log(&[], 1000.0, Damage::default(), 10);
    let cut = &text[..text.len() - 20];
    let e = read(cut, "a.csv").unwrap_err();
    let last = cut.lines().count();
    let fields = cut.lines().last().expect("line").split(',').count();
    assert_eq!(
        e.to_string(),
        format!("a.csv:{last}: {fields} fields where the header has 7 (the file ends in the middle of a row)")
    );
}

#[test]
fn an_effort_column_of_the_wrong_sign_is_named_with_its_joint() {
    let a = log(&[], 1000.0, Damage::default(), 11);
    let b = log(&[], 1000.0, Damage::default(), 12);
    let flip = |text: &str| -> String {
        text.lines()
            .enumerate()
            .map(|(i, l)| {
                if i == 0 {
                    return l.to_string() + "\n";
                }
                let mut c: Vec<String> = l.split(',').map(str::to_string).collect();
                c[5] = format!("{}", -c[5].parse::<f64>().expect("tau"));
                c.join(",") + "\n"
            })
            .collect()
    };
    let e = diagnosed(&flip(&a), &b).unwrap_err();
    let s = e.to_string();
    assert!(
        s.starts_with("training data: joint j1: the measured effort correlates negatively with the nominal model's (r = -"),
        "{s}"
    );
    assert!(s.ends_with("is the effort column's sign flipped?"), "{s}");
}

/// An effort mostly made of what the model lacks is diagnosed, not taken
/// for a flipped column, even where it anticorrelates with the model's: a
/// stiff spring at `j1` of the two-link arm, whose effort (+k q) on this
/// motion runs against the arm's own (r = -0.68). The KUKA LWR4+'s `lwr_4`
/// and `lwr_6` without friction in the model (README, "Real logs") were
/// refused so.
#[test]
fn an_effort_that_the_model_mostly_lacks_is_not_a_flipped_column() {
    let spring = [Effect::JointSpring {
        joint: 0,
        stiffness: 40.0,
        preload: 0.0,
    }];
    let (a, b) = (
        log(&spring, 1000.0, Damage::default(), 13),
        log(&spring, 1000.0, Damage::default(), 14),
    );
    let r = correlation_with_model(&read(&a, "a.csv").expect("reads"), 0);
    assert!(r < -0.5, "the case needs an anticorrelation, got {r}");
    let report = diagnosed(&a, &b).expect("diagnosed");
    assert!(
        report
            .which
            .effects
            .iter()
            .any(|e| e.kind.name() == "joint_spring" && e.joint.as_deref() == Some("j1")),
        "{:?}",
        report.which.effects
    );
}

/// The correlation of joint `j`'s measured effort with the two-link arm's
/// inverse dynamics on the measured motion (accelerations by central
/// differences of the velocities).
fn correlation_with_model(m: &Measured<2>, j: usize) -> f64 {
    let arm = Arm2::default();
    let pairs: Vec<(f64, f64)> = (1..m.len() - 1)
        .map(|k| {
            let qdd = (m.qd[k + 1] - m.qd[k - 1]) / (m.t[k + 1] - m.t[k - 1]);
            (
                m.tau[k][j],
                arm.inverse_dynamics(&m.q[k], &m.qd[k], &qdd)[j],
            )
        })
        .collect();
    let n = pairs.len() as f64;
    let (my, mx) = pairs
        .iter()
        .fold((0.0, 0.0), |(a, b), (y, x)| (a + y / n, b + x / n));
    let (sxy, sxx, syy) = pairs.iter().fold((0.0, 0.0, 0.0), |(a, b, c), (y, x)| {
        (
            a + (x - mx) * (y - my),
            b + (x - mx).powi(2),
            c + (y - my).powi(2),
        )
    });
    sxy / (sxx * syy).sqrt()
}
