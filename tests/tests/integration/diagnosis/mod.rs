//! The diagnoser scored on random synthetic cases: robot, effect, joint,
//! magnitude (realistic ranges), excitation, noise level and seed drawn at
//! random; the generator writes the CSVs and a truth file; the diagnoser
//! gets the CSVs only; the truth is read after the verdict. Whether a case
//! is identifiable at all is decided from the truth side too (the
//! generator's `snr` and `distinct_snr`, see [`IDENTIFIABLE_SNR`]), never
//! by the diagnoser's own gap estimate. Targets (issue 7): effect named first in >= 90 % of
//! identifiable cases, joint right in >= 95 % of those, every control
//! answered `none`, median held-out shrink >= 80 %.
//!
//! Beside the scoring: a fitted parameter's reported spread against a
//! bootstrap (`spread.rs`); the noise floor and the answers on either side
//! of it (`floor.rs`).

mod floor;
mod spread;

use std::collections::BTreeMap;
use std::path::Path;

use dynamics_cli::gap::{SynthRequest, Truth};
use dynamics_sim2real::diagnose::Options;
use dynamics_sim2real::effects::EffectKind;
use dynamics_sim2real::synth::{ExcitationKind, Noise, Rng};
use robots::builtin::{diagnose_files, synth};

const CASES: usize = 44;
/// A case is identifiable when the withheld effect's effort, RMS along the
/// recorded motion through the diagnosis's smoothing (what lies above the
/// band it passes is in none of its fits), is at least this many times
/// the effort noise of one sample (`Truth::snr`, computed by the generator
/// from the truth side),
/// and so is the part of it that tells the effect from the simpler effect
/// it contains (`Truth::distinct_snr`: elasticity and backlash carry a
/// rotor inertia, which alone is `armature`; a backlash whose gap is never
/// crossed under load is a rotor on these data).
const IDENTIFIABLE_SNR: f64 = 2.0;

/// Seed base: `DIAGNOSIS_SEED_BASE` (default 0) shifts every draw, to check
/// that the scores are not a property of one set of seeds.
fn seed_base() -> u64 {
    std::env::var("DIAGNOSIS_SEED_BASE")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(0)
}
const ROBOTS: [&str; 3] = ["arm3r", "rrp-rigid", "mar"];

/// `DIAGNOSIS_ONLY=3,17` runs only those cases (to look at one closely;
/// the count of cases is then not checked).
fn only() -> Vec<usize> {
    std::env::var("DIAGNOSIS_ONLY")
        .map(|s| s.split(',').filter_map(|x| x.trim().parse().ok()).collect())
        .unwrap_or_default()
}

struct Outcome {
    truth: String,
    truth_joint: Option<String>,
    said: String,
    said_joint: Option<String>,
    identifiable: bool,
    shrink: f64,
}

fn run_case(i: usize, dir: &Path) -> Outcome {
    let base = seed_base();
    let mut rng = Rng::new(1000 + base + i as u64);
    let robot = ROBOTS[rng.below(ROBOTS.len())];
    // One case in eleven is a control without any effect.
    let kind = if i.is_multiple_of(11) {
        EffectKind::None
    } else {
        EffectKind::ALL[1 + rng.below(EffectKind::ALL.len() - 1)]
    };
    let excitation = [
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
    // A draw the generator cannot run (the closed loop goes unstable: e.g.
    // a rotor on the rrp arm's light direction of motion, where a 10 kg
    // point load sits on links of a few hundredths of a kg m^2) is drawn
    // again with another seed and the next excitation, and from the third
    // try on for the next robot.
    let mut seed = 77 + base + i as u64;
    let (mut robot, mut excitation) = (robot, excitation);
    let mut tries = 0;
    let out = loop {
        match synth(&SynthRequest {
            robot: robot.into(),
            kind: Some(kind),
            joint: None,
            magnitude: None,
            seed,
            excitation,
            duration: 6.0,
            noise,
        }) {
            Ok(out) => break out,
            Err(e) if tries < 6 => {
                eprintln!("case {i}: {robot} {kind:?} {excitation:?} seed {seed} redrawn: {e}");
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
            Err(e) => panic!("case {i}: {robot} {kind:?} {excitation:?} seed {seed}: {e}"),
        }
    };
    let (train, holdout, truth_file) = (
        dir.join(format!("{i}-a.csv")),
        dir.join(format!("{i}-b.csv")),
        dir.join(format!("{i}-truth.json")),
    );
    std::fs::write(&train, &out.train).expect("writes");
    std::fs::write(&holdout, &out.holdout).expect("writes");
    std::fs::write(
        &truth_file,
        serde_json::to_string(&out.truth).expect("json"),
    )
    .expect("writes");
    drop(out);
    let (report, _) = diagnose_files(robot, &train, &holdout, &Options::default(), &|_, _| {})
        .expect("diagnoses");
    // Only now read the truth.
    let truth: Truth = serde_json::from_str(&std::fs::read_to_string(&truth_file).expect("reads"))
        .expect("parses");
    let gap = report
        .where_
        .joints
        .iter()
        .map(|j| j.torque_ratio)
        .fold(0.0, f64::max);
    let v = &report.which.verdict;
    let first = report.which.ranked.first();
    // `none` and `unexplained` name no effect: they are said as such.
    let said = if v.names_effect() {
        first.map(|r| r.kind.to_string()).unwrap_or_default()
    } else {
        v.kind.to_string()
    };
    let said_joint = if v.names_effect() {
        first.and_then(|r| r.joint.clone())
    } else {
        None
    };
    eprintln!(
        "case {i:2} {robot:9} {:>22} {:>4} -> {:>22} {:>4} {:9} snr {:7.2} distinct {:7.2} gap {gap:7.1} shrink {:.2} ({}) top {:?}",
        truth.kind,
        truth.joint.clone().unwrap_or_default(),
        said,
        said_joint.clone().unwrap_or_default(),
        v.status,
        truth.snr,
        truth.distinct_snr,
        report.shrink.fraction,
        truth.effect,
        report.which.ranked.iter().take(2).map(|r| (r.kind.name(), r.delta_aicc.round(), (r.holdout_share * 100.0).round())).collect::<Vec<_>>()
    );
    // A miss: the top three, with their fitted parameters.
    if said != truth.kind && truth.kind != "none" {
        for r in report.which.ranked.iter().take(3) {
            eprintln!(
                "    case {i:2} ranked {:>22} {:>4} daicc {:9.1} holdout {:5.2} {:?}",
                r.kind,
                r.joint.clone().unwrap_or_default(),
                r.delta_aicc,
                r.holdout_share,
                r.parameters
                    .iter()
                    .map(|p| format!("{}={:.3e}", p.name, p.value))
                    .collect::<Vec<_>>()
            );
        }
    }
    Outcome {
        identifiable: truth.kind != "none"
            && truth.snr >= IDENTIFIABLE_SNR
            && truth.distinct_snr >= IDENTIFIABLE_SNR,
        truth: truth.kind,
        truth_joint: truth.joint,
        said,
        said_joint,
        shrink: report.shrink.fraction,
    }
}

#[test]
fn diagnoser_names_the_withheld_effect() {
    let dir = std::env::temp_dir().join(format!("dynamics-diagnosis-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let outcomes: Vec<Outcome> = std::thread::scope(|s| {
        let hs: Vec<_> = (0..2)
            .map(|t| {
                let dir = &dir;
                s.spawn(move || {
                    (0..CASES)
                        .filter(|i| i % 2 == t)
                        .filter(|i| only().is_empty() || only().contains(i))
                        .map(|i| run_case(i, dir))
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        hs.into_iter()
            .flat_map(|h| h.join().expect("case thread"))
            .collect()
    });
    let _ = std::fs::remove_dir_all(&dir);

    let mut confusion: BTreeMap<(String, String), usize> = BTreeMap::new();
    for o in &outcomes {
        *confusion
            .entry((o.truth.clone(), o.said.clone()))
            .or_default() += 1;
    }
    eprintln!("\nconfusion (truth -> said: count)");
    for ((t, s), c) in &confusion {
        eprintln!("  {t:>22} -> {s:<22} {c}");
    }
    let ident: Vec<&Outcome> = outcomes.iter().filter(|o| o.identifiable).collect();
    let named = ident.iter().filter(|o| o.said == o.truth).count();
    let joint_cases: Vec<&&Outcome> = ident
        .iter()
        .filter(|o| o.truth_joint.is_some() && o.said == o.truth)
        .collect();
    let joint_ok = joint_cases
        .iter()
        .filter(|o| o.said_joint == o.truth_joint)
        .count();
    let controls: Vec<&Outcome> = outcomes.iter().filter(|o| o.truth == "none").collect();
    let controls_ok = controls.iter().filter(|o| o.said == "none").count();
    let mut shrinks: Vec<f64> = ident
        .iter()
        .filter(|o| o.said == o.truth)
        .map(|o| o.shrink)
        .collect();
    shrinks.sort_by(f64::total_cmp);
    let median = shrinks.get(shrinks.len() / 2).copied().unwrap_or(0.0);
    eprintln!(
        "effect named first: {named}/{} identifiable; joint: {joint_ok}/{}; controls none: {controls_ok}/{}; median held-out shrink {median:.3}; not identifiable: {}",
        ident.len(),
        joint_cases.len(),
        controls.len(),
        outcomes.len() - ident.len() - controls.len()
    );
    assert!(outcomes.len() >= 40 || !only().is_empty());
    assert!(
        named as f64 >= 0.90 * ident.len() as f64,
        "effect named first in {named} of {}",
        ident.len()
    );
    assert!(
        joint_ok as f64 >= 0.95 * joint_cases.len() as f64,
        "joint right in {joint_ok} of {}",
        joint_cases.len()
    );
    assert_eq!(
        controls_ok,
        controls.len(),
        "a control was not answered none"
    );
    assert!(median >= 0.8, "median held-out shrink {median}");
}
