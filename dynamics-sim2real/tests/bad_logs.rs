//! Real logs as they come (issue 15), each damage with its message pinned:
//! an irregular clock, repeated samples, holes, glitches (and too many of
//! them), a time column in milliseconds, a file that ends in the middle of
//! a row, an effort column of the wrong sign, a record where nothing moves,
//! a joint whose velocity never reverses, a slow rate.

use dynamics_sim2real::data::{read_csv_str, write_csv, DataError, Measured};
use dynamics_sim2real::diagnose::{diagnose, DiagnoseError, Options, Report};
use dynamics_sim2real::effects::Effect;
use dynamics_sim2real::synth::{synthesize, Damage, SynthOptions};
use dynamics_sim2real::Warning;

mod common;
use common::Arm2;

const JOINTS: [&str; 2] = ["j1", "j2"];

fn opts(seed: u64, rate: f64, damage: Damage) -> SynthOptions<2> {
    SynthOptions {
        duration: 4.0,
        rate,
        home: [0.0, 0.4].into(),
        amplitude: [0.6, 0.6].into(),
        seed,
        damage,
        ..Default::default()
    }
}

fn text(m: &Measured<2>) -> String {
    let mut out = Vec::new();
    write_csv(&mut out, m, &JOINTS).expect("writes");
    String::from_utf8(out).expect("utf8")
}

fn log(effects: &[Effect], rate: f64, damage: Damage, seed: u64) -> String {
    text(&synthesize(&Arm2::default(), effects, &opts(seed, rate, damage)).expect("synthesizes"))
}

fn read(text: &str, file: &str) -> Result<Measured<2>, DataError> {
    read_csv_str(text, &JOINTS, file)
}

fn diagnosed(a: &str, b: &str) -> Result<Report, DiagnoseError> {
    let a = read(a, "a.csv").expect("reads");
    let b = read(b, "b.csv").expect("reads");
    diagnose(&Arm2::default(), &a, &b, &Options::default(), &|_, _| {})
}

fn messages(w: &[Warning]) -> Vec<String> {
    w.iter().map(ToString::to_string).collect()
}

#[test]
fn a_jittered_clock_is_brought_onto_a_grid_with_the_jitter_said() {
    let damage = Damage {
        jitter: 0.3,
        ..Damage::default()
    };
    let m = read(&log(&[], 1000.0, damage, 3), "a.csv").expect("reads");
    assert_eq!(m.warnings.len(), 1, "{:?}", messages(&m.warnings));
    let Warning::Resampled {
        interval,
        jitter,
        min,
        max,
        ..
    } = m.warnings[0]
    else {
        panic!("{:?}", m.warnings);
    };
    // Uniform factors in 1 +- 0.3: RMS 0.3 / sqrt(3) = 17.3 %.
    assert!((interval - 1e-3).abs() < 3e-5, "{interval}");
    assert!((jitter - 0.173).abs() < 0.01, "{jitter}");
    assert!(min >= 0.7e-3 - 1e-9 && max <= 1.3e-3 + 1e-9);
    let w = m.warnings[0].to_string();
    assert!(
        w.starts_with("a.csv: irregular clock (intervals 7.0"),
        "{w}"
    );
    assert!(w.contains("RMS jitter 17."), "{w}");
    assert!(
        w.ends_with("by linear interpolation at the true times"),
        "{w}"
    );
    let steps: Vec<f64> = m.t.windows(2).map(|w| w[1] - w[0]).collect();
    assert!(steps.iter().all(|d| (d - interval).abs() < 1e-9));
}

#[test]
fn repeated_rows_are_missing_and_said() {
    let damage = Damage {
        repeats: 0.06,
        ..Damage::default()
    };
    let m = read(&log(&[], 1000.0, damage, 4), "a.csv").expect("reads");
    // 240 repeats: in turn the whole row but the time (q, qd, tau), only
    // the positions, only the efforts (draws may land on the same row).
    let repeated: Vec<&Warning> = m
        .warnings
        .iter()
        .filter(|w| matches!(w, Warning::Repeated { .. }))
        .collect();
    let said = messages(&m.warnings);
    assert_eq!(repeated.len(), 3, "{said:?}");
    for (w, (quantity, lo, hi)) in
        repeated
            .iter()
            .zip([("q", 150, 160), ("qd", 75, 80), ("tau", 150, 160)])
    {
        let Warning::Repeated {
            quantity: q, rows, ..
        } = w
        else {
            unreachable!()
        };
        assert_eq!(q, quantity);
        assert!((lo..=hi).contains(rows), "{said:?}");
        assert!(w.to_string().ends_with(&format!(
            "repeat the previous row's `{quantity}` exactly: treated as missing"
        )));
    }
    // Nothing else is found but, where three or more rows in a row repeat,
    // a hole.
    assert!(
        m.warnings
            .iter()
            .all(|w| matches!(w, Warning::Repeated { .. } | Warning::Hole { .. })),
        "{said:?}"
    );
    let missing = m.missing.iter().filter(|&&x| x).count();
    assert!((220..=250).contains(&missing), "{missing}");
}

#[test]
fn a_whole_row_written_twice_is_dropped_and_said() {
    let text = log(&[], 1000.0, Damage::default(), 5);
    let mut lines: Vec<&str> = text.lines().collect();
    let twice = lines[700];
    lines.insert(701, twice);
    let m = read(&(lines.join("\n") + "\n"), "a.csv").expect("reads");
    assert_eq!(
        messages(&m.warnings),
        vec![
            "a.csv:702: 1 rows (0.0 %) repeat the previous row's `row` exactly: treated as missing"
        ]
    );
    assert_eq!(m.len(), 4001);
}

#[test]
fn holes_split_the_record_and_are_said_with_their_lines() {
    let damage = Damage {
        holes: 2,
        hole_length: 0.1,
        ..Damage::default()
    };
    let text = log(&[], 1000.0, damage, 6);
    let m = read(&text, "a.csv").expect("reads");
    let said = messages(&m.warnings);
    assert_eq!(said.len(), 2, "{said:?}");
    assert_eq!(m.holes.len(), 2);
    for (w, &(a, b)) in m.warnings.iter().zip(&m.holes) {
        let Warning::Hole {
            line, start, end, ..
        } = w
        else {
            panic!("{said:?}")
        };
        // The line is the first row after the hole, as in the file.
        let row: Vec<f64> = text
            .lines()
            .nth(line - 1)
            .expect("line")
            .split(',')
            .map(|c| c.parse().expect("number"))
            .collect();
        assert_eq!(row[0], *end);
        assert!((end - start - 0.101).abs() < 1.5e-3, "{start} {end}");
        assert!(b - a >= 99 && b - a <= 101, "{a} {b}");
        assert!(m.missing[a..b].iter().all(|&x| x));
    }
    assert!(
        said[0].contains(": hole of 0.10")
            && said[0].ends_with(
                "the record is split there; nothing is interpolated or differentiated across it"
            ),
        "{said:?}"
    );
}

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
fn a_time_column_in_milliseconds_is_said() {
    let text = log(&[], 1000.0, Damage::default(), 9);
    let ms: Vec<String> = text
        .lines()
        .enumerate()
        .map(|(i, l)| {
            if i == 0 {
                return l.to_string();
            }
            let (t, rest) = l.split_once(',').expect("row");
            format!("{},{rest}", t.parse::<f64>().expect("t") * 1000.0)
        })
        .collect();
    let e = read(&(ms.join("\n") + "\n"), "a.csv").unwrap_err();
    assert_eq!(
        e.to_string(),
        "a.csv: time looks like milliseconds (the positions change 1000 times slower per unit of `t` than the recorded velocities say); write `t` in seconds"
    );
    // Without velocities: from the interval alone.
    let no_qd: Vec<String> = ms
        .iter()
        .map(|l| {
            let c: Vec<&str> = l.split(',').collect();
            [c[0], c[1], c[2], c[5], c[6]].join(",")
        })
        .collect();
    let e = read(&(no_qd.join("\n") + "\n"), "a.csv").unwrap_err();
    assert_eq!(
        e.to_string(),
        "a.csv: time looks like milliseconds (the median interval is 1 of its unit, a rate of 1.00 samples per unit); write `t` in seconds"
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

/// A record where the robot holds still (the effort its weight needs).
fn still(seed: u64) -> String {
    let arm = Arm2::default();
    let mut o = opts(seed, 1000.0, Damage::default());
    o.amplitude = [0.0, 0.0].into();
    text(&synthesize(&arm, &[Effect::coulomb(0, 0.5)], &o).expect("synthesizes"))
}

#[test]
fn a_record_where_nothing_moves_is_a_clear_error() {
    let e = diagnosed(&still(13), &still(14)).unwrap_err();
    assert_eq!(
        e.to_string(),
        "training data: no joint moves; nothing about the robot can be identified from them"
    );
}

#[test]
fn a_joint_that_does_not_move_gets_no_candidate() {
    // Joint j1 still, joint j2 moving: j1 is named as not moving.
    let arm = Arm2::default();
    let mut o = opts(15, 1000.0, Damage::default());
    o.amplitude = [0.0, 0.6].into();
    let a = text(&synthesize(&arm, &[], &o).expect("synthesizes"));
    o.seed = 16;
    let b = text(&synthesize(&arm, &[], &o).expect("synthesizes"));
    let r = diagnosed(&a, &b).expect("diagnoses");
    let said = messages(&r.warnings);
    assert!(
        said.iter()
            .any(|s| s.starts_with("joint j1: does not move (peak speed")),
        "{said:?}"
    );
    assert!(r
        .which
        .ranked
        .iter()
        .all(|c| c.joint.as_deref() != Some("j1")));
    assert!(!r.which.verdict.names_effect(), "{:?}", r.which.verdict);
}

#[test]
fn at_100_hz_fast_signatures_are_not_guessed() {
    let a = log(&[], 100.0, Damage::default(), 17);
    let b = log(&[], 100.0, Damage::default(), 18);
    let r = diagnosed(&a, &b).expect("diagnoses");
    let said = messages(&r.warnings);
    assert_eq!(
        said,
        vec![
            "`backlash` (signatures up to 40 Hz) is not identifiable above 25 Hz on these data (sampled at 100 Hz; a signature needs four samples a period): searched only below, not guessed",
            "`joint_elasticity` (signatures up to 45 Hz) is not identifiable above 25 Hz on these data (sampled at 100 Hz; a signature needs four samples a period): searched only below, not guessed",
        ]
    );
    assert!(r.which.ranked.iter().all(|c| c.kind != "backlash"));
    assert_eq!(r.which.verdict.kind, "none");
}
