//! Comparing evaluated quantities with a reference file (Pinocchio's).

use serde_json::Value;

use crate::eval::Evaluated;

/// Largest relative error of each field over all states: per state,
/// `max |ours - ref| / max |ref|` over the entries of the field (a norm-wise
/// relative error, so entries that are zero up to round-off do not blow it
/// up). `C` is compared as `C v` (C is one factorisation among many).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Comparison {
    /// (field, worst relative error).
    pub fields: Vec<(&'static str, f64)>,
}

impl Comparison {
    /// The worst error over all fields.
    pub fn worst(&self) -> f64 {
        self.fields.iter().map(|f| f.1).fold(0.0, f64::max)
    }
}

fn rel(ours: &[f64], theirs: &[f64]) -> f64 {
    let scale = theirs.iter().fold(0.0f64, |m, x| m.max(x.abs())).max(1e-12);
    let err = ours
        .iter()
        .zip(theirs)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    if ours.len() != theirs.len() {
        return f64::INFINITY;
    }
    err / scale
}

fn vec_of(v: &Value) -> Vec<f64> {
    match v {
        Value::Array(a) => a.iter().flat_map(vec_of).collect(),
        Value::Number(n) => n.as_f64().into_iter().collect(),
        _ => Vec::new(),
    }
}

fn mat_vec(m: &[Vec<f64>], v: &[f64]) -> Vec<f64> {
    m.iter()
        .map(|row| row.iter().zip(v).map(|(a, b)| a * b).sum())
        .collect()
}

/// Compares `ours` with the `states` of a reference document.
///
/// ```
/// use dynamics_cli::{compare::compare, eval::evaluate, states::State};
/// dynamics_macros::robot! {
///     pub robot Pendulum; gravity = [0.0, -9.81, 0.0];
///     link base; link rod { mass = 1.0; com = [0.2, 0.0, 0.0]; inertia = [1e-3, 1e-2, 1e-2]; }
///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
/// }
/// let s = State { q: vec![0.3], v: vec![1.0], a: vec![-2.0] };
/// let ours = evaluate(&Pendulum::default(), &[s]).unwrap();
/// let doc = serde_json::json!({ "states": ours });
/// assert_eq!(compare(&ours, &doc).worst(), 0.0);
/// let mut other = ours.clone();
/// other[0].tau[0] *= 1.01;
/// assert!((compare(&other, &doc).worst() - 0.01).abs() < 1e-12);
/// ```
pub fn compare(ours: &[Evaluated], reference: &Value) -> Comparison {
    let empty = Vec::new();
    let states = reference
        .get("states")
        .and_then(Value::as_array)
        .unwrap_or(&empty);
    let mut worst: Vec<(&'static str, f64)> = Vec::new();
    if states.len() != ours.len() {
        return Comparison {
            fields: vec![("states", f64::INFINITY)],
        };
    }
    for (o, s) in ours.iter().zip(states) {
        let get = |k: &str| s.get(k).map(vec_of).unwrap_or_default();
        let cv_ref = {
            let c: Vec<Vec<f64>> = s
                .get("C")
                .and_then(Value::as_array)
                .map(|rows| rows.iter().map(vec_of).collect())
                .unwrap_or_default();
            mat_vec(&c, &get("v"))
        };
        let errs = [
            ("tau", rel(&o.tau, &get("tau"))),
            ("M", rel(&o.m.concat(), &get("M"))),
            ("g", rel(&o.g, &get("g"))),
            ("C v", rel(&mat_vec(&o.c, &o.v), &cv_ref)),
            ("nle", rel(&o.nle, &get("nle"))),
            ("ddq", rel(&o.ddq, &get("ddq"))),
            (
                "kinetic_energy",
                rel(&[o.kinetic_energy], &get("kinetic_energy")),
            ),
            (
                "potential_energy",
                rel(&[o.potential_energy], &get("potential_energy")),
            ),
            ("dtau_dq", rel(&o.dtau_dq.concat(), &get("dtau_dq"))),
            ("dtau_dv", rel(&o.dtau_dv.concat(), &get("dtau_dv"))),
            ("ddq_dq", rel(&o.ddq_dq.concat(), &get("ddq_dq"))),
            ("ddq_dv", rel(&o.ddq_dv.concat(), &get("ddq_dv"))),
        ];
        if worst.is_empty() {
            worst = errs.iter().map(|(f, _)| (*f, 0.0)).collect();
        }
        for (w, (_, e)) in worst.iter_mut().zip(errs) {
            w.1 = w.1.max(if e.is_nan() { f64::INFINITY } else { e });
        }
    }
    Comparison { fields: worst }
}
