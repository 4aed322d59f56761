//! The compound explanation scored on random compound cases (issue 14):
//! realistic arms (Coulomb and viscous friction on every joint, 2-8 % of
//! each joint's peak effort, and one further effect), two or three effects
//! of different kinds on different joints, and controls without any
//! effect, on arm3r, rrp, mar, ur5 and panda. The generator writes the
//! training and held-out CSV texts; the diagnoser gets only what they
//! hold (read back from the text); the truth is looked at after the
//! report. Per case: recall (true effects named at the right place, of
//! those large enough to be seen, see [`IDENTIFIABLE_SNR`]) and precision
//! (named effects that are true; also printed: the precision counting as
//! true a rotor inertia named at a joint whose motor side shows no more
//! than its rigid rotor, but the target is on the strict one). Targets:
//! mean recall and mean precision
//! at least 0.9, every control names nothing, median held-out shrink at
//! least 0.9. `COMPOUND_CASES=N` scores more cases, `COMPOUND_SEED_BASE=B`
//! draws others, `COMPOUND_ONLY=3,17` runs only those cases (the targets
//! are then not asserted).

use std::collections::BTreeMap;

use dynamics_runtime::Robot;
use dynamics_sim2real::data::{read_csv_str, write_csv, Measured};
use dynamics_sim2real::diagnose::{diagnose, Options, Report};
use dynamics_sim2real::effects::{Effect, PlaceKind, Tip};
use dynamics_sim2real::inertial::check;
use dynamics_sim2real::synth::{
    draw_compound, synthesize, synthesize_with_size, CompoundCase, ExcitationKind, Noise, Rng,
    SynthOptions,
};
use nalgebra::SVector;
use robots::registry::AnyRobot;

/// A withheld effect counts for recall when its effort alone, RMS along
/// the motion through the diagnosis's smoothing, is at least this many
/// times one sample's effort noise (and
/// so is the part a rigid rotor does not explain, for the motor sides).
const IDENTIFIABLE_SNR: f64 = 2.0;
const ROBOTS: [&str; 5] = ["arm3r", "rrp-rigid", "mar", "ur5", "panda"];

fn env(name: &str, default: u64) -> u64 {
    std::env::var(name)
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(default)
}

struct Outcome {
    robot: &'static str,
    case: CompoundCase,
    /// Per true effect: kind, place, identifiable, found.
    truth: Vec<(String, String, bool, bool)>,
    /// Per named effect: kind, place, true.
    said: Vec<(String, String, bool)>,
    /// Per named effect: a rotor inertia (`armature`) named where the truth
    /// has a motor side (elasticity, backlash) whose part beyond its rigid
    /// rotor is too small to be seen: what the data show of it.
    rotor: Vec<bool>,
    shrink: f64,
    rms_shrink: f64,
}

fn place<R: Robot<N>, const N: usize>(e: &Effect) -> String {
    match e.joint() {
        Some(j) => R::JOINT_NAMES[j].to_string(),
        None if e.kind().place() == PlaceKind::Point => {
            Tip::of::<R, N>().name::<R, N>().to_string()
        }
        None => String::new(),
    }
}

/// Synthesises, diagnoses and scores one case on `robot`.
fn case_on<R: Robot<N> + Clone + Sync, const N: usize>(
    robot: &R,
    name: &'static str,
    case: CompoundCase,
    i: usize,
    rng: &mut Rng,
) -> Result<Outcome, String> {
    let base = env("COMPOUND_SEED_BASE", 0);
    let excitation = [
        ExcitationKind::Sines,
        ExcitationKind::Chirp,
        ExcitationKind::PickPlace,
    ][rng.below(3)];
    let level = rng.uniform(0.5, 2.0);
    let m = robots::builtin::motion(name);
    let (home, amp) = (m.home, m.amplitude);
    let seed = 77 + base + i as u64 + 100_000 * rng.below(1000) as u64;
    let opts = SynthOptions::<N> {
        duration: 6.0,
        excitation,
        home: SVector::from_fn(|k, _| home[k]),
        amplitude: SVector::from_fn(|k, _| amp[k]),
        noise: Noise {
            q: 2e-5 * level,
            qd: 2e-3 * level,
            tau_relative: 2e-3 * level,
        },
        seed,
        ..Default::default()
    };
    let effects = draw_compound(robot, case, &opts, rng);
    let hold_opts = SynthOptions {
        seed: seed + 1_000_003,
        ..opts.clone()
    };
    let train = synthesize(robot, &effects, &opts).map_err(|e| e.to_string())?;
    let holdout = synthesize(robot, &effects, &hold_opts).map_err(|e| e.to_string())?;
    // What a CSV holds.
    let through_csv = |m: &Measured<N>, file: &str| -> Measured<N> {
        let mut text = Vec::new();
        write_csv(&mut text, m, &R::JOINT_NAMES).expect("csv");
        read_csv_str(
            &String::from_utf8(text).expect("utf-8"),
            &R::JOINT_NAMES,
            file,
        )
        .expect("reads back")
    };
    let (train, holdout) = (
        through_csv(&train, "train"),
        through_csv(&holdout, "holdout"),
    );
    let report: Report = diagnose(robot, &train, &holdout, &Options::default(), &|_, _| {})
        .map_err(|e| e.to_string())?;
    // Only now the truth: which effects are large enough to be seen
    // (friction on every joint of a realistic arm is, at 2-8 % of the
    // peak effort against noise of at most 0.4 %).
    let (mut truth, mut rotor_only) = (Vec::new(), Vec::new());
    for e in &effects {
        let friction_everywhere = case == CompoundCase::RealisticArm
            && matches!(
                e,
                Effect::CoulombFriction { .. } | Effect::ViscousFriction { .. }
            );
        let (identifiable, seen) = if friction_everywhere {
            (true, true)
        } else {
            let sized = synthesize_with_size(robot, &[*e], &opts).map_err(|e| e.to_string())?;
            let seen = sized.snr() >= IDENTIFIABLE_SNR;
            (seen && sized.distinct_snr() >= IDENTIFIABLE_SNR, seen)
        };
        // A motor side seen only as its rigid rotor.
        rotor_only.push(
            matches!(e, Effect::JointElasticity { .. } | Effect::Backlash { .. })
                && seen
                && !identifiable,
        );
        truth.push((
            e.kind().name().to_string(),
            place::<R, N>(e),
            identifiable,
            false,
        ));
    }
    // Every link correction reported is a physical body with the link's
    // nominal parameters (mass >= 0, inertia about the centre of mass
    // positive semi-definite, triangle inequalities).
    let mut nominal = vec![SVector::<f64, 10>::zeros(); R::LINK_NAMES.len()];
    robot
        .inertial_parameters(&mut nominal)
        .expect("nominal links");
    for x in report
        .which
        .effects
        .iter()
        .filter(|x| x.kind.name() == "inertial_parameters")
    {
        let name = x.point.clone().unwrap_or_default();
        let l = R::LINK_NAMES
            .iter()
            .position(|n| *n == name)
            .unwrap_or_else(|| panic!("case {i}: no link {name}"));
        let d = SVector::<f64, 10>::from_fn(|i, _| x.parameters[i].value);
        if let Err(e) = check(&(nominal[l] + d), 1e-6) {
            panic!("case {i}: {name}: {e}: {:?}", x.description);
        }
    }
    let (mut said, mut rotor) = (Vec::new(), Vec::new());
    for x in &report.which.effects {
        let p = x.joint.clone().or(x.point.clone()).unwrap_or_default();
        let mut names = vec![(x.kind.to_string(), p.clone())];
        if let Some(r) = &x.ambiguous_with {
            names.push((
                r.kind.to_string(),
                r.joint.clone().or(r.point.clone()).unwrap_or_default(),
            ));
        }
        let mut ok = false;
        for t in truth.iter_mut() {
            if names.iter().any(|(k, p)| *k == t.0 && *p == t.1) {
                t.3 = true;
                ok = true;
            }
        }
        rotor.push(
            !ok && x.kind.name() == "armature"
                && rotor_only.iter().zip(&truth).any(|(r, t)| *r && t.1 == p),
        );
        said.push((x.kind.to_string(), p, ok));
    }
    eprintln!(
        "case {i:3} {name:9} {case:?} {excitation:?} level {level:.2}: shrink {:.3} (rms {:.3}) \n    truth {:?}\n    said  {:?}",
        report.shrink.fraction,
        report.shrink.rms_fraction,
        truth
            .iter()
            .map(|t| format!("{}@{}{}{}", t.0, t.1, if t.2 { "" } else { "(small)" }, if t.3 { "" } else { " MISSED" }))
            .collect::<Vec<_>>(),
        said.iter()
            .map(|s| format!("{}@{}{}", s.0, s.1, if s.2 { "" } else { " FALSE" }))
            .collect::<Vec<_>>(),
    );
    Ok(Outcome {
        robot: name,
        case,
        truth,
        said,
        rotor,
        shrink: report.shrink.fraction,
        rms_shrink: report.shrink.rms_fraction,
    })
}

fn run_case(i: usize) -> Outcome {
    let base = env("COMPOUND_SEED_BASE", 0);
    let mut rng = Rng::new(5000 + base + i as u64);
    let case = if i.is_multiple_of(6) {
        CompoundCase::Control
    } else if i.is_multiple_of(2) {
        CompoundCase::Mixed
    } else {
        CompoundCase::RealisticArm
    };
    let mut at = i % ROBOTS.len();
    for attempt in 0..6 {
        let name = ROBOTS[at];
        let robot = AnyRobot::by_name(name).expect("a robot");
        let out = robots::each_robot!(&robot, r => case_on(r, name, case, i, &mut rng));
        match out {
            Ok(o) => return o,
            Err(e) => {
                eprintln!("case {i}: {name} {case:?} redrawn: {e}");
                if attempt >= 2 {
                    at = (at + 1) % ROBOTS.len();
                }
            }
        }
    }
    panic!("case {i}: no draw could be run");
}

#[test]
fn compound_explanation_names_every_effect() {
    let cases = env("COMPOUND_CASES", 60) as usize;
    let only: Option<Vec<usize>> = std::env::var("COMPOUND_ONLY")
        .ok()
        .map(|s| s.split(',').filter_map(|x| x.trim().parse().ok()).collect());
    let wanted = |i: &usize| only.as_ref().is_none_or(|o| o.contains(i));
    let outcomes: Vec<Outcome> = std::thread::scope(|s| {
        let hs: Vec<_> = (0..2)
            .map(|t| {
                s.spawn(move || {
                    (0..cases)
                        .filter(|i| i % 2 == t && wanted(i))
                        .map(run_case)
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        hs.into_iter()
            .flat_map(|h| h.join().expect("case thread"))
            .collect()
    });
    let mut per_kind: BTreeMap<String, (usize, usize)> = BTreeMap::new();
    let (mut recalls, mut precisions, mut shrinks, mut rms) = (vec![], vec![], vec![], vec![]);
    let mut rotor_precisions = vec![];
    let mut controls_ok = 0;
    for o in &outcomes {
        for t in o.truth.iter().filter(|t| t.2) {
            let e = per_kind.entry(t.0.clone()).or_default();
            e.0 += t.3 as usize;
            e.1 += 1;
        }
        if o.case == CompoundCase::Control {
            controls_ok += o.said.is_empty() as usize;
            continue;
        }
        let seen: Vec<_> = o.truth.iter().filter(|t| t.2).collect();
        if !seen.is_empty() {
            recalls.push(seen.iter().filter(|t| t.3).count() as f64 / seen.len() as f64);
        }
        precisions.push(if o.said.is_empty() {
            1.0
        } else {
            o.said.iter().filter(|s| s.2).count() as f64 / o.said.len() as f64
        });
        rotor_precisions.push(if o.said.is_empty() {
            1.0
        } else {
            let right = o.said.iter().zip(&o.rotor).filter(|(s, r)| s.2 || **r);
            right.count() as f64 / o.said.len() as f64
        });
        shrinks.push(o.shrink);
        rms.push(o.rms_shrink);
    }
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len().max(1) as f64;
    let median = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v.get(v.len() / 2).copied().unwrap_or(0.0)
    };
    eprintln!("\nrecall per effect kind (identifiable effects found / present)");
    for (k, (f, n)) in &per_kind {
        eprintln!("  {k:>22} {f}/{n}");
    }
    let controls = outcomes
        .iter()
        .filter(|o| o.case == CompoundCase::Control)
        .count();
    let big = outcomes
        .iter()
        .filter(|o| matches!(o.robot, "ur5" | "panda"))
        .count();
    let (r, p) = (mean(&recalls), mean(&precisions));
    let (ms, mr) = (median(&mut shrinks), median(&mut rms));
    eprintln!(
        "{} cases ({big} on 6-7 joint arms): mean recall {r:.3}, mean precision {p:.3}, controls naming nothing {controls_ok}/{controls}, median held-out shrink {ms:.3} (plain RMS {mr:.3})",
        outcomes.len()
    );
    let rotors: usize = outcomes
        .iter()
        .map(|o| o.rotor.iter().filter(|r| **r).count())
        .sum();
    eprintln!(
        "of the effects counted false, {rotors} are a rotor inertia named where a motor side's rigid rotor is all the data show of it; counted true, mean precision {:.3}",
        mean(&rotor_precisions)
    );
    if only.is_some() {
        return;
    }
    assert!(r >= 0.9, "mean recall {r}");
    assert!(p >= 0.9, "mean precision {p}");
    assert_eq!(controls_ok, controls, "a control named an effect");
    assert!(ms >= 0.9, "median held-out shrink {ms}");
}
