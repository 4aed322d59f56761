//! Writing measured data as CSV.

use std::io::Write;

use super::Measured;

/// Writes `t`, `q_<joint>`, `qd_<joint>` (when measured), `tau_<joint>`.
///
/// ```
/// use dynamics_sim2real::data::{read_csv_str, write_csv, Measured};
/// let m = Measured::<1> {
///     t: (0..300).map(|k| k as f64 * 1e-3).collect(),
///     q: vec![[0.25].into(); 300],
///     qd: vec![[0.0].into(); 300],
///     tau: vec![[1.5].into(); 300],
///     qd_measured: true,
///     ..Default::default()
/// };
/// let mut out = Vec::new();
/// write_csv(&mut out, &m, &["j"]).unwrap();
/// let text = String::from_utf8(out).unwrap();
/// assert!(text.starts_with("t,q_j,qd_j,tau_j\n0,0.25,0,1.5\n"));
/// let back = read_csv_str(&text, &["j"], "m.csv").unwrap();
/// assert_eq!((back.t, back.q, back.qd, back.tau), (m.t, m.q, m.qd, m.tau));
/// ```
pub fn write_csv<const N: usize>(
    out: &mut impl Write,
    m: &Measured<N>,
    joints: &[&str; N],
) -> std::io::Result<()> {
    let mut header = vec!["t".to_string()];
    let prefixes: &[&str] = if m.qd_measured {
        &["q", "qd", "tau"]
    } else {
        &["q", "tau"]
    };
    for p in prefixes {
        header.extend(joints.iter().map(|j| format!("{p}_{j}")));
    }
    writeln!(out, "{}", header.join(","))?;
    let mut line = String::new();
    for k in 0..m.len() {
        line.clear();
        line.push_str(&format!("{}", m.t[k]));
        let mut cols = vec![&m.q[k]];
        if m.qd_measured {
            cols.push(&m.qd[k]);
        }
        cols.push(&m.tau[k]);
        for v in cols {
            for x in v.iter() {
                line.push_str(&format!(",{x}"));
            }
        }
        writeln!(out, "{line}")?;
    }
    Ok(())
}
