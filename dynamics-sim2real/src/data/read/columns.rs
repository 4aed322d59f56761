//! The header of a data file matched to the robot's joints: which column
//! holds `t` and each joint's `q`, `qd`, `tau`, with a "did you mean" for a
//! near miss, an error for a column naming no joint, and a warning for
//! each column ignored.

use super::DataError;
use crate::Warning;

/// Column indices of the quantities of `N` joints, and the columns ignored.
pub(super) struct Columns<const N: usize> {
    /// The time column.
    pub(super) t: usize,
    /// Each joint's position column.
    pub(super) q: [usize; N],
    /// Each joint's effort column.
    pub(super) tau: [usize; N],
    /// Each joint's velocity column, if the file has all of them.
    pub(super) qd: Option<[usize; N]>,
    /// One per column ignored.
    pub(super) warnings: Vec<Warning>,
}

impl<const N: usize> Columns<N> {
    /// Matches `header` to `joints`; `file` names the file in errors.
    pub(super) fn find(
        header: &[String],
        joints: &[&str; N],
        file: &str,
    ) -> Result<Self, DataError> {
        let find = |name: &str| header.iter().position(|h| h == name);
        let joint_list = joints.join(", ");
        let missing = |column: String| {
            let hint = header
                .iter()
                .find(|h| h.eq_ignore_ascii_case(&column) || close(h, &column))
                .map(|h| format!(" (there is `{h}`: did you mean `{column}`?)"))
                .unwrap_or_else(|| format!(" (the robot's joints: {joint_list})"));
            DataError::MissingColumn {
                file: file.to_string(),
                column,
                hint,
            }
        };
        let t_col = find("t").ok_or_else(|| missing("t".into()))?;
        let cols = |prefix: &str, required: bool| -> Result<Option<[usize; N]>, DataError> {
            let mut out = [0; N];
            for (i, j) in joints.iter().enumerate() {
                let name = format!("{prefix}_{j}");
                match find(&name) {
                    Some(c) => out[i] = c,
                    None if required => return Err(missing(name)),
                    None => return Ok(None),
                }
            }
            Ok(Some(out))
        };
        let q_cols = cols("q", true)?.unwrap_or([0; N]);
        let tau_cols = cols("tau", true)?.unwrap_or([0; N]);
        let qd_cols = cols("qd", false)?;
        let mut warnings = Vec::new();
        for h in header {
            let used = h == "t"
                || joints
                    .iter()
                    .any(|j| ["q", "qd", "tau"].iter().any(|p| *h == format!("{p}_{j}")));
            if used {
                continue;
            }
            if let Some(rest) = ["q_", "qd_", "tau_"].iter().find_map(|p| h.strip_prefix(p)) {
                if !rest.is_empty() && !h.starts_with("qdd_") {
                    return Err(DataError::UnknownJoint {
                        file: file.to_string(),
                        column: h.clone(),
                        joints: joint_list,
                    });
                }
            }
            warnings.push(Warning::ColumnIgnored {
                file: file.to_string(),
                column: h.clone(),
            });
        }
        Ok(Columns {
            t: t_col,
            q: q_cols,
            tau: tau_cols,
            qd: qd_cols,
            warnings,
        })
    }
}

/// One edit apart (a typo), for "did you mean".
fn close(a: &str, b: &str) -> bool {
    let (a, b): (Vec<char>, Vec<char>) = (a.chars().collect(), b.chars().collect());
    if a.len().abs_diff(b.len()) > 1 {
        return false;
    }
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    for i in 1..=a.len() {
        let mut cur = vec![i; b.len() + 1];
        for j in 1..=b.len() {
            let sub = prev[j - 1] + usize::from(a[i - 1] != b[j - 1]);
            cur[j] = sub.min(prev[j] + 1).min(cur[j - 1] + 1);
        }
        prev = cur;
    }
    prev[b.len()] <= 1
}

#[cfg(test)]
mod tests {
    use crate::data::read_csv_str;

    fn rows(n: usize, f: impl Fn(usize) -> String) -> String {
        (0..n).map(f).collect()
    }

    #[test]
    fn every_kind_of_bad_header_is_named() {
        let ok = |k: usize| format!("{},0,0,1\n", k as f64 * 1e-3);
        let e = read_csv_str::<1>(
            &format!("t,q_j,qd_j,torque_j\n{}", rows(300, ok)),
            &["j"],
            "a.csv",
        )
        .unwrap_err();
        assert!(e.to_string().contains("no column `tau_j`"), "{e}");
        let e = read_csv_str::<1>(
            &format!("t,q_J,qd_j,tau_j\n{}", rows(300, ok)),
            &["j"],
            "a.csv",
        )
        .unwrap_err();
        assert!(e.to_string().contains("did you mean `q_j`"), "{e}");
        let e = read_csv_str::<1>(
            &format!(
                "t,q_j,qd_j,tau_j,q_k\n{}",
                rows(300, |k| format!("{},0,0,1,0\n", k))
            ),
            &["j"],
            "a.csv",
        )
        .unwrap_err();
        assert!(e.to_string().contains("`q_k` names no joint"), "{e}");
        let m = read_csv_str::<1>(
            &format!(
                "t,q_j,qd_j,tau_j,temp\n{}",
                rows(300, |k| format!("{},0,0,1,20\n", k as f64 * 1e-3))
            ),
            &["j"],
            "a.csv",
        )
        .unwrap();
        let text: Vec<String> = m.warnings.iter().map(|w| w.to_string()).collect();
        assert_eq!(text, vec!["a.csv: column `temp` ignored"]);
    }
}
