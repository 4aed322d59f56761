//! Motions that tell two rival effects apart: for each ambiguous pair, the
//! smallest principal angle between the two effects' column spaces after
//! every other base column is projected out. Zero: some combination of one
//! effect's columns is, as far as this motion shows, a combination of the
//! other's; 90 degrees: they cannot be mistaken. The design maximises the
//! smallest such angle over the pairs.
//!
//! The effects handled are those whose columns the motion alone gives:
//! Coulomb, Stribeck and viscous friction, an effort offset, rotor inertia
//! and a link's inertial parameters. A payload at the tip is a change of
//! the distal link's inertial parameters (its column lies in their span:
//! no motion separates them), and elasticity, backlash, delays and motor
//! sides are fitted by simulation, not by columns: those pairs are refused
//! with that reason.

use nalgebra::{DMatrix, SMatrix, SVector};

use super::{BaseColumns, ExciteError};
use crate::identify::Column;
use dynamics_runtime::control::Reference;
use dynamics_runtime::Robot;

/// The velocity scale of the Stribeck column, rad/s or m/s.
pub const STRIBECK_VS: f64 = 0.1;

/// An effect whose regressor columns follow from the motion alone.
///
/// ```
/// use dynamics_sim2real::excite::Rival;
/// let names = ["j1", "j2"];
/// let links = ["l1", "l2"];
/// assert_eq!(Rival::named("coulomb_friction", Some("j2"), &names, &links), Ok(Rival::Coulomb(1)));
/// assert_eq!(Rival::named("inertial_parameters", Some("l1"), &names, &links), Ok(Rival::Link(0)));
/// assert!(Rival::named("backlash", Some("j1"), &names, &links).is_err());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rival {
    /// Coulomb friction of joint j (smooth sign of the velocity).
    Coulomb(usize),
    /// Stribeck friction of joint j: its part beyond Coulomb friction,
    /// `sign(qd) exp(-(qd / vs)^2)`, `vs` = [`STRIBECK_VS`] (the Coulomb
    /// column it also holds is the rival's, or projected out with the
    /// others: Stribeck friction contains Coulomb friction, so the angle
    /// that tells them apart is that of the extra column).
    Stribeck(usize),
    /// Viscous friction of joint j.
    Viscous(usize),
    /// A constant effort offset on joint j.
    Offset(usize),
    /// Rotor inertia of joint j.
    Armature(usize),
    /// The inertial parameters of link l (its base columns).
    Link(usize),
}

impl Rival {
    /// The effect a report names by `kind` (the vocabulary's names) and
    /// place (a joint of `joints`, or a link of `links` for
    /// `inertial_parameters`). The error says why a kind has no columns here.
    pub fn named(
        kind: &str,
        place: Option<&str>,
        joints: &[&str],
        links: &[&str],
    ) -> Result<Rival, String> {
        let joint = || {
            place
                .and_then(|p| joints.iter().position(|j| *j == p))
                .ok_or_else(|| format!("{kind}: no joint of the robot named {place:?}"))
        };
        Ok(match kind {
            "coulomb_friction" => Rival::Coulomb(joint()?),
            "stribeck_friction" => Rival::Stribeck(joint()?),
            "viscous_friction" => Rival::Viscous(joint()?),
            "effort_offset" => Rival::Offset(joint()?),
            "armature" => Rival::Armature(joint()?),
            "inertial_parameters" => Rival::Link(
                place
                    .and_then(|p| links.iter().position(|l| *l == p))
                    .ok_or_else(|| format!("{kind}: no link of the robot named {place:?}"))?,
            ),
            "payload_mass" => {
                return Err("payload_mass: a payload at the tip is a change of the distal link's inertial parameters; no motion separates the two".into())
            }
            other => {
                return Err(format!(
                    "{other}: fitted by simulation, not by regressor columns; `excite --separate` separates friction, offsets, rotor inertia and link inertia"
                ))
            }
        })
    }

    /// Whether base column `c` belongs to this effect (and is therefore
    /// not projected out).
    fn owns(&self, c: Column) -> bool {
        match (*self, c) {
            (Rival::Coulomb(j), Column::Coulomb(i)) => i == j,
            (Rival::Viscous(j), Column::Viscous(i)) => i == j,
            (Rival::Offset(j), Column::Offset(i)) => i == j,
            (Rival::Armature(j), Column::Armature(i)) => i == j,
            (Rival::Link(l), Column::Link(m, _)) => l == m,
            _ => false,
        }
    }
}

/// The weighted columns of `rival` at state `s` (one `SVector` a column),
/// with `kept` the base columns' values there.
fn rival_columns<const N: usize>(
    rival: Rival,
    columns: &BaseColumns<N>,
    s: &Reference<N>,
    kept: &[SVector<f64, N>],
) -> Vec<SVector<f64, N>> {
    let w = &columns.weights;
    let unit = |j: usize, v: f64| {
        let mut c = SVector::zeros();
        c[j] = v * w[j];
        c
    };
    match rival {
        Rival::Coulomb(j) => vec![unit(j, (s.qd[j] / columns.sign_zone).tanh())],
        Rival::Stribeck(j) => vec![unit(
            j,
            (s.qd[j] / columns.sign_zone).tanh() * (-(s.qd[j] / STRIBECK_VS).powi(2)).exp(),
        )],
        Rival::Viscous(j) => vec![unit(j, s.qd[j])],
        Rival::Offset(j) => vec![unit(j, 1.0)],
        Rival::Armature(j) => vec![unit(j, s.qdd[j])],
        Rival::Link(l) => columns
            .kept
            .iter()
            .zip(kept)
            .filter(|(&k, _)| matches!(columns.all[k], Column::Link(m, _) if m == l))
            .map(|(_, v)| *v)
            .collect(),
    }
}

/// The smallest principal angle (rad) between the columns of `a` and `b`
/// after the columns of every other base parameter are projected out, for
/// each pair, over the motion `states`.
///
/// ```
/// use dynamics_sim2real::excite::{separation_angles, BaseColumns, Fourier, Limits, Rival};
/// dynamics_macros::robot! {
///     pub robot Pendulum;
///     gravity = [0.0, -9.81, 0.0];
///     link base;
///     link rod { mass = 1.0; com = [0.5, 0.0, 0.0]; inertia = [1e-3, 0.1, 0.1]; }
///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
/// }
/// let p = Pendulum::default();
/// let cols = BaseColumns::of(&p, &Limits::new([-1.0], [1.0], [3.0], [50.0]), 1).unwrap();
/// let mut f = Fourier::<1>::new([0.0].into(), 4.0, 4);
/// f.set_flat(&[0.3, 0.0, 0.2, 0.1, 0.1, -0.1, 0.05, 0.0]);
/// f.to_rest();
/// let states: Vec<_> = (0..400).map(|k| f.at(k as f64 * 0.01)).collect();
/// let pairs = [(Rival::Coulomb(0), Rival::Offset(0))];
/// let a = separation_angles(&p, &cols, &pairs, &states).unwrap();
/// assert!(a[0] > 0.1); // a swinging joint tells a friction level from an offset
/// ```
pub fn separation_angles<R: Robot<N>, const N: usize>(
    robot: &R,
    columns: &BaseColumns<N>,
    pairs: &[(Rival, Rival)],
    states: &[Reference<N>],
) -> Result<Vec<f64>, ExciteError> {
    let k = columns.kept.len();
    let links = R::LINK_NAMES.len();
    let mut y = vec![SMatrix::<f64, N, 10>::zeros(); links];
    // Per state, the weighted base columns (one SVector each).
    let x = columns.stack(robot, states)?;
    let mut out = Vec::new();
    for &(a, b) in pairs {
        let others: Vec<usize> = (0..k)
            .filter(|&c| {
                !a.owns(columns.all[columns.kept[c]]) && !b.owns(columns.all[columns.kept[c]])
            })
            .collect();
        let rows = states.len() * N;
        let mut xa: Vec<Vec<f64>> = Vec::new();
        let mut xb: Vec<Vec<f64>> = Vec::new();
        for (si, s) in states.iter().enumerate() {
            robot
                .inertial_regressor(&s.q, &s.qd, &s.qdd, &mut y)
                .map_err(|e| ExciteError::Regressor {
                    robot: R::NAME,
                    cause: e.to_string(),
                })?;
            let kept: Vec<SVector<f64, N>> = (0..k)
                .map(|c| SVector::from_fn(|j, _| x[(si * N + j, c)]))
                .collect();
            for (cols, target) in [(a, &mut xa), (b, &mut xb)] {
                let cs = rival_columns(cols, columns, s, &kept);
                if target.is_empty() {
                    target.resize(cs.len(), vec![0.0; rows]);
                }
                for (c, v) in cs.iter().enumerate() {
                    for j in 0..N {
                        target[c][si * N + j] = v[j];
                    }
                }
            }
        }
        let to_matrix = |cols: &[Vec<f64>]| DMatrix::from_fn(rows, cols.len(), |r, c| cols[c][r]);
        let xo = DMatrix::from_fn(rows, others.len(), |r, c| x[(r, others[c])]);
        let qo = orthonormal(&xo);
        let perp = |m: DMatrix<f64>| match &qo {
            Some(q) => &m - q * (q.transpose() * &m),
            None => m,
        };
        let (pa, pb) = (perp(to_matrix(&xa)), perp(to_matrix(&xb)));
        let angle = match (orthonormal(&pa), orthonormal(&pb)) {
            (Some(qa), Some(qb)) => {
                let s = (qa.transpose() * qb).singular_values();
                s.max().clamp(-1.0, 1.0).acos()
            }
            // An effect the motion does not excite at all.
            _ => 0.0,
        };
        out.push(angle);
    }
    Ok(out)
}

/// An orthonormal basis of the columns of `m` (those of norm above 1e-9
/// of the largest after orthogonalisation); `None` when there is none.
fn orthonormal(m: &DMatrix<f64>) -> Option<DMatrix<f64>> {
    if m.ncols() == 0 {
        return None;
    }
    let norms: Vec<f64> = (0..m.ncols()).map(|c| m.column(c).norm()).collect();
    let big = norms.iter().fold(0.0_f64, |a, &b| a.max(b));
    if big == 0.0 {
        return None;
    }
    let mut basis: Vec<nalgebra::DVector<f64>> = Vec::new();
    for c in 0..m.ncols() {
        if norms[c] <= 1e-12 * big {
            continue;
        }
        let mut v = m.column(c).into_owned() / norms[c];
        for _ in 0..2 {
            for b in &basis {
                let d = b.dot(&v);
                v.axpy(-d, b, 1.0);
            }
        }
        let n = v.norm();
        if n > 1e-9 {
            basis.push(v / n);
        }
    }
    if basis.is_empty() {
        None
    } else {
        Some(DMatrix::from_columns(&basis))
    }
}
