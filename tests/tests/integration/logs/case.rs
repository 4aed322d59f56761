//! One case: its record generated with the drawn effect and damages, the
//! diagnosis from the files alone, and what it said against the truth.

use dynamics_cli::gap::{SynthRequest, Truth};
use dynamics_sim2real::diagnose::Options;
use dynamics_sim2real::synth::{ExcitationKind, Noise, Rng};
use dynamics_sim2real::Warning;
use robots::builtin::{diagnose_files, synth_recorded};

use super::draw::{draw, recording, seed_base, ROBOTS};
use super::{rate_snr, IDENTIFIABLE_SNR, WINDOW_TOLERANCE};

/// Whether `w` names damage `name`.
fn names(w: &Warning, name: &str) -> bool {
    matches!(
        (name, w),
        ("jitter", Warning::Resampled { .. })
            | ("repeats", Warning::Repeated { .. })
            | ("holes", Warning::Hole { .. })
            | ("glitches", Warning::Glitch { .. })
            | ("100 Hz", Warning::RateTooLow { .. })
    )
}

pub(super) struct Outcome {
    pub(super) truth: Truth,
    pub(super) said: String,
    pub(super) said_joint: Option<String>,
    pub(super) identifiable: bool,
    pub(super) shrink: f64,
    pub(super) warned: bool,
    /// For a windowed effect named: whether its window is within
    /// [`WINDOW_TOLERANCE`]; for a late stream named: whether the channel
    /// is the late one; else true.
    pub(super) detail: bool,
}

pub(super) fn run_case(i: usize, dir: &std::path::Path, only: &[usize]) -> Outcome {
    let base = seed_base();
    let mut rng = Rng::new(5000 + base + i as u64);
    let (kind, window, late, damages) = draw(i, &mut rng);
    let mut rec = recording(&damages);
    rec.window = window;
    rec.damage.q_late = late.q;
    rec.damage.tau_late = late.tau;
    let mut robot = ROBOTS[rng.below(ROBOTS.len())];
    let mut excitation = [
        ExcitationKind::Sines,
        ExcitationKind::Chirp,
        ExcitationKind::PickPlace,
    ][rng.below(3)];
    let level = rng.uniform(0.5, 2.0);
    let noise = Noise {
        q: 2e-5 * level,
        qd: 2e-3 * level,
        tau_relative: 2e-3 * level,
    };
    let mut seed = 91 + base + i as u64;
    let mut tries = 0;
    let out = loop {
        let req = SynthRequest {
            robot: robot.into(),
            kind: Some(kind),
            joint: None,
            magnitude: None,
            seed,
            excitation,
            duration: 6.0,
            noise,
        };
        match synth_recorded(&req, &rec) {
            Ok(out) => break out,
            Err(e) if tries < 6 => {
                eprintln!("case {i}: {robot} {kind:?} seed {seed} redrawn: {e}");
                tries += 1;
                seed += 100_000;
                excitation = match excitation {
                    ExcitationKind::Sines => ExcitationKind::Chirp,
                    ExcitationKind::Chirp => ExcitationKind::PickPlace,
                    ExcitationKind::PickPlace => ExcitationKind::Sines,
                };
                if tries >= 2 {
                    let at = ROBOTS.iter().position(|r| *r == robot).unwrap_or(0);
                    robot = ROBOTS[(at + 1) % ROBOTS.len()];
                }
            }
            Err(e) => panic!("case {i}: {robot} {kind:?} seed {seed}: {e}"),
        }
    };
    let (a, b) = (
        dir.join(format!("{i}-a.csv")),
        dir.join(format!("{i}-b.csv")),
    );
    std::fs::write(&a, &out.train).expect("writes");
    std::fs::write(&b, &out.holdout).expect("writes");
    let mut truth = out.truth;
    // A late position or effort stream is a `time_delay` of that channel.
    if matches!(truth.late.as_deref(), Some("positions" | "effort")) {
        truth.kind = "time_delay".into();
    }
    let (report, _) =
        diagnose_files(robot, &a, &b, &Options::default(), &|_, _| {}).expect("diagnoses");
    if !only.is_empty() {
        eprintln!("truth: {}", truth.effect);
        eprintln!(
            "{}",
            serde_json::to_string_pretty(&report.which).unwrap_or_default()
        );
    }
    let v = &report.which.verdict;
    let first = report.which.ranked.first();
    let said = if v.names_effect() {
        first.map(|r| r.kind.to_string()).unwrap_or_default()
    } else {
        v.kind.to_string()
    };
    let said_joint = v
        .names_effect()
        .then(|| first.and_then(|r| r.joint.clone()))
        .flatten();
    let warned = damages
        .iter()
        .all(|d| report.warnings.iter().any(|w| names(w, d)))
        && (late.q == 0.0
            || report
                .warnings
                .iter()
                .any(|w| matches!(w, Warning::LatePositions { .. })))
        && (late.tau == 0.0
            || report
                .warnings
                .iter()
                .any(|w| matches!(w, Warning::LateEffort { .. })));
    // The window found, and the late channel named.
    let effect = report
        .which
        .effects
        .iter()
        .find(|e| e.kind.name() == truth.kind && e.joint == truth.joint);
    let found = effect.and_then(|e| e.window.clone());
    let detail = match (&truth.window, said == truth.kind) {
        (Some(w), true) => found.as_ref().is_some_and(|f| {
            (f.start - w.start).abs() < WINDOW_TOLERANCE && (f.end - w.end).abs() < WINDOW_TOLERANCE
        }),
        (None, true) if late.q > 0.0 || late.tau > 0.0 => {
            v.channel.map(|c| c.to_string()) == truth.late
        }
        _ => true,
    };
    // At 100 Hz, backlash (contact at 40-80 Hz) is beyond what the rate shows.
    let visible = !(rec.rate < 160.0 && truth.kind == "backlash");
    let identifiable = truth.kind != "none"
        && visible
        && rate_snr(truth.snr, rec.rate) >= IDENTIFIABLE_SNR
        && rate_snr(truth.distinct_snr, rec.rate) >= IDENTIFIABLE_SNR;
    let window_said = |w: Option<(f64, f64)>| {
        w.map(|(a, b)| format!(" [{a:.2}, {b:.2})"))
            .unwrap_or_default()
    };
    eprintln!(
        "case {i:2} {robot:9} {:>22}{}{} {:>4} [{}] -> {:>22}{}{} {:>4} {:9} snr {:7.2} distinct {:7.2} shrink {:.2} warned {warned}{} {}",
        truth.kind,
        window_said(truth.window.map(|w| (w.start, w.end))),
        match truth.late.as_deref() {
            Some(c @ ("positions" | "effort")) => format!(" {c} {:.1} ms", (late.q + late.tau) * 1e3),
            _ => String::new(),
        },
        truth.joint.clone().unwrap_or_default(),
        damages.join(", "),
        said,
        window_said(found.map(|w| (w.start, w.end))),
        v.channel
            .as_ref()
            .map(|c| {
                // The delay found, beside the channel.
                let d = first
                    .and_then(|r| r.parameters.iter().find(|p| p.name == "delay"))
                    .map(|p| format!(" {:.1} +- {:.1} ms", p.value * 1e3, p.std * 1e3))
                    .unwrap_or_default();
                format!(" ({c}{d})")
            })
            .unwrap_or_default(),
        said_joint.clone().unwrap_or_default(),
        v.status,
        truth.snr,
        truth.distinct_snr,
        report.shrink.fraction,
        if identifiable { "" } else { " (not identifiable)" },
        if detail { "" } else { "WINDOW/CHANNEL OFF" },
    );
    Outcome {
        detail,
        truth,
        said,
        said_joint,
        identifiable,
        shrink: report.shrink.fraction,
        warned,
    }
}
