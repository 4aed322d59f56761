//! The least-squares identification baseline on generated data whose
//! truth is known: friction and rotor inertia on every joint are recovered
//! within their standard deviations, structurally unidentifiable
//! parameters are dropped and named, and the held-out gap closes.

use dynamics_sim2real::effects::Effect;
use dynamics_sim2real::identify::{identify, Estimate, Options};
use dynamics_sim2real::synth::{synthesize, SynthOptions};

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
        truth.push(Effect::CoulombFriction {
            joint: j,
            fc: fc[j],
        });
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
