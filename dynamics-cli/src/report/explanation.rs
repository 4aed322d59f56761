//! The compound explanation, which leads the readable report: the effects
//! in words, the shrink they give, a table of the effects in the order of
//! their gains (friction on every joint one row, with its own table;
//! parameters from the joint fit, share of the training gap, held-out
//! contribution, ambiguous pairs), what was suggested but not confirmed,
//! and a bar chart of the held-out gap left after each added effect.

use std::fmt::Write as _;

use dynamics_sim2real::diagnose::{Channel, Parameter, Report, Status};
use dynamics_sim2real::effects::EffectKind;

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

/// Friction kinds, grouped into one row of the table.
fn is_friction(kind: EffectKind) -> bool {
    matches!(
        kind,
        EffectKind::CoulombFriction | EffectKind::ViscousFriction | EffectKind::StribeckFriction
    )
}

/// A parameter as the table shows it: its value and spread, or why the
/// data give none.
fn value(p: &Parameter) -> String {
    match &p.note {
        Some(note) => format!("{}: {note}", p.name),
        None => format!("{} = {} +- {}", p.name, g(p.value), g(p.std)),
    }
}

/// The report's lead section: what explains the gap (friction on many
/// joints as one row, the other effects each in a row), how far the whole
/// explanation shrinks the held-out gap, and what the training record
/// suggested but the held-out record did not confirm.
///
/// ```
/// # use dynamics_sim2real::diagnose::Report;
/// fn show(report: &Report) -> String { dynamics_cli::report::explanation::section(report) }
/// ```
pub fn section(report: &Report) -> String {
    let mut s = String::new();
    let effects = &report.which.effects;
    let _ = writeln!(s, "## What explains the gap\n");
    if effects.is_empty() {
        let _ = writeln!(
            s,
            "No effect both explains the training gap by the margins and holds on the held-out \
             data: {}.\n",
            match report.which.verdict.status {
                Status::Unexplained =>
                    "the gap is real, but none of the candidate effects explains it",
                _ => "the nominal model explains the data within noise",
            }
        );
        suggestions(report, &mut s);
        return s;
    }
    let sh = &report.shrink;
    let (friction, others): (Vec<_>, Vec<_>) = effects.iter().partition(|e| is_friction(e.kind));
    let mut words = Vec::new();
    if !friction.is_empty() {
        let mut joints: Vec<&str> = friction.iter().filter_map(|e| e.joint.as_deref()).collect();
        joints.dedup();
        words.push(format!("friction on {} (table below)", joints.join(", ")));
    }
    for e in &others {
        let place = e
            .joint
            .clone()
            .or(e.point.clone())
            .unwrap_or("all signals".into());
        words.push(format!("{} at {place}", e.kind));
    }
    let _ = writeln!(
        s,
        "**{}.** Together they shrink the held-out torque gap above noise by {:.1} % and the \
         plain RMS of the effort residual over all joints (noise included) by {:.1} % \
         (`explanation.svg`: the gap left after each added effect).\n",
        words.join("; "),
        100.0 * sh.torque_fraction,
        100.0 * sh.rms_fraction
    );
    let _ = writeln!(
        s,
        "Each effect was chosen on the training data (forward selection by the information \
         criterion, confirmed by block cross-validation over its time segments) and then held \
         on the held-out data: leaving it out raises the held-out residual by more than \
         sensor noise could (chance 0.001, shared by the effects tested). Share = part of the training gap above noise it explained when \
         added; held-out contribution = how much the held-out gap grows when it alone is left \
         out (the others refitted).\n"
    );
    let _ = writeln!(
        s,
        "| # | effect | place | parameters (value +- std) | share | held-out contribution |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|");
    if !friction.is_empty() {
        let share: f64 = friction.iter().map(|e| e.share).sum();
        let held: f64 = friction.iter().map(|e| e.holdout_contribution).sum();
        let joints: Vec<&str> = report
            .which
            .friction
            .iter()
            .filter(|f| f.corrected)
            .map(|f| f.joint.as_str())
            .collect();
        let _ = writeln!(
            s,
            "| 1 | friction | {} | see the friction table | {:.1} % | {:.1} % |",
            joints.join(", "),
            100.0 * share,
            100.0 * held
        );
    }
    let first = usize::from(!friction.is_empty());
    for (i, e) in others.iter().enumerate() {
        let place = e
            .joint
            .clone()
            .or(e.point.clone())
            .unwrap_or("all signals".into());
        let place = late_place(place, e.channel);
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
                .map(value)
                .collect::<Vec<_>>()
                .join("; "),
        };
        let kind = match &e.ambiguous_with {
            Some(r) => format!(
                "{} (or {} at {}: {})",
                e.kind,
                r.kind,
                r.joint.clone().or(r.point.clone()).unwrap_or_default(),
                r.inseparable
                    .as_deref()
                    .unwrap_or("these data cannot tell them apart")
            ),
            None => e.kind.to_string(),
        };
        let _ = writeln!(
            s,
            "| {} | {kind} | {place} | {params} | {:.1} % | {:.1} % |",
            first + i + 1,
            100.0 * e.share,
            100.0 * e.holdout_contribution
        );
    }
    if !friction.is_empty() {
        let _ = writeln!(
            s,
            "\nFriction in the calibrated model (nominal -> with the explanation):\n"
        );
        let _ = writeln!(s, "| joint | Coulomb | breakaway | viscous |");
        let _ = writeln!(s, "|---|---|---|---|");
        for f in report.which.friction.iter().filter(|f| f.corrected) {
            let _ = writeln!(
                s,
                "| {} | {:.4} -> {:.4} | {:.4} | {:.4} -> {:.4} |",
                f.joint, f.coulomb_nominal, f.coulomb, f.breakaway, f.viscous_nominal, f.viscous
            );
        }
    }
    let _ = writeln!(s);
    suggestions(report, &mut s);
    s
}

/// A place with, for a delay, which channel is late.
pub fn late_place(place: String, channel: Option<Channel>) -> String {
    match channel {
        Some(Channel::Positions) => format!("{place} (the position stream late)"),
        Some(Channel::Effort) => format!("{place} (the effort stream late)"),
        Some(_) => format!("{place} (positions and velocities late together)"),
        None => place,
    }
}

/// What the training data suggested and the held-out data did not
/// confirm.
fn suggestions(report: &Report, s: &mut String) {
    let suggested = &report.which.suggested;
    if suggested.is_empty() {
        return;
    }
    let _ = writeln!(
        s,
        "Suggested by the training data, not confirmed (not named):\n"
    );
    for e in suggested {
        let place = e
            .joint
            .clone()
            .or(e.point.clone())
            .unwrap_or("all signals".into());
        let place = late_place(place, e.channel);
        let _ = writeln!(s, "- {} at {place}: {}", e.kind, e.reason);
    }
    let _ = writeln!(s);
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
