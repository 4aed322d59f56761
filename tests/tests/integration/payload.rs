//! A payload relative to the model: the Panda logged without the hand its
//! model carries (as Gaz et al. logged theirs) is diagnosed against the
//! model with the hand. The tool must name the hand's mass as missing at
//! the flange (a negative payload), not scatter it over the links; and
//! the same arm with nothing changed names nothing.
//!
//! Truth, independent of the diagnosis: the hand and its fingers are
//! 0.73 + 2 x 0.015 = 0.76 kg in `robots/data/urdf/panda.urdf`, and the
//! model without them (`panda-arm`, `robots/data/urdf/panda_arm.urdf`)
//! differs from it by exactly those bodies.

use dynamics_runtime::Robot;
use dynamics_sim2real::data::Measured;
use dynamics_sim2real::diagnose::{diagnose, Options, Report};
use dynamics_sim2real::effects::{Effect, SIGN_SMOOTHING};
use dynamics_sim2real::synth::{synthesize, ExcitationKind, Noise, SynthOptions};
use nalgebra::SVector;
use robots::{Panda, PandaArm};

/// The hand and fingers of the Panda's URDF, kg.
const HAND: f64 = 0.76;

/// Coulomb friction and viscous friction on every joint (N m, N m s/rad),
/// a few per cent of each joint's effort on the motion below.
fn friction() -> Vec<Effect> {
    let fc = [0.6, 0.6, 0.5, 0.5, 0.25, 0.25, 0.12];
    let fv = [0.4, 0.4, 0.3, 0.3, 0.15, 0.15, 0.08];
    (0..7)
        .flat_map(|j| {
            [
                Effect::CoulombFriction {
                    joint: j,
                    fc: fc[j],
                    vw: SIGN_SMOOTHING,
                },
                Effect::ViscousFriction {
                    joint: j,
                    fv: fv[j],
                },
            ]
        })
        .collect()
}

/// The Panda's builtin motion as sines for 6 s, light sensor noise.
pub(crate) fn options(seed: u64) -> SynthOptions<7> {
    let m = robots::builtin::motion("panda");
    SynthOptions::<7> {
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

/// Training and held-out records of `robot` with `effects`.
fn records<R: Robot<7> + Clone>(robot: &R, effects: &[Effect]) -> (Measured<7>, Measured<7>) {
    let train = synthesize(robot, effects, &options(11)).expect("synthesises");
    let holdout = synthesize(robot, effects, &options(1_000_014)).expect("synthesises");
    (train, holdout)
}

fn diagnosed(train: &Measured<7>, holdout: &Measured<7>) -> Report {
    diagnose(
        &Panda::rigid(),
        train,
        holdout,
        &Options::default(),
        &|_, _| {},
    )
    .expect("diagnoses")
}

/// The kinds named besides friction, and the payload's mass if named.
fn named(report: &Report) -> (Vec<String>, Option<f64>) {
    let others = report
        .which
        .effects
        .iter()
        .map(|e| e.kind.name().to_string())
        .filter(|k| !k.ends_with("_friction"))
        .collect();
    let mass = report
        .which
        .effects
        .iter()
        .find(|e| e.kind.name() == "payload_mass")
        .and_then(|e| e.parameters.iter().find(|p| p.name == "mass"))
        .map(|p| p.value);
    (others, mass)
}

/// The hand and fingers' centre of mass in the tool frame
/// (panda_hand_tcp, 0.1034 m beyond the hand's frame along z), m.
fn hand_com_z() -> f64 {
    (0.73 * 0.03 + 0.03 * 0.0584) / HAND - 0.1034
}

/// The model's own hand taken away as a point mass at its centre of mass
/// (what leaves the body carrying the tip a physical body: the arm's last
/// link and the hand's spread about its centre): the diagnosis names a
/// negative payload of that mass (within 10 %), in words that say it is
/// absent, and nothing else besides friction.
#[test]
fn a_hand_the_robot_lacks_is_named_as_a_negative_payload() {
    let mut effects = friction();
    effects.push(Effect::PayloadMass {
        mass: -HAND,
        com: [0.0, 0.0, hand_com_z()],
    });
    let (train, holdout) = records(&Panda::rigid(), &effects);
    let report = diagnosed(&train, &holdout);
    let (others, mass) = named(&report);
    println!("named besides friction {others:?}, payload {mass:?}");
    assert_eq!(others, ["payload_mass"], "{others:?}");
    let mass = mass.expect("a payload mass");
    assert!(
        (mass + HAND).abs() <= 0.1 * HAND,
        "payload {mass} kg, the hand {HAND} kg"
    );
    let words = report
        .which
        .effects
        .iter()
        .find_map(|e| e.description.clone())
        .unwrap_or_default();
    assert!(words.contains("is not on the robot"), "{words}");
}

/// The arm logged without its hand (the `panda-arm` model: the hand's
/// bodies, not a point mass) against the model with the hand.
#[test]
fn the_arm_without_its_hand_against_the_model_with_it() {
    let (train, holdout) = records(&PandaArm::rigid(), &friction());
    let report = diagnosed(&train, &holdout);
    let (others, mass) = named(&report);
    println!("named besides friction {others:?}, payload {mass:?}");
    assert_eq!(others, ["payload_mass"], "{others:?}");
    let mass = mass.expect("a payload mass");
    assert!(
        (mass + HAND).abs() <= 0.1 * HAND,
        "payload {mass} kg, the hand {HAND} kg"
    );
    // Where the data place its centre: the hand and fingers' centre in
    // the tool frame.
    let com_z = hand_com_z();
    let payload = report
        .which
        .effects
        .iter()
        .find(|e| e.kind.name() == "payload_mass");
    let z = payload.and_then(|e| e.parameters.iter().find(|p| p.name == "com_z"));
    println!("com_z {z:?} (the hand's {com_z:.4} m)");
    if let Some(z) = z.filter(|z| z.note.is_none()) {
        assert!(
            (z.value - com_z).abs() < 0.02,
            "com_z {} m, the hand's {com_z:.4} m",
            z.value
        );
    }
}

/// The control: the model's own arm, with friction only, names nothing
/// but friction; with nothing at all, nothing.
#[test]
fn the_model_itself_names_no_payload() {
    let (train, holdout) = records(&Panda::rigid(), &friction());
    let (others, _) = named(&diagnosed(&train, &holdout));
    assert!(others.is_empty(), "{others:?}");
    let (train, holdout) = records(&Panda::rigid(), &[]);
    let report = diagnosed(&train, &holdout);
    assert!(report.which.effects.is_empty(), "{:?}", named(&report));
}

/// The payload's columns against the exact point mass, independently
/// computed from the tip's Jacobian and bias acceleration at the centre
/// (`Tip::position_jacobian_at`, `Tip::bias_acceleration_at`): with the
/// second moments taken at the centre, what is left is the record's
/// smoothing of the tip's motion (the basis smooths it once more than the
/// joint signals): under half of what leaving them at the tip's origin
/// misses (a third on this record).
#[test]
fn a_payloads_columns_at_its_centre_are_the_point_mass() {
    use dynamics_sim2real::diagnose::{Candidate, Prepared};
    use dynamics_sim2real::effects::Tip;
    use nalgebra::Vector3;
    let robot = Panda::rigid();
    let (train, _) = records(&robot, &[]);
    let p = Prepared::new(&robot, &train);
    let (m, com) = (-HAND, [0.004, -0.003, hand_com_z()]);
    let c = Vector3::from(com);
    let tip = Tip::of::<Panda, 7>();
    let g = Vector3::from(<Panda as Robot<7>>::GRAVITY);
    let miss = |candidate: Candidate| -> f64 {
        let theta = [m, m * com[0], m * com[1], m * com[2]];
        let (mut err, mut size) = (0.0, 0.0);
        for &k in p.rows.iter().step_by(10) {
            let (q, qd, qdd) = (p.sig.q(k), p.sig.qd(k), p.sig.qdd(k));
            let (_, jac) = tip.position_jacobian_at(&robot, &q, &c);
            let acc = jac * qdd + tip.bias_acceleration_at(&robot, &q, &qd, &c);
            let exact = jac.transpose() * ((acc - g) * m);
            let cols = candidate.columns(&p.sig, &p.basis, k);
            let fitted: SVector<f64, 7> = (0..4).map(|i| cols[i] * theta[i]).sum();
            err += (fitted - exact).norm_squared();
            size += exact.norm_squared();
        }
        (err / size).sqrt()
    };
    let (at_origin, at_centre) = (
        miss(Candidate::PayloadCom([0.0; 3])),
        miss(Candidate::PayloadCom(com)),
    );
    println!("relative miss: second moments at the origin {at_origin:.2e}, at the centre {at_centre:.2e}");
    assert!(
        at_centre < 0.5 * at_origin,
        "{at_centre:e} vs {at_origin:e}"
    );
}
