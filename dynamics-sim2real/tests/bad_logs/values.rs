//! Damage to a log's values: glitches (and too many of them), a file that
//! ends in the middle of a row, an effort column of the wrong sign.

use dynamics_sim2real::synth::Damage;

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
