//! The compound explanation in the readable report: a table of the
//! effects in the order of their gains (parameters from the joint fit, share of
//! the training gap, held-out contribution, ambiguous pairs) and a bar
//! chart of the held-out gap left after each added effect.

use std::fmt::Write as _;

use dynamics_sim2real::diagnose::{Channel, Report};

use crate::plot::bars;

/// A number for a table: 4 significant digits, `not determined` for an
/// infinite spread.
fn g(v: f64) -> String {
    if v.is_finite() {
        format!("{v:.4e}")
    } else {
        "not determined".into()
    }
}

/// The markdown section (empty when nothing was added).
///
/// ```
/// # use dynamics_sim2real::diagnose::Report;
/// fn show(report: &Report) -> String { dynamics_cli::report::explanation::section(report) }
/// ```
pub fn section(report: &Report) -> String {
    let mut s = String::new();
    let effects = &report.which.effects;
    let _ = writeln!(s, "\n## The whole gap: effects that together explain it\n");
    if effects.is_empty() {
        let _ = writeln!(
            s,
            "No set of effects explains the gap better than the nominal model by the margins \
             (the verdict above says why).\n"
        );
        return s;
    }
    let _ = writeln!(
        s,
        "Chosen over every candidate on every joint (forward selection, and where model error \
         is left on most joints a search from the full linear model), each fitted jointly with \
         the others; listed in the order of their gains (each in turn the one that lowers the \
         criterion most when added to those before it); share = part of the training gap above \
         noise it explained when added; held-out contribution = how much the held-out gap \
         grows when it alone is left out (the others refitted).\n"
    );
    let _ = writeln!(
        s,
        "| # | effect | place | parameters (value +- std) | share | held-out contribution |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|");
    for (i, e) in effects.iter().enumerate() {
        let place = e
            .joint
            .clone()
            .or(e.point.clone())
            .unwrap_or("all signals".into());
        // A delay: which channel is late.
        let place = match &e.channel {
            Some(Channel::Positions) => format!("{place} (the position stream late)"),
            Some(Channel::Effort) => format!("{place} (the effort stream late)"),
            Some(_) => format!("{place} (positions and velocities late together)"),
            None => place,
        };
        // An effect that starts and stops: where in time.
        let place = match &e.window {
            Some(w) => format!("{place}, on from {:.3} s to {:.3} s", w.start, w.end),
            None => place,
        };
        let params = match &e.description {
            Some(d) => d.clone(),
            None => e
                .parameters
                .iter()
                .map(|p| format!("{} = {} +- {}", p.name, g(p.value), g(p.std)))
                .collect::<Vec<_>>()
                .join("; "),
        };
        let kind = match &e.ambiguous_with {
            Some(r) => format!(
                "{} (or {} at {}: these data cannot tell them apart)",
                e.kind,
                r.kind,
                r.joint.clone().or(r.point.clone()).unwrap_or_default()
            ),
            None => e.kind.to_string(),
        };
        let _ = writeln!(
            s,
            "| {} | {kind} | {place} | {params} | {:.1} % | {:.1} % |",
            i + 1,
            100.0 * e.share,
            100.0 * e.holdout_contribution
        );
    }
    let sh = &report.shrink;
    let _ = writeln!(
        s,
        "\nWith all {} effects the held-out torque gap above noise shrinks by {:.1} % and the \
         plain RMS of the effort residual over all joints (noise included) by {:.1} % \
         (`explanation.svg`: the gap left after each added effect).",
        effects.len(),
        100.0 * sh.torque_fraction,
        100.0 * sh.rms_fraction
    );
    s
}

/// The held-out torque gap above noise left by the nominal model and after
/// each added effect.
pub fn chart(report: &Report) -> String {
    let rows: Vec<(String, f64)> = report
        .shrink
        .steps
        .iter()
        .map(|st| {
            let label = if st.effects == 0 {
                st.added.clone()
            } else {
                format!("+ {}", st.added)
            };
            (label, st.torque_gap)
        })
        .collect();
    bars(
        "Held-out torque gap above noise left after each added effect",
        "gap above the noise floor (noise units, root sum of squares over joints)",
        &rows,
        None,
    )
}
