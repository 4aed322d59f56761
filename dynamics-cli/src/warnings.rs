//! Warnings as a reader wants them: one line each, except that the
//! glitches of one row (a logger hiccup that throws every column of a row
//! off course, as in FloBaRoID's KUKA records) are one line naming the
//! columns. The JSON report keeps them one by one.

use dynamics_sim2real::Warning;

/// The lines of `warnings`, in order, a row's glitches together.
///
/// ```
/// use dynamics_cli::warnings::lines;
/// use dynamics_sim2real::Warning;
/// let glitch = |column: &str, sigmas: f64| Warning::Glitch {
///     file: "run.csv".into(), line: 455, column: column.into(), value: 0.3, sigmas,
/// };
/// let said = lines(&[glitch("q_0", 24.0), glitch("q_1", 47.0), glitch("tau_1", 45.0)]);
/// assert_eq!(said, vec![
///     "run.csv:455: glitches in 3 columns (`q_0`, `q_1`, `tau_1`; 24 to 47 sigma off their course): excluded from every fit".to_string(),
/// ]);
/// ```
pub fn lines(warnings: &[Warning]) -> Vec<String> {
    let mut out = Vec::new();
    let mut i = 0;
    while i < warnings.len() {
        let Warning::Glitch { file, line, .. } = &warnings[i] else {
            out.push(warnings[i].to_string());
            i += 1;
            continue;
        };
        let row: Vec<(&String, f64)> = warnings[i..]
            .iter()
            .map_while(|w| match w {
                Warning::Glitch {
                    file: f,
                    line: l,
                    column,
                    sigmas,
                    ..
                } if f == file && l == line => Some((column, *sigmas)),
                _ => None,
            })
            .collect();
        if row.len() == 1 {
            out.push(warnings[i].to_string());
        } else {
            let columns: Vec<String> = row.iter().map(|(c, _)| format!("`{c}`")).collect();
            let lo = row.iter().map(|r| r.1).fold(f64::INFINITY, f64::min);
            let hi = row.iter().map(|r| r.1).fold(0.0, f64::max);
            let (lo, hi) = (sigmas(lo), sigmas(hi));
            let range = if lo == hi {
                lo
            } else {
                format!("{lo} to {hi}")
            };
            out.push(format!(
                "{file}:{line}: glitches in {} columns ({}; {range} sigma off their course): excluded from every fit",
                row.len(),
                columns.join(", "),
            ));
        }
        i += row.len();
    }
    out
}

/// A departure in robust deviations, as [`Warning`]'s words give it.
fn sigmas(x: f64) -> String {
    if x < 1e6 {
        format!("{x:.0}")
    } else {
        format!("{x:.1e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A lone glitch keeps its own words; glitches of two rows are two
    /// lines; other warnings pass through in their place.
    #[test]
    fn a_rows_glitches_are_one_line() {
        let glitch = |line: usize, column: &str| Warning::Glitch {
            file: "a.csv".into(),
            line,
            column: column.into(),
            value: 1.0,
            sigmas: 20.0,
        };
        let more = Warning::MoreGlitches {
            file: "a.csv".into(),
            count: 4,
        };
        let ws = [
            glitch(10, "q_0"),
            glitch(12, "q_0"),
            glitch(12, "qd_0"),
            more.clone(),
        ];
        let said = lines(&ws);
        assert_eq!(said.len(), 3, "{said:?}");
        assert_eq!(said[0], ws[0].to_string());
        assert!(said[1].starts_with("a.csv:12: glitches in 2 columns (`q_0`, `qd_0`; 20 sigma off"));
        assert_eq!(said[2], more.to_string());
    }
}
