//! What the nominal model already says: friction a CAD export made up,
//! which the data do not have, is taken away by a correction of the
//! friction terms (never below none at all); an effort scale far off is
//! reported at its limit, in the single-effect ranking as in the
//! explanation.

use dynamics_runtime::ode::Tolerances;
use dynamics_runtime::Robot;
use dynamics_sim2real::diagnose::{diagnose, Options};
use dynamics_sim2real::effects::{Calibrated, Effect, Plant};
use dynamics_sim2real::synth::synthesize;

mod common;
use common::{synth_options, Arm2};

dynamics_macros::robot! {
    /// Arm2 (`common`) with friction parameters at its shoulder.
    pub robot Arm2Friction;
    gravity = [0.0, -9.8, 0.0];
    param fv = 0.0;
    param fc = 0.0;
    link base;
    link upper { mass = 3.0; com = [0.1, 0.0, 0.0]; inertia = [1e-5, 0.02, 0.02]; }
    link lower { mass = 1.5; com = [0.08, 0.0, 0.0]; inertia = [1e-5, 0.008, 0.008]; }
    joint j1 = revolute(base -> upper) { transfer = [rot(q)]; damping = fv; coulomb = fc; }
    joint j2 = revolute(upper -> lower) { transfer = [tu(0.25), rot(q)]; }
}

/// The data come from the arm without friction; the nominal model says
/// j1 has 0.8 N m s/rad of damping. The diagnosis takes it away with a
/// viscous correction of about -0.8 (no more: the total stays >= 0), says
/// so against the nominal value, and the held-out gap closes.
#[test]
fn made_up_nominal_damping_is_taken_away() {
    let truth = Arm2Friction::default();
    let a = synthesize(&truth, &[], &synth_options(6.0, 3)).expect("synthesizes");
    let b = synthesize(&truth, &[], &synth_options(6.0, 103)).expect("synthesizes");
    let mut nominal = Arm2Friction::default();
    nominal.params_mut().fv = 0.8;
    let r = diagnose(&nominal, &a, &b, &Options::default(), &|_, _| {}).expect("diagnoses");
    let fv: f64 = r
        .which
        .effects
        .iter()
        .filter(|e| e.kind.name() == "viscous_friction" && e.joint.as_deref() == Some("j1"))
        .flat_map(|e| e.parameters.iter())
        .map(|p| p.value)
        .sum();
    assert!((fv + 0.8).abs() < 0.08, "{fv} {:#?}", r.which.effects);
    assert!(fv >= -0.8 - 1e-12, "{fv}");
    // Said in words, against the nominal value.
    let said = r
        .which
        .effects
        .iter()
        .filter_map(|e| e.description.as_deref())
        .find(|d| d.starts_with("j1: the nominal model's viscous coefficient 0.800 corrected by"));
    assert!(said.is_some(), "{:#?}", r.which.effects);
    assert!(r.shrink.rms_fraction > 0.5, "{:?}", r.shrink);
    // The short-horizon simulation with the explanation is made (its
    // plant takes the nominal damping away too) and closes its gap.
    assert!(
        r.shrink
            .joints
            .iter()
            .all(|j| j.simulation_after.is_some_and(f64::is_finite)),
        "{:?}",
        r.shrink
    );
    assert!(
        r.shrink.simulation_fraction.is_some_and(|x| x > 0.5),
        "{:?}",
        r.shrink
    );
    assert!(r.warnings.is_empty(), "{:?}", r.warnings);
    // The calibrated model's friction at j1: none left of the 0.8.
    let j1 = &r.which.friction[0];
    assert_eq!(j1.joint, "j1");
    assert!((j1.viscous_nominal - 0.8).abs() < 1e-6, "{j1:?}");
    assert!(j1.viscous < 0.08 && j1.corrected, "{j1:?}");
}

/// Measured efforts at j1 three times the applied ones: the single-effect
/// ranking's effort scale at j1 is held at its limit (1.5), as in the
/// compound explanation.
#[test]
fn an_effort_scale_far_off_is_held_at_its_limit() {
    let arm = Arm2::default();
    let scale = [Effect::EffortScale {
        joint: 0,
        scale: 3.0,
    }];
    let a = synthesize(&arm, &scale, &synth_options(6.0, 5)).expect("synthesizes");
    let b = synthesize(&arm, &scale, &synth_options(6.0, 105)).expect("synthesizes");
    let r = diagnose(&arm, &a, &b, &Options::default(), &|_, _| {}).expect("diagnoses");
    let ranked = r
        .which
        .ranked
        .iter()
        .find(|e| e.kind.name() == "effort_scale" && e.joint.as_deref() == Some("j1"))
        .expect("an effort scale at j1 is ranked");
    let s = ranked.parameters[0].value;
    assert!((s - 1.5).abs() < 1e-9, "{:?}", ranked.parameters);
    for e in r
        .which
        .effects
        .iter()
        .filter(|e| e.kind.name() == "effort_scale")
    {
        assert!(
            e.parameters.iter().all(|p| (0.5..=1.5).contains(&p.value)),
            "{e:?}"
        );
    }
}

/// A plant (and a calibrated model) takes a friction correction that
/// removes the nominal model's own friction, no more: the arm with 0.8 N m
/// s/rad of nominal damping and a correction of -0.8 moves as the arm
/// without damping (the same integrator, to its tolerance); -1.0 is
/// refused, naming the parameter.
#[test]
fn a_plant_takes_away_the_nominal_friction_but_no_more() {
    let mut damped = Arm2Friction::default();
    damped.params_mut().fv = 0.8;
    let away = vec![Effect::ViscousFriction { joint: 0, fv: -0.8 }];
    let plant = Plant::new(damped, away.clone()).expect("within the nominal");
    let bare = Plant::new(Arm2Friction::default(), vec![]).expect("plant");
    let (q0, qd0) = ([0.3, -0.2].into(), [1.5, -0.7].into());
    let (mut a, mut b) = (plant.start(q0, qd0), bare.start(q0, qd0));
    let tol = Tolerances {
        rtol: 1e-10,
        atol: 1e-12,
        ..Default::default()
    };
    let tau = [2.0, -1.0].into();
    a.advance(&plant, 0.5, &tau, tol).expect("advances");
    b.advance(&bare, 0.5, &tau, tol).expect("advances");
    assert!(
        (a.state.q - b.state.q).norm() < 1e-7,
        "{:?} {:?}",
        a.state.q,
        b.state.q
    );
    assert!(Calibrated::new(damped, away).is_ok());
    let too_much = vec![Effect::ViscousFriction { joint: 0, fv: -1.0 }];
    let e = Plant::new(damped, too_much.clone()).unwrap_err();
    assert!(e.to_string().contains("fv"), "{e}");
    let e = Calibrated::new(damped, too_much).unwrap_err();
    assert!(e.to_string().contains("fv"), "{e}");
}
