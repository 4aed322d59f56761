//! The derived expression DAG as readable text, for debugging and for
//! counting operations: when [`Options::ir_dir`](crate::Options) is set
//! (by `robot!`: the environment variable `DYNAMICS_IR_DIR` at compile time),
//! the expansion writes `<DIR>/<Robot>.ir.txt` with the operation count of
//! every output and the DAG of each.

use std::fmt::Write as _;

use dynamics_symbolic::{Graph, Id, Var};

use crate::derive::{Derived, Vars};
use crate::model::Model;

/// The outputs of a robot, by name, with their roots.
pub fn outputs(d: &Derived) -> Vec<(&'static str, Vec<Id>)> {
    let n = d.vars.n;
    let flat = |m: &Vec<Vec<Id>>| -> Vec<Id> { m.iter().flatten().copied().collect() };
    let upper: Vec<Id> = (0..n)
        .flat_map(|i| (i..n).map(move |j| (i, j)))
        .map(|(i, j)| d.a[i][j])
        .collect();
    let qqt = d.qqt.clone();
    let mut terms = upper.clone();
    terms.extend(&qqt);
    terms.extend(&d.q0);
    let mut terms_and_jacobians: Vec<Id> = (0..n)
        .flat_map(|i| (i..n).map(move |j| (i, j)))
        .map(|(i, j)| d.a_fused[i][j])
        .collect();
    terms_and_jacobians.extend(&d.qqt_fused);
    terms_and_jacobians.extend(&d.q0);
    terms_and_jacobians.extend(d.perturbation.k.iter().chain(&d.perturbation.d).flatten());
    vec![
        ("mass_matrix (upper triangle)", upper),
        ("qqt1 + qqt2", qqt),
        ("gravity", d.gravity.clone()),
        ("generalized_forces", d.q0.clone()),
        ("coriolis_matrix", flat(&d.coriolis)),
        ("inverse_dynamics", d.tau.clone()),
        ("motion_terms (A, Qqt1 + Qqt2, Q0)", terms),
        (
            "perturbation_jacobians (K, D)",
            d.perturbation
                .k
                .iter()
                .chain(&d.perturbation.d)
                .flatten()
                .copied()
                .collect(),
        ),
        (
            "motion_and_jacobians (motion terms, K, D)",
            terms_and_jacobians,
        ),
        (
            "  K = dF/dq alone",
            d.perturbation.k.iter().flatten().copied().collect(),
        ),
        (
            "  D = dF/dqd alone",
            d.perturbation.d.iter().flatten().copied().collect(),
        ),
        (
            "inertial_regressor",
            d.regressor.y.iter().flatten().copied().collect(),
        ),
        ("kinetic_energy", vec![d.kinetic]),
        ("potential_energy", vec![d.potential]),
    ]
}

fn name_of(vars: Vars, model: &Model, v: Var) -> String {
    let (kind, i) = vars.classify(v);
    match kind {
        0 => format!("q{i}"),
        1 => format!("qd{i}"),
        2 => format!("qdd{i}"),
        4 => "t".to_string(),
        _ => model.params[i].name.to_string(),
    }
}

/// The whole dump as text.
pub fn text(model: &Model, d: &Derived) -> String {
    let g: &Graph = &d.graph;
    let mut out = format!(
        "# robot {} ({} coordinates, {} graph nodes)\n\n",
        model.name,
        d.vars.n,
        g.len()
    );
    for (name, roots) in outputs(d) {
        let _ = writeln!(out, "{name:36} {}", g.count_ops(&roots));
    }
    for (name, roots) in outputs(d) {
        let _ = writeln!(
            out,
            "\n## {name}\n{}",
            g.to_text(&roots, &|v| name_of(d.vars, model, v))
        );
    }
    out
}

/// Writes the dump into `dir`; errors are ignored (a dump is a debugging aid
/// and must never break a build).
pub fn write(dir: &std::path::Path, model: &Model, d: &Derived) {
    let path = dir.join(format!("{}.ir.txt", model.name));
    let _ = std::fs::create_dir_all(dir);
    let _ = std::fs::write(path, text(model, d));
}
