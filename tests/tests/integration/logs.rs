//! The diagnoser scored on damaged logs (issue 15): each single effect of
//! the vocabulary in turn, and controls, under one or two of the damages of
//! real logs (a jittered clock, repeated rows, holes, glitches, a 100 Hz
//! rate), drawn at random; the diagnoser gets the CSV files only. Targets:
//! the effect named first in at least 95 % of identifiable cases, the joint
//! right in at least 95 % of those, controls `none`, median held-out shrink
//! at least 0.9, and every damage present named by a warning. Then
//! effects that start and stop (an encoder that slips at a drawn time and
//! keeps the offset, a tool in a medium and a payload carried for a drawn
//! window; the held-out run has the window a quarter of its start
//! earlier), a late position stream (named `time_delay`, channel
//! `positions`, and warned) and a late effort stream (channel `effort`,
//! warned), each under one damage: the window found must lie within
//! [`WINDOW_TOLERANCE`] of the truth's, the late channel be the one named.
//! `LOGS_SEED_BASE=N` draws other cases (base 0 was the one looked at while
//! building); `LOGS_ONLY=i,j` runs single cases (printing the report and
//! the truth), `LOGS_KEEP=DIR` keeps the cases' files there.

use dynamics_cli::gap::{Recording, SynthRequest, Truth};
use dynamics_sim2real::diagnose::Options;
use dynamics_sim2real::effects::EffectKind;
use dynamics_sim2real::effects::Window;
use dynamics_sim2real::synth::{ExcitationKind, Noise, Rng};
use dynamics_sim2real::Warning;
use robots::builtin::{diagnose_files, synth_recorded};

/// Single effects under damage, then effects in a window and late positions,
/// then late efforts.
const CASES: usize = 44;
const LATER_CASES: usize = 16;
/// Of the later cases, the first this many cycle through the windows and
/// late positions; the rest have the effort late.
const CYCLED_CASES: usize = 12;
/// How near the truth's edges a window found must lie, s (a few widths of
/// the 40 ms smoothing filter).
const WINDOW_TOLERANCE: f64 = 0.2;
/// As in the clean scoring (`diagnosis/`): the effect's effort, and the
/// part that tells it from the simpler effect it contains, at least this
/// many times one sample's effort noise, on a 1 kHz record; on a record of
/// rate `r`, the ratio times `sqrt(r / 1 kHz)` (see [`rate_snr`]).
const IDENTIFIABLE_SNR: f64 = 2.0;

/// The generator's signal-to-noise ratio (per sample) of a record of rate
/// `rate`, as the ratio a 1 kHz record of the same motion and the same
/// evidence would have: the evidence grows with the samples (the sum of
/// the squared ratio), so 100 Hz holds a tenth of it. On the same draw
/// (base 12000, case 37: a rotor inertia of snr 2.2 on the RRP) the
/// diagnosis gained 249 AICc at 1 kHz and 22 at 100 Hz (under the
/// `none` margin of 100; the inertia 2.05 +- 0.41 against a truth of
/// 3.12, 1 kHz 3.17 +- 0.18).
fn rate_snr(snr: f64, rate: f64) -> f64 {
    snr * (rate / 1000.0).min(1.0).sqrt()
}
const ROBOTS: [&str; 3] = ["arm3r", "rrp-rigid", "mar"];

fn seed_base() -> u64 {
    std::env::var("LOGS_SEED_BASE")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(0)
}

/// The damages, by name.
const DAMAGES: [&str; 5] = ["jitter", "repeats", "holes", "glitches", "100 Hz"];

fn recording(names: &[&str]) -> Recording {
    let mut r = Recording::default();
    for n in names {
        match *n {
            "jitter" => r.damage.jitter = 0.3,
            "repeats" => r.damage.repeats = 0.05,
            "holes" => r.damage.holes = 2,
            "glitches" => r.damage.glitches = 3,
            _ => r.rate = 100.0,
        }
    }
    r
}

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

struct Outcome {
    truth: Truth,
    said: String,
    said_joint: Option<String>,
    identifiable: bool,
    shrink: f64,
    warned: bool,
    /// For a windowed effect named: whether its window is within
    /// [`WINDOW_TOLERANCE`]; for a late stream named: whether the channel
    /// is the late one; else true.
    detail: bool,
}

/// A late stream: positions or effort, s.
#[derive(Clone, Copy, Default)]
struct Late {
    q: f64,
    tau: f64,
}

/// What case `i` withholds: its effect kind, a window, a late position or
/// effort stream, its damages.
fn draw(i: usize, rng: &mut Rng) -> (EffectKind, Option<Window>, Late, Vec<&'static str>) {
    if i < CASES {
        let kind = if i.is_multiple_of(11) {
            EffectKind::None
        } else {
            EffectKind::ALL[i % 11]
        };
        let mut damages = vec![DAMAGES[rng.below(DAMAGES.len())]];
        if rng.below(2) == 0 {
            let second = DAMAGES[rng.below(DAMAGES.len())];
            if second != damages[0] {
                damages.push(second);
            }
        }
        return (kind, None, Late::default(), damages);
    }
    let damages = vec![DAMAGES[rng.below(DAMAGES.len())]];
    if i - CASES >= CYCLED_CASES {
        let tau = rng.uniform(0.01, 0.025);
        return (EffectKind::None, None, Late { q: 0.0, tau }, damages);
    }
    let start = rng.uniform(1.0, 3.0);
    let length = rng.uniform(1.5, 2.5);
    match (i - CASES) % 4 {
        0 => (
            EffectKind::EncoderOffset,
            Some(Window {
                start,
                end: f64::INFINITY,
            }),
            Late::default(),
            damages,
        ),
        1 => (
            EffectKind::EnvironmentResistance,
            Some(Window {
                start,
                end: start + length,
            }),
            Late::default(),
            damages,
        ),
        2 => (
            EffectKind::PayloadMass,
            Some(Window {
                start,
                end: start + length,
            }),
            Late::default(),
            damages,
        ),
        _ => {
            let q = rng.uniform(0.01, 0.025);
            (EffectKind::None, None, Late { q, tau: 0.0 }, damages)
        }
    }
}

fn run_case(i: usize, dir: &std::path::Path, only: &[usize]) -> Outcome {
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
        first.map(|r| r.kind.clone()).unwrap_or_default()
    } else {
        v.kind.clone()
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
        .find(|e| e.kind == truth.kind && e.joint == truth.joint);
    let found = effect.and_then(|e| e.window.clone());
    let detail = match (&truth.window, said == truth.kind) {
        (Some(w), true) => found.as_ref().is_some_and(|f| {
            (f.start - w.start).abs() < WINDOW_TOLERANCE && (f.end - w.end).abs() < WINDOW_TOLERANCE
        }),
        (None, true) if late.q > 0.0 || late.tau > 0.0 => v.channel == truth.late,
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

#[test]
#[ignore = "50-200 s of diagnosis (60 cases); identifiable by the evidence of a 1 kHz record (rate_snr): base 12000 31/33 named (a backlash on the MAR named elastic twice), bases 21000 36/39, 22000 27/28, 23000 34/34, 24000 31/31, fresh 31000 34/36 (two RRP slide backlashes), 32000 35/35, 33000 34/35; joints, controls, warnings right on all eight; run with --ignored"]
fn diagnoser_names_the_effect_in_damaged_logs() {
    // `LOGS_KEEP=DIR` writes the cases' files there and keeps them.
    let keep = std::env::var("LOGS_KEEP").ok();
    let dir = keep
        .clone()
        .map(std::path::PathBuf::from)
        .unwrap_or_else(|| {
            std::env::temp_dir().join(format!("dynamics-logs-{}", std::process::id()))
        });
    std::fs::create_dir_all(&dir).expect("temp dir");
    // `LOGS_ONLY=3,17` runs only those cases (to look at one closely).
    let only: Vec<usize> = std::env::var("LOGS_ONLY")
        .map(|s| s.split(',').filter_map(|x| x.trim().parse().ok()).collect())
        .unwrap_or_default();
    let outcomes: Vec<Outcome> = (0..CASES + LATER_CASES)
        .filter(|i| only.is_empty() || only.contains(i))
        .map(|i| run_case(i, &dir, &only))
        .collect();
    if keep.is_none() {
        let _ = std::fs::remove_dir_all(&dir);
    }
    let ident: Vec<&Outcome> = outcomes.iter().filter(|o| o.identifiable).collect();
    let named = ident.iter().filter(|o| o.said == o.truth.kind).count();
    let joints: Vec<&&Outcome> = ident
        .iter()
        .filter(|o| o.said == o.truth.kind && o.truth.joint.is_some())
        .collect();
    let joint_right = joints
        .iter()
        .filter(|o| o.said_joint == o.truth.joint)
        .count();
    let controls: Vec<&Outcome> = outcomes.iter().filter(|o| o.truth.kind == "none").collect();
    let quiet = controls.iter().filter(|o| o.said == "none").count();
    let mut shrinks: Vec<f64> = ident
        .iter()
        .filter(|o| o.said == o.truth.kind)
        .map(|o| o.shrink)
        .collect();
    shrinks.sort_by(f64::total_cmp);
    let median = shrinks.get(shrinks.len() / 2).copied().unwrap_or(0.0);
    let warned = outcomes.iter().filter(|o| o.warned).count();
    let later: Vec<&&Outcome> = ident
        .iter()
        .filter(|o| o.truth.window.is_some() || o.truth.late.is_some())
        .filter(|o| o.said == o.truth.kind)
        .collect();
    let detailed = later.iter().filter(|o| o.detail).count();
    eprintln!(
        "seed base {}: named {named}/{} identifiable, joint {joint_right}/{}, controls {quiet}/{} none, median shrink {median:.2}, damage warned {warned}/{}, windows and channels right {detailed}/{}",
        seed_base(),
        ident.len(),
        joints.len(),
        controls.len(),
        outcomes.len(),
        later.len()
    );
    assert!(
        named as f64 >= 0.95 * ident.len() as f64,
        "named {named}/{}",
        ident.len()
    );
    assert!(
        joint_right as f64 >= 0.95 * joints.len() as f64,
        "joints {joint_right}/{}",
        joints.len()
    );
    assert_eq!(quiet, controls.len(), "controls");
    assert!(median >= 0.9, "median shrink {median}");
    assert_eq!(warned, outcomes.len(), "warnings");
    // (A window's edge where the effect fades below the noise, a medium
    // met at low speed, is not in the data: 90 %.)
    assert!(
        detailed as f64 >= 0.9 * later.len() as f64,
        "windows and channels {detailed}/{}",
        later.len()
    );
}
