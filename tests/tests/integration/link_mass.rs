//! A link of the arm heavier than the model, its centre of mass elsewhere:
//! the Panda's fourth link carries 0.5 kg more and 0.03 kg m more first
//! moment along its frame's y axis (the 0.5 kg as if 6 cm off the frame's
//! origin), its rotational inertia about the origin as the model's (a
//! change of the first four inertial parameters alone). The
//! diagnosis names that link's mass and centre of mass and nothing else
//! besides friction, and the change it names gives the true change's
//! effort at states it was not fitted on.
//!
//! Truth, independent of the diagnosis: the change is written into the
//! plant by our generator ([`Effect::InertialParameters`]); the effort of
//! a change `delta` of link `l` at any state is `Y_l(q, qd, qdd) delta`
//! (the emitted regressor, itself checked against Pinocchio in
//! `regressor.rs`).

use dynamics_runtime::Robot;
use dynamics_sim2real::diagnose::{diagnose, Options};
use dynamics_sim2real::effects::{Effect, SIGN_SMOOTHING};
use dynamics_sim2real::synth::synthesize;
use nalgebra::{SMatrix, SVector};
use robots::Panda;

use crate::payload::options;

#[test]
fn a_heavier_middle_link_is_named_by_its_mass_and_centre_of_mass() {
    let robot = Panda::rigid();
    let link = Panda::LINK_NAMES
        .iter()
        .position(|n| *n == "panda_link4")
        .expect("panda_link4");
    // 0.5 kg more, 0.5 kg x 6 cm more first moment along y.
    let delta = [0.5, 0.0, 0.03, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
    let mut effects = vec![Effect::InertialParameters { link, delta }];
    let fc = [0.6, 0.6, 0.5, 0.5, 0.25, 0.25, 0.12];
    for (j, &fc) in fc.iter().enumerate() {
        effects.push(Effect::CoulombFriction {
            joint: j,
            fc,
            vw: SIGN_SMOOTHING,
        });
    }
    let train = synthesize(&robot, &effects, &options(21)).expect("synthesises");
    let holdout = synthesize(&robot, &effects, &options(1_000_022)).expect("synthesises");
    let report =
        diagnose(&robot, &train, &holdout, &Options::default(), &|_, _| {}).expect("diagnoses");
    let others: Vec<String> = report
        .which
        .effects
        .iter()
        .filter(|e| !e.kind.name().ends_with("_friction"))
        .map(|e| format!("{}@{}", e.kind.name(), e.point.as_deref().unwrap_or("")))
        .collect();
    println!("named besides friction: {others:?}");
    assert_eq!(others, ["inertial_parameters@panda_link4"], "{others:?}");
    let entry = report
        .which
        .effects
        .iter()
        .find(|e| e.kind.name() == "inertial_parameters")
        .expect("the link");
    let words = entry.description.as_deref().unwrap_or("");
    println!("{words}");
    assert!(
        words.contains("its mass and centre of mass alone"),
        "{words}"
    );
    let fitted = SVector::<f64, 10>::from_iterator(entry.parameters.iter().map(|p| p.value));
    let truth = SVector::<f64, 10>::from(delta);
    // The named change's effort against the true one's at other states.
    let mut y = vec![SMatrix::<f64, 7, 10>::zeros(); Panda::LINK_NAMES.len()];
    let m = robots::builtin::motion("panda");
    let mut worst: f64 = 0.0;
    for k in 0..50 {
        let t = k as f64 * 0.37;
        let q = SVector::<f64, 7>::from_fn(|j, _| {
            m.home[j] + m.amplitude[j] * (t * (1.0 + 0.3 * j as f64)).sin()
        });
        let qd = SVector::<f64, 7>::from_fn(|j, _| 0.5 * (t * (0.7 + 0.2 * j as f64)).cos());
        let qdd = SVector::<f64, 7>::from_fn(|j, _| (t * (1.3 + 0.1 * j as f64)).sin());
        robot
            .inertial_regressor(&q, &qd, &qdd, &mut y)
            .expect("length");
        let want = y[link] * truth;
        worst = worst.max((y[link] * fitted - want).norm() / want.norm().max(1e-9));
    }
    println!(
        "the named change's effort off the true one's by {worst:.3} (relative, worst of 50 states)"
    );
    assert!(worst < 0.15, "{worst}");
}
