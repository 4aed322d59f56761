//! The least-squares identification baseline on generated data whose
//! truth is known: friction and rotor inertia on every joint are recovered
//! within their standard deviations, structurally unidentifiable
//! parameters are dropped and named, and the held-out gap closes.

use dynamics_sim2real::effects::Effect;
use dynamics_sim2real::identify::{identify, Estimate, Options};
use dynamics_sim2real::synth::{synthesize, SynthOptions};
use nalgebra::SVector;

fn within(e: Estimate, truth: f64, what: &str) {
    let std = e.std.unwrap_or_else(|| panic!("{what}: not identified"));
    assert!(
        (e.value - truth).abs() <= 4.0 * std,
        "{what}: {} +- {std:.2e}, truth {truth}",
        e.value
    );
    // The test can fail: the deviation is small against the value.
    assert!(std < 0.1 * truth, "{what}: std {std:.2e} for {truth}");
}

#[test]
fn friction_and_rotor_inertia_of_every_joint_are_recovered() {
    let robot = robots::Arm3r::default();
    let (fc, fv, ia) = ([0.6, 0.3, 0.08], [0.5, 0.2, 0.05], [0.03, 0.01, 0.004]);
    let mut truth = Vec::new();
    for j in 0..3 {
        truth.push(Effect::coulomb(j, fc[j]));
        truth.push(Effect::ViscousFriction {
            joint: j,
            fv: fv[j],
        });
        truth.push(Effect::Armature {
            joint: j,
            inertia: ia[j],
        });
    }
    let opts = |seed| SynthOptions::<3> {
        seed,
        ..Default::default()
    };
    let train = synthesize(&robot, &truth, &opts(11)).expect("synthesizes");
    let holdout = synthesize(&robot, &truth, &opts(12)).expect("synthesizes");
    let id = identify(&robot, &train, &holdout, &Options::default()).expect("fits");
    for (j, t) in id.joints.iter().enumerate() {
        within(t.coulomb, fc[j], &format!("coulomb {}", t.joint));
        within(t.viscous, fv[j], &format!("viscous {}", t.joint));
        assert!(
            t.holdout_after < 0.2 * t.holdout_before,
            "{}: held-out {} -> {}",
            t.joint,
            t.holdout_before,
            t.holdout_after
        );
    }
    // Joint 1's rotor and link 1's I_zz are one column (a planar arm
    // turning about z): the joint's is kept, the link's dropped as equal
    // to it. Joints 2 and 3 have their own.
    let dropped = id
        .dropped
        .iter()
        .find(|d| d.column == "link1 I_zz")
        .expect("link1 I_zz dropped");
    assert_eq!(dropped.combination.len(), 1, "{dropped:?}");
    assert_eq!(dropped.combination[0].0, "armature j1");
    assert!((dropped.combination[0].1 - 1.0).abs() < 1e-9);
    within(id.joints[1].armature, ia[1], "armature j2");
    within(id.joints[2].armature, ia[2], "armature j3");
    // A planar arm excites none of the out-of-plane parameters.
    assert!(id.rank < id.columns);
    assert!(id.shrink > 0.8, "shrink {}", id.shrink);
    println!(
        "arm3r: rank {} of {}, held-out shrink {:.3}",
        id.rank, id.columns, id.shrink
    );
}

#[test]
fn the_nominal_robot_needs_no_correction() {
    let robot = robots::Arm3r::default();
    let opts = |seed| SynthOptions::<3> {
        duration: 4.0,
        seed,
        ..Default::default()
    };
    let train = synthesize(&robot, &[], &opts(21)).expect("synthesizes");
    let holdout = synthesize(&robot, &[], &opts(22)).expect("synthesizes");
    let id = identify(&robot, &train, &holdout, &Options::default()).expect("fits");
    // Every fitted joint term is zero within a few standard deviations.
    for t in &id.joints {
        for e in [t.coulomb, t.viscous, t.offset, t.armature] {
            if let Some(std) = e.std {
                assert!(e.value.abs() < 5.0 * std, "{}: {e:?}", t.joint);
            }
        }
    }
    // Nothing to explain: the held-out residual (noise) barely changes.
    assert!(id.shrink.abs() < 0.1, "shrink {}", id.shrink);
}

#[test]
fn too_short_data_is_an_error_not_a_fit() {
    let robot = robots::Arm3r::default();
    let opts = SynthOptions::<3> {
        duration: 0.1,
        ..Default::default()
    };
    let data = synthesize(&robot, &[], &opts).expect("synthesizes");
    let err = identify(&robot, &data, &data, &Options::default()).unwrap_err();
    assert!(err.to_string().contains("record longer"), "{err}");
}

/// A point mass `m` at `at` added to a link, as a parameter change.
fn point_mass(m: f64, at: [f64; 3]) -> [f64; 10] {
    let [x, y, z] = at;
    let r2 = x * x + y * y + z * z;
    [
        m,
        m * x,
        m * y,
        m * z,
        m * (r2 - x * x),
        -m * x * y,
        m * (r2 - y * y),
        -m * x * z,
        -m * y * z,
        m * (r2 - z * z),
    ]
}

#[test]
fn a_changed_link_in_the_plant_is_the_robot_with_that_link_changed() {
    use super::regressor::{parameters, Parametric};
    use dynamics_sim2real::effects::Plant;
    use nalgebra::{SVector, Vector3};
    let nominal = Parametric::default();
    let mut real = nominal;
    real.params.m += 0.4;
    real.params.cx -= 0.03;
    real.params.ixy += 0.002;
    real.params.load += 0.1;
    let l2 = 1;
    let delta: [f64; 10] = (parameters(&real)[l2] - parameters(&nominal)[l2]).into();
    let plant = Plant::new(
        nominal,
        vec![Effect::InertialParameters { link: l2, delta }],
    )
    .expect("plant");
    let truth = Plant::new(real, vec![]).expect("plant");
    for k in 0..10 {
        let t = k as f64;
        let q = Vector3::new((0.7 * t).sin(), (1.3 * t).cos(), 0.1 * (0.4 * t).sin());
        let qd = Vector3::new((0.3 * t).cos(), -(0.9 * t).sin(), 0.5);
        let (a, f) = plant.mass_and_forces(&q, &qd);
        let (at, ft) = truth.mass_and_forces(&q, &qd);
        assert!((a - at).abs().max() < 1e-12, "{a} vs {at}");
        assert!(
            (f - ft).abs().max() < 1e-10 * (1.0 + ft.abs().max()),
            "{f} vs {ft}"
        );
        let x = dynamics_sim2real::effects::PlantState {
            q,
            qd,
            qm: SVector::zeros(),
            qmd: SVector::zeros(),
        };
        let (e, et) = (plant.energy(&x, &[0; 3]), truth.energy(&x, &[0; 3]));
        assert!((e - et).abs() < 1e-10 * (1.0 + et.abs()), "{e} vs {et}");
    }
    // Out of range and unphysical changes are refused.
    let bad = Effect::InertialParameters { link: 9, delta };
    assert!(Plant::new(nominal, vec![bad]).is_err());
    let mut lighter = [0.0; 10];
    lighter[0] = -10.0;
    let err = Plant::new(
        nominal,
        vec![Effect::InertialParameters {
            link: l2,
            delta: lighter,
        }],
    )
    .unwrap_err();
    assert!(err.to_string().contains("mass"), "{err}");
}

#[test]
fn a_heavier_link_is_identified_through_its_efforts() {
    use dynamics_runtime::Robot;
    use nalgebra::SMatrix;
    let robot = robots::Arm3r::default();
    // Link 3 gains 0.25 kg at 8 cm along it; friction on every joint.
    let delta = point_mass(0.25, [0.08, 0.0, 0.0]);
    let mut truth = vec![Effect::InertialParameters { link: 2, delta }];
    for j in 0..3 {
        truth.push(Effect::coulomb(j, 0.3));
        truth.push(Effect::ViscousFriction { joint: j, fv: 0.2 });
    }
    let opts = |seed| SynthOptions::<3> {
        seed,
        ..Default::default()
    };
    let train = synthesize(&robot, &truth, &opts(31)).expect("synthesizes");
    let holdout = synthesize(&robot, &truth, &opts(32)).expect("synthesizes");
    let id = identify(&robot, &train, &holdout, &Options::default()).expect("fits");
    assert!(id.shrink > 0.9, "shrink {}", id.shrink);
    for t in &id.joints {
        within(t.coulomb, 0.3, &format!("coulomb {}", t.joint));
    }
    // The link corrections (base parameters: not unique one by one) give
    // the true extra effort at other states.
    let fitted: Vec<SVector<f64, 10>> = id
        .links
        .iter()
        .map(|l| SVector::from(l.delta.map(|e| e.value)))
        .collect();
    let armature = SVector::<f64, 3>::from_fn(|j, _| id.joints[j].armature.value);
    let mut y = vec![SMatrix::<f64, 3, 10>::zeros(); 4];
    let mut worst: f64 = 0.0;
    for k in 0..50 {
        let t = k as f64 * 0.37;
        let q = SVector::<f64, 3>::new(t.sin(), (1.7 * t).cos(), (0.3 * t).sin());
        let qd = SVector::<f64, 3>::new((0.5 * t).cos(), (1.1 * t).sin(), 0.4);
        let qdd = SVector::<f64, 3>::new((2.1 * t).sin(), -(0.8 * t).cos(), 1.0);
        robot
            .inertial_regressor(&q, &qd, &qdd, &mut y)
            .expect("length");
        let want = y[2] * SVector::from(delta);
        let got: SVector<f64, 3> = y
            .iter()
            .zip(&fitted)
            .map(|(y, d)| y * d)
            .sum::<SVector<f64, 3>>()
            + armature.component_mul(&qdd);
        worst = worst.max((got - want).norm() / want.norm().max(1e-9));
    }
    assert!(
        worst < 0.1,
        "fitted link efforts off by {worst:.3} (relative)"
    );
    println!(
        "heavier link 3: held-out shrink {:.3}, worst relative effort error {worst:.3}",
        id.shrink
    );
    let words =
        dynamics_sim2real::inertial::describe(id.links[2].link, &id.links[2].nominal, &fitted[2]);
    println!("{words}");
}

#[test]
fn panda_friction_on_every_joint_is_recovered_and_the_gap_closes() {
    let robot = robots::Panda::rigid();
    let motion = robots::builtin::motion("panda");
    let fc = [0.8, 0.8, 0.6, 0.6, 0.3, 0.3, 0.2];
    let fv = [0.6, 0.6, 0.4, 0.4, 0.2, 0.2, 0.1];
    let mut truth = Vec::new();
    for j in 0..7 {
        truth.push(Effect::coulomb(j, fc[j]));
        truth.push(Effect::ViscousFriction {
            joint: j,
            fv: fv[j],
        });
    }
    let opts = |seed| SynthOptions::<7> {
        seed,
        home: SVector::from_column_slice(&motion.home),
        amplitude: SVector::from_column_slice(&motion.amplitude),
        ..Default::default()
    };
    let train = synthesize(&robot, &truth, &opts(41)).expect("synthesizes");
    let holdout = synthesize(&robot, &truth, &opts(42)).expect("synthesizes");
    let id = identify(&robot, &train, &holdout, &Options::default()).expect("fits");
    for (j, t) in id.joints.iter().enumerate() {
        within(t.coulomb, fc[j], &format!("coulomb {}", t.joint));
    }
    assert!(id.shrink > 0.8, "shrink {}", id.shrink);
    println!(
        "panda: rank {} of {}, {} training rows, held-out shrink {:.3}",
        id.rank, id.columns, id.train_rows, id.shrink
    );
    for t in &id.joints {
        println!(
            "  {}: coulomb {:.3} +- {:.3}, viscous {:.3} +- {:.3}, held-out {:.3} -> {:.3}",
            t.joint,
            t.coulomb.value,
            t.coulomb.std.unwrap_or(f64::NAN),
            t.viscous.value,
            t.viscous.std.unwrap_or(f64::NAN),
            t.holdout_before,
            t.holdout_after
        );
    }
}
