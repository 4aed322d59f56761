//! Damage to a log's clock and rows: an irregular clock, repeated
//! samples, a row written twice, holes, a time column in milliseconds.

use dynamics_sim2real::synth::Damage;
use dynamics_sim2real::Warning;

use crate::{log, messages, read};

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
