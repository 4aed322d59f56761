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
//! are then not asserted). `COMPOUND_HOLD_LINKS=1` diagnoses with
//! [`Options::hold_links`] (link corrections held to the nearest physical
//! body) and scores that, `COMPOUND_JUDGE_LINKS=1` with
//! [`Options::judge_links`] (never held, not even where most links' corrections
//! leave no body). `COMPOUND_DUMP=DIR` writes each case's training
//! and held-out records (CSV), its drawn effects and the report (JSON)
//! into `DIR`, named by case and robot.
//!
//! `COMPOUND_MOTION=designed` drives every training run with a motion
//! designed once per robot by `dynamics_sim2real::excite` (6 s, the
//! robot's limits, default options) instead of the drawn reference; the
//! effects are drawn as before (against the drawn reference: the same
//! effects) and the held-out run is the same drawn one. `COMPOUND_MOTION=both`
//! scores every case both ways and also asserts that the median relative
//! error of the named true effects' main parameters shrinks on the
//! designed motion (issue 28, "it pays off"; docs/excite.md).

use std::any::Any;
use std::collections::{BTreeMap, HashMap};
use std::sync::{Mutex, OnceLock};

use dynamics_runtime::Robot;
use dynamics_sim2real::data::{read_csv_str, write_csv, Measured};
use dynamics_sim2real::diagnose::{diagnose, Options, Report};
use dynamics_sim2real::effects::{Effect, PlaceKind, Tip};
use dynamics_sim2real::excite::{design, Fourier, Options as DesignOptions};
use dynamics_sim2real::inertial::check;
use dynamics_sim2real::synth::{
    draw_compound, synthesize, synthesize_with_size, CompoundCase, Excitation, ExcitationKind,
    Noise, Rng, SynthOptions,
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
    /// Per true effect named at its place with its own kind: the relative
    /// error of its main parameter (see [`main_parameter`]).
    errors: Vec<(String, f64)>,
    /// The case's number and, per entry of `errors`, the effect's place.
    index: usize,
    places: Vec<String>,
}

/// Duration of every run, s.
const DURATION: f64 = 6.0;

/// The motion designed for robot `name` (once per robot and process).
fn designed_motion<R: Robot<N> + Sync, const N: usize>(
    robot: &R,
    name: &'static str,
) -> Fourier<N> {
    static CACHE: OnceLock<Mutex<HashMap<&'static str, Box<dyn Any + Send>>>> = OnceLock::new();
    let mut cache = CACHE
        .get_or_init(|| Mutex::new(HashMap::new()))
        .lock()
        .expect("design cache");
    let entry = cache.entry(name).or_insert_with(|| {
        let m = robots::builtin::motion(name);
        let lim = dynamics_cli::excite::limits::<N>(
            AnyRobot::by_name(name).expect("robot").limits().as_ref(),
            &m,
        );
        let d = design(robot, &lim, &DesignOptions::new(DURATION))
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        eprintln!(
            "{name}: designed {DURATION} s, condition number {:.1}",
            d.figures.condition
        );
        Box::new(d.motion)
    });
    entry
        .downcast_ref::<Fourier<N>>()
        .expect("the robot's joint count")
        .clone()
}

/// The main parameter of an effect: its name in the report and its true
/// value (`None`: not compared: a link correction, an effort scale).
fn main_parameter(e: &Effect) -> Option<(&'static str, f64)> {
    Some(match *e {
        Effect::CoulombFriction { fc, .. } => ("fc", fc),
        Effect::ViscousFriction { fv, .. } => ("fv", fv),
        Effect::StribeckFriction { fc, .. } => ("fc", fc),
        Effect::Armature { inertia, .. } => ("inertia", inertia),
        Effect::PayloadMass { mass, .. } => ("mass", mass),
        Effect::EnvironmentResistance { mu, .. } => ("mu", mu),
        Effect::EncoderOffset { offset, .. } => ("offset", offset),
        Effect::TimeDelay { delay } => ("delay", delay),
        Effect::JointElasticity { stiffness, .. } => ("stiffness", stiffness),
        Effect::Backlash { half_width, .. } => ("half_width", half_width),
        Effect::EffortOffset { offset, .. } => ("offset", offset),
        Effect::JointSpring { stiffness, .. } => ("stiffness", stiffness),
        Effect::EffortScale { .. } | Effect::InertialParameters { .. } => return None,
    })
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
fn case_on<R: Robot<N> + Clone + Send + Sync + 'static, const N: usize>(
    robot: &R,
    name: &'static str,
    case: CompoundCase,
    i: usize,
    (base, rng): (u64, &mut Rng),
    designed: bool,
) -> Result<Outcome, String> {
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
        duration: DURATION,
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
    // The training run: the drawn reference, or the designed motion (the
    // same effects, drawn against the drawn reference).
    let opts = if designed {
        SynthOptions {
            motion: Some(Excitation::designed(designed_motion(robot, name))),
            ..opts
        }
    } else {
        opts
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
    let dump = std::env::var_os("COMPOUND_DUMP").map(std::path::PathBuf::from);
    if let Some(dir) = &dump {
        std::fs::create_dir_all(dir).map_err(|e| e.to_string())?;
        for (m, file) in [(&train, "train"), (&holdout, "holdout")] {
            let mut text = Vec::new();
            write_csv(&mut text, m, &R::JOINT_NAMES).map_err(|e| e.to_string())?;
            std::fs::write(dir.join(format!("{i:03}-{name}-{file}.csv")), text)
                .map_err(|e| e.to_string())?;
        }
        std::fs::write(
            dir.join(format!("{i:03}-{name}-truth.txt")),
            format!("{effects:#?}\n"),
        )
        .map_err(|e| e.to_string())?;
    }
    let options = Options {
        hold_links: env("COMPOUND_HOLD_LINKS", 0) == 1,
        judge_links: env("COMPOUND_JUDGE_LINKS", 0) == 1,
        ..Options::default()
    };
    let report: Report =
        diagnose(robot, &train, &holdout, &options, &|_, _| {}).map_err(|e| e.to_string())?;
    if let Some(dir) = &dump {
        let json = serde_json::to_string_pretty(&report).map_err(|e| e.to_string())?;
        std::fs::write(dir.join(format!("{i:03}-{name}-report.json")), json)
            .map_err(|e| e.to_string())?;
    }
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
    let (mut said, mut rotor, mut errors, mut places) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new());
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
        // The named effect's own parameter against the true one of its
        // kind at its place.
        for (e, t) in effects.iter().zip(&truth) {
            if t.0 != x.kind.to_string() || t.1 != p {
                continue;
            }
            let Some((param, value)) = main_parameter(e) else {
                continue;
            };
            let fitted = x
                .parameters
                .iter()
                .find(|q| q.name == param && q.note.is_none() && q.value.is_finite());
            if let (Some(f), true) = (fitted, value.abs() > 0.0) {
                errors.push((t.0.clone(), ((f.value - value) / value).abs()));
                places.push(t.1.clone());
            }
        }
        said.push((x.kind.to_string(), p, ok));
    }
    eprintln!(
        "case {i:3} {name:9} {case:?} {} level {level:.2}: shrink {:.3} (rms {:.3}) \n    truth {:?}\n    said  {:?}",
        if designed { "Designed".to_string() } else { format!("{excitation:?}") },
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
        errors,
        index: i,
        places,
    })
}

/// Per named true effect: (case, kind, place) and its relative error.
fn keyed(outcomes: &[Outcome]) -> BTreeMap<(usize, String, String), f64> {
    outcomes
        .iter()
        .flat_map(|o| {
            o.errors
                .iter()
                .zip(&o.places)
                .map(move |((k, e), p)| ((o.index, k.clone(), p.clone()), *e))
        })
        .collect()
}

fn run_case(base: u64, i: usize, designed: bool) -> Outcome {
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
        let out =
            robots::each_robot!(&robot, r => case_on(r, name, case, i, (base, &mut rng), designed));
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

/// What one scoring found: mean recall, mean precision, controls naming
/// nothing (and their count), median held-out shrink, median relative
/// parameter error of the named true effects (and their count).
struct Score {
    recall: f64,
    precision: f64,
    controls_ok: usize,
    controls: usize,
    shrink: f64,
    error: f64,
    errors: usize,
}

fn score(outcomes: &[Outcome], label: &str) -> Score {
    let mut per_kind: BTreeMap<String, (usize, usize)> = BTreeMap::new();
    let (mut recalls, mut precisions, mut shrinks, mut rms) = (vec![], vec![], vec![], vec![]);
    let mut rotor_precisions = vec![];
    let mut controls_ok = 0;
    let mut errors: Vec<f64> = vec![];
    let mut kind_errors: BTreeMap<String, Vec<f64>> = BTreeMap::new();
    for o in outcomes {
        for (k, e) in &o.errors {
            errors.push(*e);
            kind_errors.entry(k.clone()).or_default().push(*e);
        }
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
    eprintln!("\n[{label}] recall per effect kind (identifiable effects found / present)");
    for (k, (f, n)) in &per_kind {
        eprintln!("  {k:>22} {f}/{n}");
    }
    eprintln!(
        "[{label}] median relative error of the main parameter per kind (named true effects)"
    );
    for (k, v) in kind_errors.iter_mut() {
        let n = v.len();
        eprintln!("  {k:>22} {:.3} ({n})", median(v));
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
    let n_err = errors.len();
    let me = median(&mut errors);
    eprintln!(
        "[{label}] {} cases ({big} on 6-7 joint arms): mean recall {r:.3}, mean precision {p:.3}, controls naming nothing {controls_ok}/{controls}, median held-out shrink {ms:.3} (plain RMS {mr:.3}), median relative parameter error {me:.3} ({n_err} named true effects)",
        outcomes.len()
    );
    let rotors: usize = outcomes
        .iter()
        .map(|o| o.rotor.iter().filter(|r| **r).count())
        .sum();
    eprintln!(
        "[{label}] of the effects counted false, {rotors} are a rotor inertia named where a motor side's rigid rotor is all the data show of it; counted true, mean precision {:.3}",
        mean(&rotor_precisions)
    );
    Score {
        recall: r,
        precision: p,
        controls_ok,
        controls,
        shrink: ms,
        error: me,
        errors: n_err,
    }
}

#[test]
fn compound_explanation_names_every_effect() {
    let cases = env("COMPOUND_CASES", 60) as usize;
    let only: Option<Vec<usize>> = std::env::var("COMPOUND_ONLY")
        .ok()
        .map(|s| s.split(',').filter_map(|x| x.trim().parse().ok()).collect());
    let modes: &[bool] = match std::env::var("COMPOUND_MOTION").as_deref() {
        Ok("designed") => &[true],
        Ok("both") => &[false, true],
        _ => &[false],
    };
    let wanted = |i: &usize| only.as_ref().is_none_or(|o| o.contains(i));
    let base = env("COMPOUND_SEED_BASE", 0);
    let mut scores = Vec::new();
    let mut errors = Vec::new();
    for &designed in modes {
        let outcomes: Vec<Outcome> = std::thread::scope(|s| {
            let hs: Vec<_> = (0..2)
                .map(|t| {
                    s.spawn(move || {
                        (0..cases)
                            .filter(|i| i % 2 == t && wanted(i))
                            .map(|i| run_case(base, i, designed))
                            .collect::<Vec<_>>()
                    })
                })
                .collect();
            hs.into_iter()
                .flat_map(|h| h.join().expect("case thread"))
                .collect()
        });
        let label = if designed { "designed" } else { "drawn" };
        scores.push((label, score(&outcomes, label)));
        errors.push(keyed(&outcomes));
    }
    if only.is_some() {
        return;
    }
    for (label, s) in &scores {
        assert!(s.recall >= 0.9, "{label}: mean recall {}", s.recall);
        assert!(
            s.precision >= 0.9,
            "{label}: mean precision {}",
            s.precision
        );
        assert_eq!(
            s.controls_ok, s.controls,
            "{label}: a control named an effect"
        );
        assert!(
            s.shrink >= 0.9,
            "{label}: median held-out shrink {}",
            s.shrink
        );
    }
    if let [drawn, designed] = &errors[..] {
        // The effects named (right kind, right place) on both motions.
        let mut kinds: BTreeMap<&str, (Vec<f64>, Vec<f64>)> = BTreeMap::new();
        let (mut a, mut b) = (vec![], vec![]);
        for (key, e) in drawn {
            if let Some(f) = designed.get(key) {
                let k = kinds.entry(key.1.as_str()).or_default();
                k.0.push(*e);
                k.1.push(*f);
                a.push(*e);
                b.push(*f);
            }
        }
        let median = |mut v: Vec<f64>| {
            v.sort_by(f64::total_cmp);
            v.get(v.len() / 2).copied().unwrap_or(f64::NAN)
        };
        let better = a.iter().zip(&b).filter(|(x, y)| y < x).count();
        eprintln!(
            "\npaired (the same effect named on both motions, {} effects): median relative error drawn {:.4}, designed {:.4}; smaller on the designed motion for {better}",
            a.len(),
            median(a.clone()),
            median(b.clone())
        );
        for (k, (x, y)) in kinds {
            eprintln!(
                "  {k:>22} drawn {:.4} designed {:.4} ({})",
                median(x.clone()),
                median(y.clone()),
                x.len()
            );
        }
    }
    if let [(_, drawn), (_, designed)] = &scores[..] {
        eprintln!(
            "median relative parameter error: drawn {:.3} ({}), designed {:.3} ({}): x{:.2}",
            drawn.error,
            drawn.errors,
            designed.error,
            designed.errors,
            designed.error / drawn.error
        );
        assert!(designed.error < drawn.error);
    }
}

/// Seed base 15000's case 38: the UR5 on a pick-and-place motion, the
/// whole motion 9.4 ms late and a resistance of the environment at the
/// tool (mu 1.13, alpha 1.53). Alone against the gap the delay leaves, the
/// resistance fits best in a window of the record; the explanation named
/// viscous friction at three joints in its place until the pool kept it
/// on all the time too. Both named, nothing else.
#[test]
fn a_resistance_under_a_motion_delay_is_named() {
    let o = run_case(15000, 38, false);
    assert_eq!(o.robot, "ur5");
    assert!(o.truth.iter().all(|t| t.3), "missed: {:?}", o.truth);
    assert!(o.said.iter().all(|s| s.2), "said: {:?}", o.said);
}
