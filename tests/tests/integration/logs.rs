//! The diagnoser scored on damaged logs (issue 15): each single effect of
//! the vocabulary in turn, and controls, under one or two of the damages of
//! real logs (a jittered clock, repeated rows, holes, glitches, a 100 Hz
//! rate), drawn at random; the diagnoser gets the CSV files only. Targets:
//! the effect named first in at least 95 % of identifiable cases, the joint
//! right in at least 95 % of those, controls `none`, median held-out shrink
//! at least 0.9, and every damage present named by a warning.
//! `LOGS_SEED_BASE=N` draws other cases (base 0 was the one looked at while
//! building).

use dynamics_cli::gap::{Recording, SynthRequest, Truth};
use dynamics_sim2real::diagnose::Options;
use dynamics_sim2real::effects::EffectKind;
use dynamics_sim2real::synth::{ExcitationKind, Noise, Rng};
use dynamics_sim2real::Warning;
use robots::builtin::{diagnose_files, synth_recorded};

const CASES: usize = 44;
/// As in the clean scoring (`diagnosis.rs`): the effect's effort, and the
/// part that tells it from the simpler effect it contains, at least this
/// many times one sample's effort noise.
const IDENTIFIABLE_SNR: f64 = 2.0;
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
}

fn run_case(i: usize, dir: &std::path::Path) -> Outcome {
    let base = seed_base();
    let mut rng = Rng::new(5000 + base + i as u64);
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
    let rec = recording(&damages);
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
    let truth = out.truth;
    let (report, _) =
        diagnose_files(robot, &a, &b, &Options::default(), &|_, _| {}).expect("diagnoses");
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
        .all(|d| report.warnings.iter().any(|w| names(w, d)));
    // At 100 Hz, backlash (contact at 40-80 Hz) is beyond what the rate shows.
    let visible = !(rec.rate < 160.0 && truth.kind == "backlash");
    let identifiable = truth.kind != "none"
        && visible
        && truth.snr >= IDENTIFIABLE_SNR
        && truth.distinct_snr >= IDENTIFIABLE_SNR;
    eprintln!(
        "case {i:2} {robot:9} {:>22} {:>4} [{}] -> {:>22} {:>4} {:9} snr {:7.2} distinct {:7.2} shrink {:.2} warned {warned}",
        truth.kind,
        truth.joint.clone().unwrap_or_default(),
        damages.join(", "),
        said,
        said_joint.clone().unwrap_or_default(),
        v.status,
        truth.snr,
        truth.distinct_snr,
        report.shrink.fraction,
    );
    Outcome {
        truth,
        said,
        said_joint,
        identifiable,
        shrink: report.shrink.fraction,
        warned,
    }
}

#[test]
#[ignore = "issue 15's targets not met yet on seed base 0: 26/28 named (a Coulomb friction under a jittered clock taken for an encoder offset, a viscous friction at snr 2.0 at 100 Hz answered none); run with --ignored"]
fn diagnoser_names_the_effect_in_damaged_logs() {
    let dir = std::env::temp_dir().join(format!("dynamics-logs-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let outcomes: Vec<Outcome> = (0..CASES).map(|i| run_case(i, &dir)).collect();
    let _ = std::fs::remove_dir_all(&dir);
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
    eprintln!(
        "seed base {}: named {named}/{} identifiable, joint {joint_right}/{}, controls {quiet}/{} none, median shrink {median:.2}, damage warned {warned}/{}",
        seed_base(),
        ident.len(),
        joints.len(),
        controls.len(),
        outcomes.len()
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
}
