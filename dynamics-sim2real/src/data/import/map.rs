//! The column map: which part of a recorded file holds the time and each
//! joint's position, velocity and effort, in the robot's joint order.
//!
//! `t=SOURCE,q=SOURCE[,qd=SOURCE],tau=SOURCE`, each `SOURCE` being
//! `[ENTRY][:COLUMNS][*SCALE]`:
//! - `ENTRY`: a file of the directory given as the data path, or an array of
//!   a `.npz`; empty for a single text or `.npy` file;
//! - `COLUMNS`: 1-based, `3` or `2-8` (one column per joint, in the robot's
//!   joint order); absent: all the columns the source has;
//! - `SCALE`: a factor applied on reading (`*1e-3` for a clock in
//!   milliseconds, `*-1` for an effort of the opposite sign).

use std::str::FromStr;

use super::error::ImportError;

/// Where one quantity is in the recorded data.
#[derive(Debug, Clone, PartialEq)]
pub struct Source {
    /// A file of the directory or an array of the archive (empty: the file itself).
    pub entry: String,
    /// 1-based first and last column, inclusive (`None`: every column).
    pub columns: Option<(usize, usize)>,
    /// Factor applied on reading.
    pub scale: f64,
}

/// The column map of a recorded file: where `t`, `q`, `qd` (optional: then
/// differentiated from `q`) and `tau` are.
///
/// ```
/// use dynamics_sim2real::data::import::ColumnMap;
/// let map: ColumnMap = "t=times,q=positions,qd=velocities,tau=torques".parse().unwrap();
/// assert_eq!(map.q.entry, "positions");
/// let map: ColumnMap = "t=:1*1e-3,q=:2-8,tau=:9-15".parse().unwrap();
/// assert_eq!((map.t.columns, map.t.scale, map.qd), (Some((1, 1)), 1e-3, None));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct ColumnMap {
    /// The time, s (after scaling).
    pub t: Source,
    /// Positions.
    pub q: Source,
    /// Velocities, if recorded.
    pub qd: Option<Source>,
    /// Efforts.
    pub tau: Source,
}

impl FromStr for ColumnMap {
    type Err = ImportError;

    fn from_str(text: &str) -> Result<Self, ImportError> {
        let err = |message: String| ImportError::Map {
            map: text.to_string(),
            message,
        };
        let (mut t, mut q, mut qd, mut tau) = (None, None, None, None);
        for item in text.split(',').map(str::trim).filter(|s| !s.is_empty()) {
            let (key, source) = item
                .split_once('=')
                .ok_or_else(|| err(format!("`{item}` is not KEY=SOURCE")))?;
            let slot = match key.trim() {
                "t" => &mut t,
                "q" => &mut q,
                "qd" => &mut qd,
                "tau" => &mut tau,
                other => return Err(err(format!("`{other}` is not one of t, q, qd, tau"))),
            };
            if slot.is_some() {
                return Err(err(format!("`{}` given twice", key.trim())));
            }
            *slot = Some(source_of(source.trim()).map_err(|m| err(format!("`{item}`: {m}")))?);
        }
        let need = |s: Option<Source>, key: &str, what: &str| {
            s.ok_or_else(|| err(format!("no `{key}=` ({what})")))
        };
        Ok(ColumnMap {
            t: need(t, "t", "the time")?,
            q: need(q, "q", "the positions")?,
            qd,
            tau: need(tau, "tau", "the efforts")?,
        })
    }
}

/// Reads `[ENTRY][:COLUMNS][*SCALE]`.
fn source_of(text: &str) -> Result<Source, String> {
    let (rest, scale) = match text.rsplit_once('*') {
        Some((rest, s)) => {
            let scale: f64 = s
                .trim()
                .parse()
                .ok()
                .filter(|v: &f64| v.is_finite() && *v != 0.0)
                .ok_or_else(|| format!("scale `{s}` is not a non-zero number"))?;
            (rest, scale)
        }
        None => (text, 1.0),
    };
    let (entry, columns) = match rest.rsplit_once(':') {
        Some((entry, cols)) => (entry, Some(columns_of(cols.trim())?)),
        None => (rest, None),
    };
    Ok(Source {
        entry: entry.trim().to_string(),
        columns,
        scale,
    })
}

/// Reads `3` or `2-8` (1-based, inclusive).
fn columns_of(text: &str) -> Result<(usize, usize), String> {
    let bad = || format!("columns `{text}` are not N or A-B (1-based)");
    let number = |s: &str| s.trim().parse::<usize>().ok().filter(|&n| n >= 1);
    let (a, b) = match text.split_once('-') {
        Some((a, b)) => (number(a).ok_or_else(bad)?, number(b).ok_or_else(bad)?),
        None => {
            let n = number(text).ok_or_else(bad)?;
            (n, n)
        }
    };
    if b < a {
        return Err(bad());
    }
    Ok((a, b))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sources_and_mistakes() {
        let m: ColumnMap = "t=time.txt*0.001, q=pos.txt:2-8, tau=tau.txt*-1"
            .parse()
            .unwrap();
        assert_eq!(
            m.q,
            Source {
                entry: "pos.txt".into(),
                columns: Some((2, 8)),
                scale: 1.0
            }
        );
        assert_eq!((m.t.scale, m.tau.scale, m.tau.columns), (1e-3, -1.0, None));
        let e = |s: &str| s.parse::<ColumnMap>().unwrap_err().to_string();
        assert_eq!(
            e("t=a,q=b,tau=c,x=d"),
            "column map `t=a,q=b,tau=c,x=d`: `x` is not one of t, q, qd, tau"
        );
        assert_eq!(
            e("t=a,q=b:3-1,tau=c"),
            "column map `t=a,q=b:3-1,tau=c`: `q=b:3-1`: columns `3-1` are not N or A-B (1-based)"
        );
        assert_eq!(
            e("t=a,q=b,tau=c*0"),
            "column map `t=a,q=b,tau=c*0`: `tau=c*0`: scale `0` is not a non-zero number"
        );
        assert_eq!(
            e("t=a,t=b,q=b,tau=c"),
            "column map `t=a,t=b,q=b,tau=c`: `t` given twice"
        );
        assert_eq!(
            e("t=a,q=b"),
            "column map `t=a,q=b`: no `tau=` (the efforts)"
        );
    }
}
