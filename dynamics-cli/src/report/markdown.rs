//! The report's text (`report.md`): the verdict, then where, which and how
//! far it shrinks, in words and numbers, with the figures inline.

use std::fmt::Write as _;

use dynamics_sim2real::diagnose::traces::Traces;
use dynamics_sim2real::diagnose::{Options, Ranked, Report, VerdictKind};

use super::figures::{place, RANKED_SHOWN};

/// A joint's residual counts as a gap above this many noise floors.
pub const GAP_RATIO: f64 = 1.5;

/// A number to four significant digits (scientific when very large or small).
fn g(v: f64) -> String {
    if v == 0.0 {
        "0".into()
    } else if v.abs() >= 1e4 || v.abs() < 1e-3 {
        format!("{v:.3e}")
    } else {
        // Four significant digits.
        let decimals = (3 - v.abs().log10().floor() as i32).max(0) as usize;
        format!("{v:.decimals$}")
    }
}

fn pct(v: f64) -> String {
    format!("{:.1} %", 100.0 * v)
}

/// A simulation's figure, or why there is none (the warnings say more).
fn made(v: Option<f64>, f: fn(f64) -> String) -> String {
    v.map(f).unwrap_or_else(|| "not made".into())
}

fn parameters(r: &Ranked) -> String {
    r.parameters
        .iter()
        .map(|p| {
            if p.std.is_finite() {
                format!("{} = {} ± {}", p.name, g(p.value), g(p.std))
            } else {
                format!("{} = {} (not determined by these data)", p.name, g(p.value))
            }
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// The markdown text; `files(joint)` are the per-joint figure names
/// (residual, shrink, effort).
pub fn markdown(
    report: &Report,
    traces: &Traces,
    options: &Options,
    files: &dyn Fn(&str) -> [String; 3],
) -> String {
    let none_margin = options.none_margin;
    let floor_from = if options.noise.is_some() {
        "noise floor made by the stated sensor noise"
    } else {
        "noise floor made by sensor noise of the levels estimated from the data"
    };
    let mut s = String::new();
    let v = &report.which.verdict;
    let top = report.which.ranked.first();
    let chosen = v.names_effect().then_some(top).flatten();
    let unit = |joint: &str| -> (&str, &str) {
        let u = traces
            .train
            .joints
            .iter()
            .find(|j| j.joint == joint)
            .map(|j| j.unit)
            .unwrap_or("N·m");
        (u, if u == "N" { "m" } else { "rad" })
    };
    let _ = writeln!(s, "# Sim-to-real gap diagnosis: {}\n", report.robot);
    let _ = writeln!(
        s,
        "Training data: {} samples; held-out data: {} samples. \
         Residual = measured effort minus the nominal model's effort along the measured \
         motion (both smoothed); {floor_from}. Prediction error = \
         positions of 0.1 s open-loop simulations under the recorded efforts against the \
         measured ones; its yardstick is the same error for an exact model on a twin of \
         the data with the same sensor noise.\n",
        report.samples[0], report.samples[1]
    );

    // What explains the gap, first.
    s += &super::explanation::section(report);

    // The best single effect, as supporting detail.
    let _ = writeln!(s, "## The best single effect\n");
    match chosen {
        Some(r) => {
            let _ = writeln!(
                s,
                "**{}** ({}): {}. It explains {} of the gap above noise on the training data \
                 and {} on the held-out data; it improves AICc by {:.1} over the nominal model.\n",
                place(r),
                v.status,
                parameters(r),
                pct(r.share),
                pct(r.holdout_share),
                r.delta_aicc
            );
            if let (Some(rival), Some(why)) = (&v.rival, &v.inseparable) {
                let _ = writeln!(
                    s,
                    "These data cannot tell it apart from **{}** (AICc {:.1} worse only); \
                     {why}.\n",
                    place(rival),
                    rival.aicc - r.aicc
                );
            } else if let (Some(rival), Some(motion)) = (&v.rival, &v.separating_motion) {
                let _ = writeln!(
                    s,
                    "These data cannot tell it apart from **{}** (AICc {:.1} worse only). \
                     A motion that would separate them: {motion}.\n",
                    place(rival),
                    rival.aicc - r.aicc
                );
            }
            let effects = &report.which.effects;
            if effects.len() > 1 {
                let among = effects
                    .iter()
                    .any(|e| e.kind == r.kind && e.joint == r.joint && e.point == r.point);
                let _ = writeln!(
                    s,
                    "It is the best single effect. The whole gap takes {} effects together \
                     (first section), {}.\n",
                    effects.len(),
                    if among {
                        "this one among them"
                    } else {
                        "without this one: their effects account for its part"
                    }
                );
            }
        }
        None => {
            if v.kind == VerdictKind::Unexplained {
                let _ = write!(
                    s,
                    "**unexplained**: the nominal model misses the data by more than noise \
                     (see Where), and none of the candidate effects explains the gap"
                );
            } else {
                let _ = write!(
                    s,
                    "**none**: the nominal model explains the data within noise"
                );
            }
            match top {
                Some(t) => {
                    let _ = writeln!(
                        s,
                        "; the best candidate, {}, improves AICc by {:.1} (a verdict needs {:.1} \
                         and a gain on held-out data).\n",
                        place(t),
                        t.delta_aicc,
                        none_margin
                    );
                }
                None => {
                    let _ = writeln!(s, ".\n");
                }
            }
        }
    }

    // What the data preparation repaired and what the data cannot show.
    if !report.warnings.is_empty() {
        let _ = writeln!(s, "## Warnings (the data as recorded)\n");
        for w in crate::warnings::lines(&report.warnings) {
            let _ = writeln!(s, "- {w}");
        }
        let _ = writeln!(s);
    }

    // Where.
    let _ = writeln!(s, "## Where (training data, nominal model)\n");
    let mut order: Vec<_> = report.where_.joints.iter().collect();
    order.sort_by(|a, b| b.torque_ratio.total_cmp(&a.torque_ratio));
    let gaps: Vec<_> = order
        .iter()
        .filter(|j| j.torque_ratio > GAP_RATIO)
        .collect();
    if gaps.is_empty() {
        let _ = writeln!(
            s,
            "No joint's torque residual stands above {GAP_RATIO} x its noise floor{}.\n",
            order
                .first()
                .map(|j| format!(" (largest: {} at {:.1} x)", j.joint, j.torque_ratio))
                .unwrap_or_default()
        );
    } else {
        let list: Vec<String> = gaps
            .iter()
            .map(|j| {
                let (u, _) = unit(&j.joint);
                format!(
                    "{} ({} {u} RMS = {:.1} x its noise floor of {} {u})",
                    j.joint,
                    g(j.torque_rms),
                    j.torque_ratio,
                    g(j.torque_noise)
                )
            })
            .collect();
        let _ = writeln!(
            s,
            "The gap is at {}; the other joints are within {GAP_RATIO} x noise.\n",
            list.join(", ")
        );
        for j in &gaps {
            if j.windows.is_empty() {
                continue;
            }
            let w: Vec<String> = j
                .windows
                .iter()
                .map(|w| {
                    format!(
                        "{:.2}-{:.2} s ({}, {:.1} x noise)",
                        w.start, w.end, w.phase, w.ratio
                    )
                })
                .collect();
            let _ = writeln!(s, "At {} it concentrates in {}.\n", j.joint, w.join("; "));
        }
    }
    let _ = writeln!(
        s,
        "| joint | torque residual RMS | noise floor | ratio | 0.1 s prediction error RMS | an exact model's | ratio | windows |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|");
    for j in &report.where_.joints {
        let (u, q) = unit(&j.joint);
        let _ = writeln!(
            s,
            "| {} | {} {u} | {} {u} | {:.1} | {} {q} | {} {q} | {} | {} |",
            j.joint,
            g(j.torque_rms),
            g(j.torque_noise),
            j.torque_ratio,
            made(j.prediction_rms, g),
            g(j.prediction_noise),
            made(j.prediction_ratio, |x| format!("{x:.1}")),
            j.windows.len()
        );
    }
    let corrected = match chosen {
        // The figures show the whole explanation (`explained::traces`).
        _ if !traces.explained.is_empty() => {
            let left = if traces.left_out.is_empty() {
                String::new()
            } else {
                format!(
                    "; not in the figures (the calibrated model cannot take them): {}",
                    traces.left_out.join(", ")
                )
            };
            format!(
                "\"corrected\" = the model with the whole explanation ({} effect{}, fitted on the \
                 training data, applied unchanged to the held-out data){left}",
                traces.explained.len(),
                if traces.explained.len() == 1 { "" } else { "s" }
            )
        }
        Some(r) => format!(
            "\"corrected\" = the model with {} (fitted on the training data, applied unchanged \
             to the held-out data)",
            place(r)
        ),
        None => "no effect chosen".into(),
    };
    let _ = writeln!(
        s,
        "\nThe torque residual per joint; orange bands: the windows where it concentrates, \
         labelled by motion phase; grey band: 3 x the noise floor; {corrected}.\n"
    );
    for j in &report.where_.joints {
        let [residual, _, _] = files(&j.joint);
        let _ = writeln!(s, "![{} residual]({residual})\n", j.joint);
    }

    // Which.
    let _ = writeln!(s, "## Which (candidates ranked, training data)\n");
    let _ = writeln!(
        s,
        "{} candidates fitted; the first {} by AICc (share = part of the gap above noise \
         explained).\n",
        report.which.ranked.len(),
        RANKED_SHOWN.min(report.which.ranked.len())
    );
    let _ = writeln!(
        s,
        "| rank | effect | parameters | share | held-out share | delta AICc |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|");
    for (i, r) in report.which.ranked.iter().take(RANKED_SHOWN).enumerate() {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} | {:.1} |",
            i + 1,
            place(r),
            parameters(r),
            pct(r.share),
            pct(r.holdout_share),
            r.delta_aicc
        );
    }
    let _ = writeln!(s, "\n![ranking](ranking.svg)\n");

    // Shrink.
    let sh = &report.shrink;
    let _ = writeln!(s, "## How far it shrinks (held-out data)\n");
    let simulation = match sh.simulation_fraction {
        Some(x) => format!("the 0.1 s simulation error by {}", pct(x)),
        None => "the 0.1 s simulation error could not be measured (warnings)".into(),
    };
    let n = report.which.effects.len();
    match chosen {
        Some(r) if n > 1 => {
            let _ = writeln!(
                s,
                "With the {n} effects of the explanation (below) added to the model, the torque \
                 gap above noise shrinks by {} and {simulation} (overall figure `shrink.fraction` \
                 = {:.3}). The figures of this section show the first ranked, {}, alone.\n",
                pct(sh.torque_fraction),
                sh.fraction,
                place(r)
            );
        }
        Some(r) => {
            let _ = writeln!(
                s,
                "Adding {} to the model shrinks the torque gap above noise by {} and {simulation} \
                 (overall figure `shrink.fraction` = {:.3}).\n",
                place(r),
                pct(sh.torque_fraction),
                sh.fraction
            );
        }
        None => {
            let _ = writeln!(
                s,
                "No effect was added, so nothing shrinks (`shrink.fraction` = {:.3}).\n",
                sh.fraction
            );
        }
    }
    let _ = writeln!(
        s,
        "| joint | torque residual before | after | 0.1 s simulation error before | after |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|");
    for j in &sh.joints {
        let (u, q) = unit(&j.joint);
        let _ = writeln!(
            s,
            "| {} | {} {u} | {} {u} | {} {q} | {} {q} |",
            j.joint,
            g(j.torque_before),
            g(j.torque_after),
            made(j.simulation_before, g),
            made(j.simulation_after, g)
        );
    }
    let _ = writeln!(
        s,
        "\nPer joint: the held-out residual before and after, then measured vs nominal vs \
         corrected effort over 1 s around the largest residual; {corrected}.\n"
    );
    for j in &sh.joints {
        let [_, shrink, effort] = files(&j.joint);
        let _ = writeln!(
            s,
            "![{0} held-out residual]({shrink})\n\n![{0} effort]({effort})\n",
            j.joint
        );
    }
    s
}
