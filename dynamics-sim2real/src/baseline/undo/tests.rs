//! The undo against independent truth: records generated with a known
//! motor side or a windowed payload (the generator integrates the true
//! two-mass joint and plant, not the diagnosis's simulation), undone with
//! the true parameters; what is left of the measured effort against the
//! rigid model's inverse dynamics along the measured motion is then at the
//! noise floor.

use super::*;
use crate::synth::{synthesize, Noise, SynthOptions};

use crate::test_robots::Arm2;

fn options(windows: Vec<Option<Window>>) -> SynthOptions<2> {
    SynthOptions {
        duration: 6.0,
        seed: 5,
        noise: Noise {
            q: 2e-5,
            qd: 2e-3,
            tau_relative: 2e-3,
        },
        windows,
        ..Default::default()
    }
}

/// RMS over the fit rows of joint `j`'s smoothed residual (measured effort
/// less `robot`'s inverse dynamics along the measured motion), over its
/// noise floor.
fn gap<R: Robot<2> + Clone + Send + Sync + 'static>(
    robot: &R,
    m: &Measured<2>,
    j: usize,
    inside: impl Fn(f64) -> bool,
) -> f64 {
    let p = Prepared::new(robot, m);
    let rows: Vec<usize> = p
        .rows
        .iter()
        .copied()
        .filter(|&k| inside(p.sig.t[k]))
        .collect();
    let s: f64 = rows.iter().map(|&k| p.sig.residual[k][j].powi(2)).sum();
    (s / rows.len() as f64).sqrt() / p.sig.floor[j]
}

/// A motor side at the elbow of `Arm2`, resonance `hz`, motor inertia
/// `ratio` of the joint's (the generator draws a fifth; the diagnosis
/// searches 5 to 40 %).
fn motor_side(backlash: bool, hz: f64, ratio: f64) -> Effect {
    let r = Arm2::default();
    let inertia = r.mass_matrix(&SVector::zeros())[(1, 1)];
    let jm = ratio * inertia;
    let w = 2.0 * std::f64::consts::PI * hz;
    let k = w * w / (1.0 / jm + 1.0 / inertia);
    if backlash {
        Effect::Backlash {
            joint: 1,
            half_width: 8.0 / 60.0 * std::f64::consts::PI / 180.0,
            motor_inertia: jm,
            contact_stiffness: k,
            contact_damping: 2.0 * 0.1 * (k * jm).sqrt(),
        }
    } else {
        Effect::JointElasticity {
            joint: 1,
            stiffness: k,
            damping: 2.0 * 0.05 * (k * jm).sqrt(),
            motor_inertia: jm,
        }
    }
}

/// With the true motor side undone, the elbow's effort is what the rigid
/// model asks along the measured motion, to within noise; before, it was
/// far from it. A sign or convention slip in the undo (the motor's
/// effort, or the force on the other side) leaves a gap at least as large.
#[test]
fn a_known_motor_side_undone_leaves_the_rigid_links_effort() {
    // (At a motor inertia of a fifth of the joint's, these data show a
    // 10 Hz elasticity at 2.9 x noise and a 40 Hz backlash at 2.7 x: too
    // close to the floor to tell a right undo from a wrong one.)
    for (backlash, hz, ratio) in [(false, 10.0, 0.4), (true, 60.0, 0.4)] {
        let e = motor_side(backlash, hz, ratio);
        let m = synthesize(&Arm2::default(), &[e], &options(Vec::new())).expect("synthesises");
        let before = gap(&Arm2::default(), &m, 1, |_| true);
        let r = Calibrated::new(Arm2::default(), vec![e]).expect("taken");
        assert!(r.effects().is_empty() && r.motor_effects() == [e]);
        let fixed = undo(&r, &m).expect("undone");
        assert_eq!(fixed.len(), m.len());
        let after = gap(&r, &fixed, 1, |_| true);
        // The shoulder's effort is not touched.
        assert!(fixed.tau.iter().zip(&m.tau).all(|(a, b)| a[0] == b[0]));
        println!("{e:?}: elbow gap over noise {before:.2} -> {after:.2}");
        assert!(before > 4.0, "{e:?}: the effect shows ({before})");
        assert!(
            after < 1.6 && after < 0.3 * before,
            "{e:?}: {before} -> {after}"
        );
    }
}

/// A payload on the tip between 2 and 4 s, undone inside that window:
/// the gap is at the noise floor inside and outside it.
#[test]
fn a_windowed_payload_undone_inside_its_window_leaves_the_rigid_effort() {
    let held = Window {
        start: 2.0,
        end: 4.0,
    };
    let payload = Effect::PayloadMass {
        mass: 0.5,
        com: [0.0; 3],
    };
    let m =
        synthesize(&Arm2::default(), &[payload], &options(vec![Some(held)])).expect("synthesises");
    // Rows away from the window's edges (the smoothing blurs a step).
    let inside = |t: f64| (2.1..3.9).contains(&t);
    let outside = |t: f64| !(1.9..4.1).contains(&t);
    let before = gap(&Arm2::default(), &m, 0, inside);
    let r = Calibrated::timed(Arm2::default(), vec![(payload, Some(held))]).expect("taken");
    let fixed = undo(&r, &m).expect("undone");
    let (after_in, after_out) = (gap(&r, &fixed, 0, inside), gap(&r, &fixed, 0, outside));
    println!("windowed payload: shoulder gap over noise inside {before:.2} -> {after_in:.2}, outside {after_out:.2}");
    assert!(before > 5.0, "{before}");
    assert!(after_in < 2.0 && after_out < 2.0, "{after_in} {after_out}");
    // Outside the window, the record is untouched.
    for k in (0..m.len()).filter(|&k| !held.contains(m.t[k])) {
        assert_eq!(fixed.tau[k], m.tau[k]);
    }
}

/// An effort scale on all the time and an effort offset between 2 and 4 s
/// at the elbow (the generator's sensor reads `scale` x applied +
/// `offset`): undone, the elbow's effort is what the rigid model asks, to
/// within noise, inside the window and outside. Taking the offset out in
/// measured units after the scale is divided out would leave
/// `offset (1 - 1 / scale)` inside the window.
#[test]
fn a_windowed_effort_offset_at_a_scaled_joint_is_undone_in_applied_units() {
    let held = Window {
        start: 2.0,
        end: 4.0,
    };
    let scale = Effect::EffortScale {
        joint: 1,
        scale: 1.4,
    };
    let offset = Effect::EffortOffset {
        joint: 1,
        offset: 1.5,
    };
    let m = synthesize(
        &Arm2::default(),
        &[scale, offset],
        &options(vec![None, Some(held)]),
    )
    .expect("synthesises");
    let inside = |t: f64| (2.1..3.9).contains(&t);
    let outside = |t: f64| !(1.9..4.1).contains(&t);
    let before = gap(&Arm2::default(), &m, 1, inside);
    let r = Calibrated::timed(Arm2::default(), vec![(scale, None), (offset, Some(held))])
        .expect("taken");
    let fixed = undo(&r, &m).expect("undone");
    let (after_in, after_out) = (gap(&r, &fixed, 1, inside), gap(&r, &fixed, 1, outside));
    println!("scaled elbow with a windowed offset: gap over noise inside {before:.2} -> {after_in:.2}, outside {after_out:.2}");
    assert!(before > 5.0, "{before}");
    assert!(after_in < 1.6 && after_out < 1.6, "{after_in} {after_out}");
}
