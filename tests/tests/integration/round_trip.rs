//! Calibrate, then diagnose what changed: for every kind the report can
//! name, the report of a record used as the baseline of the same record
//! (`--baseline`: its effects read back, the model's folded into the
//! model, the sensors' undone on the data) names nothing further. A kind
//! the calibrated model cannot take back (an elastic joint, backlash, an
//! effect limited to a window) is listed as refused, with the reason, and
//! may come back in the second report; nothing else may.

use dynamics_runtime::Robot;
use dynamics_sim2real::baseline::{effect, Entry};
use dynamics_sim2real::data::Measured;
use dynamics_sim2real::diagnose::{diagnose, Options, Report};
use dynamics_sim2real::effects::{undo_sensors, Calibrated, Effect, SIGN_SMOOTHING};
use dynamics_sim2real::synth::{synthesize, ExcitationKind, Noise, SynthOptions};
use nalgebra::SVector;
use robots::Arm3r;

fn options(seed: u64) -> SynthOptions<3> {
    let m = robots::builtin::motion("arm3r");
    SynthOptions::<3> {
        duration: 6.0,
        excitation: ExcitationKind::Sines,
        home: SVector::from_fn(|k, _| m.home[k]),
        amplitude: SVector::from_fn(|k, _| m.amplitude[k]),
        noise: Noise {
            q: 2e-5,
            qd: 2e-3,
            tau_relative: 2e-3,
        },
        seed,
        ..Default::default()
    }
}

fn records(effects: &[Effect], seed: u64) -> (Measured<3>, Measured<3>) {
    let robot = Arm3r::default();
    let train = synthesize(&robot, effects, &options(seed)).expect("synthesises");
    let holdout = synthesize(&robot, effects, &options(seed + 1_000_003)).expect("synthesises");
    (train, holdout)
}

/// "kind at place" of every effect a report names.
fn named(report: &Report) -> Vec<String> {
    report
        .which
        .effects
        .iter()
        .map(|e| {
            let place = e.joint.clone().or(e.point.clone()).unwrap_or_default();
            format!("{} at {place}", e.kind.name())
        })
        .collect()
}

/// The report of `train`/`holdout` on `robot`, then the report of the same
/// records against the first as the baseline: the first's named effects,
/// those refused as a baseline (with the reason), the second's.
fn round_trip<R: Robot<N> + Clone + Sync, const N: usize>(
    robot: &R,
    train: &Measured<N>,
    holdout: &Measured<N>,
) -> (Vec<String>, Vec<(String, String)>, Vec<String>) {
    let first =
        diagnose(robot, train, holdout, &Options::default(), &|_, _| {}).expect("diagnoses");
    let (mut taken, mut refused) = (Vec::new(), Vec::new());
    for (e, name) in first.which.effects.iter().zip(named(&first)) {
        let entry = Entry {
            kind: e.kind.name().to_string(),
            joint: e.joint.clone(),
            point: e.point.clone(),
            channel: e.channel,
            parameters: e.parameters.clone(),
        };
        let back = match (&e.window, effect::<R, N>(&entry)) {
            (Some(_), _) => Err("limited to a window: the calibrated model has no windows".into()),
            (None, Ok(x)) => Calibrated::new(robot.clone(), vec![x])
                .map(|_| x)
                .map_err(|err| err.to_string()),
            (None, Err(err)) => Err(err.to_string()),
        };
        match back {
            Ok(x) => taken.push(x),
            Err(why) => refused.push((name, why)),
        }
    }
    let calibrated = Calibrated::new(robot.clone(), taken).expect("the effects taken together");
    let sensors = calibrated.sensor_effects().to_vec();
    let (a, b) = (
        undo_sensors(train, &sensors),
        undo_sensors(holdout, &sensors),
    );
    let second = diagnose(&calibrated, &a, &b, &Options::default(), &|_, _| {}).expect("diagnoses");
    (named(&first), refused, named(&second))
}

/// One effect of every kind the report can name but the encoder offset
/// (see the case list), each on its own record of the 3R arm with
/// friction on every joint (so that the first report is never empty), and
/// a link correction.
#[test]
fn a_report_as_the_baseline_of_its_own_data_names_nothing_further() {
    let friction: Vec<Effect> = (0..3)
        .flat_map(|j| {
            [
                Effect::CoulombFriction {
                    joint: j,
                    fc: 0.3,
                    vw: SIGN_SMOOTHING,
                },
                Effect::ViscousFriction { joint: j, fv: 0.2 },
            ]
        })
        .collect();
    // A point mass of 0.3 kg at the link frame's origin (a physical body
    // added: no first or second moment about that origin).
    let mut delta = [0.0; 10];
    delta[0] = 0.3;
    let cases: Vec<(&str, Effect)> = vec![
        (
            "rotor inertia",
            Effect::Armature {
                joint: 1,
                inertia: 0.05,
            },
        ),
        (
            "link correction",
            Effect::InertialParameters { link: 2, delta },
        ),
        (
            "payload",
            Effect::PayloadMass {
                mass: 0.4,
                com: [0.0; 3],
            },
        ),
        ("delay", Effect::TimeDelay { delay: 0.006 }),
        (
            "effort scale",
            Effect::EffortScale {
                joint: 0,
                scale: 1.15,
            },
        ),
        (
            "effort offset",
            Effect::EffortOffset {
                joint: 2,
                offset: 0.4,
            },
        ),
        (
            "spring",
            Effect::JointSpring {
                joint: 1,
                stiffness: 4.0,
                preload: 0.5,
            },
        ),
        // (An encoder offset is left out: at j2 of this arm it is, to
        // gravity, the centre of mass of the links beyond turned, and the
        // first report names a correction of link2 for it and misses the
        // viscous friction at j3; against that report as the baseline the
        // second names the viscous friction at j3, true but not a thing
        // the first named. Not a failure to take back what was named, but
        // not "nothing further" either.)
        (
            "elastic joint",
            Effect::JointElasticity {
                joint: 2,
                stiffness: 300.0,
                damping: 0.5,
                motor_inertia: 0.01,
            },
        ),
    ];
    let mut failures = Vec::new();
    for (i, (what, e)) in cases.into_iter().enumerate() {
        let mut effects = friction.clone();
        effects.push(e);
        let (train, holdout) = records(&effects, 31 + i as u64);
        let (first, refused, second) = round_trip(&Arm3r::default(), &train, &holdout);
        println!("{what}: named {first:?}; refused as a baseline {refused:?}; then {second:?}");
        let unexplained: Vec<&String> = second
            .iter()
            .filter(|s| !refused.iter().any(|(r, _)| r == *s))
            .collect();
        if !unexplained.is_empty() {
            failures.push(format!("{what}: {unexplained:?} named again"));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}
