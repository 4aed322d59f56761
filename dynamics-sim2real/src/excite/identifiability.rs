//! The predicted identifiability of a motion: per base parameter the
//! standard deviation least squares would reach at a stated effort noise
//! (white, independent per joint and sample: the inverse of the information
//! matrix), relative to the nominal value where it has one, and the
//! combinations no motion can separate (the columns the rank reduction
//! dropped).

use nalgebra::{DMatrix, SVector};
use serde::Serialize;

use super::{BaseColumns, ExciteError};
use crate::regressor::Column;
use dynamics_runtime::control::Reference;
use dynamics_runtime::Robot;

/// One base parameter's predicted precision.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Parameter {
    /// The base column's name (e.g. `panda_link3 m c_x`, `coulomb panda_joint2`).
    pub name: String,
    /// Dropped columns folded into it, with their factor (`[name, c]`: the
    /// base parameter is the named one plus `c` times each of these).
    pub merged: Vec<(String, f64)>,
    /// Its nominal value (the model's inertial parameters; 0 for friction,
    /// rotor inertia and offsets, which the nominal model does not hold).
    pub value: f64,
    /// Predicted standard deviation, SI units.
    pub std: f64,
    /// `std / |value|` where the value is not zero.
    pub relative_std: Option<f64>,
}

/// What a motion is predicted to identify.
///
/// ```
/// use dynamics_sim2real::excite::{identifiability, BaseColumns, Fourier, Limits};
/// dynamics_macros::robot! {
///     pub robot Pendulum;
///     gravity = [0.0, -9.81, 0.0];
///     link base;
///     link rod { mass = 1.0; com = [0.5, 0.0, 0.0]; inertia = [1e-3, 0.1, 0.1]; }
///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
/// }
/// let p = Pendulum::default();
/// let limits = Limits::<1>::new([-1.0], [1.0], [3.0], [50.0]);
/// let cols = BaseColumns::of(&p, &limits, 1).unwrap();
/// let mut f = Fourier::<1>::new([0.0].into(), 4.0, 4);
/// f.set_flat(&[0.3, 0.0, 0.2, 0.1, 0.1, -0.1, 0.05, 0.0]);
/// f.to_rest();
/// let states: Vec<_> = (0..400).map(|k| f.at(k as f64 * 0.01)).collect();
/// let id = identifiability(&p, &cols, &states, 1.0, &[0.01].into()).unwrap();
/// assert_eq!(id.parameters.len(), cols.kept.len());
/// // m c_x holds the weight against gravity: well determined.
/// let mcx = id.parameters.iter().find(|q| q.name == "rod m c_x").unwrap();
/// assert!(mcx.relative_std.unwrap() < 0.01);
/// // A pendulum about z never feels m c_z: unidentifiable.
/// assert!(id.unidentifiable.iter().any(|s| s.starts_with("rod m c_z")));
/// ```
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Identifiability {
    /// The effort noise assumed per joint (standard deviation per sample).
    pub noise: Vec<f64>,
    /// Per base parameter.
    pub parameters: Vec<Parameter>,
    /// Every column outside the base, in words: never acting on the
    /// efforts, or identifiable only in a named combination.
    pub unidentifiable: Vec<String>,
}

/// The identifiability of the motion sampled at `states`, repeated
/// `repeats` times (whole periods of a periodic motion), at effort noise
/// `noise` per joint.
pub fn identifiability<R: Robot<N>, const N: usize>(
    robot: &R,
    columns: &BaseColumns<N>,
    states: &[Reference<N>],
    repeats: f64,
    noise: &SVector<f64, N>,
) -> Result<Identifiability, ExciteError> {
    let mut weighted = columns.clone();
    weighted.weights = noise.map(|s| if s > 0.0 { 1.0 / s } else { 1.0 });
    let x = weighted.stack(robot, states)?;
    let g: DMatrix<f64> = x.transpose() * &x * repeats.max(1.0);
    let k = g.nrows();
    // Unit-diagonal scaling before inverting, for accuracy.
    let d: Vec<f64> = (0..k)
        .map(|i| g[(i, i)].max(f64::MIN_POSITIVE).sqrt())
        .collect();
    let unit = DMatrix::from_fn(k, k, |a, b| g[(a, b)] / (d[a] * d[b]));
    let inv = unit
        .clone()
        .cholesky()
        .map(|c| c.inverse())
        .or_else(|| unit.pseudo_inverse(1e-14).ok())
        .ok_or(ExciteError::Numeric {
            place: "identifiability",
            cause: "the information matrix could not be inverted".into(),
        })?;
    let mut pi = vec![SVector::<f64, 10>::zeros(); R::LINK_NAMES.len()];
    robot
        .inertial_parameters(&mut pi)
        .map_err(|e| ExciteError::Regressor {
            robot: R::NAME,
            cause: e.to_string(),
        })?;
    let nominal = |c: Column| match c {
        Column::Link(l, p) => pi[l][p],
        _ => 0.0,
    };
    let mut parameters: Vec<Parameter> = columns
        .kept
        .iter()
        .enumerate()
        .map(|(i, &c)| Parameter {
            name: columns.all[c].name::<R, N>(),
            merged: Vec::new(),
            value: nominal(columns.all[c]),
            std: inv[(i, i)].max(0.0).sqrt() / d[i],
            relative_std: None,
        })
        .collect();
    let mut unidentifiable = Vec::new();
    for (dcol, combo) in &columns.dropped {
        let name = columns.all[*dcol].name::<R, N>();
        if combo.is_empty() {
            unidentifiable.push(format!("{name}: never acts on the efforts"));
            continue;
        }
        let v = nominal(columns.all[*dcol]);
        let mut words = Vec::new();
        for &(kc, c) in combo {
            if let Some(i) = columns.kept.iter().position(|&k| k == kc) {
                parameters[i].value += c * v;
                parameters[i].merged.push((name.clone(), c));
                words.push(format!("{c:+.4} x {}", parameters[i].name));
            }
        }
        unidentifiable.push(format!(
            "{name}: only together with others (its column = {})",
            words.join(" ")
        ));
    }
    let scale = parameters.iter().fold(0.0_f64, |m, p| m.max(p.value.abs()));
    for p in &mut parameters {
        if p.value.abs() > 1e-9 * scale {
            p.relative_std = Some(p.std / p.value.abs());
        }
    }
    Ok(Identifiability {
        noise: noise.iter().copied().collect(),
        parameters,
        unidentifiable,
    })
}
