//! Exciting motions (`dynamics_sim2real::excite`, issue 28): on every
//! built-in robot the designed motion keeps the position, velocity and
//! effort limits (margin included) at every sample of a 1 kHz output and
//! starts and ends at rest at its start pose; on panda, ur5 and arm3r its
//! base regressor (friction, rotor inertia and offset columns included) is
//! at least twice as well conditioned as today's default excitation
//! (`synth`'s sines) over the same duration and limits.

use dynamics_cli::excite::{default_states, limits};
use dynamics_runtime::Robot;
use dynamics_sim2real::excite::{check, design, Figures, Options};
use robots::builtin::motion;
use robots::registry::{AnyRobot, ROBOTS};

/// Designs `duration` s for the robot `name` with `evaluations`; returns
/// the designed and the default sines' condition numbers after checking
/// the limits and the rest at both ends.
fn designed<R: Robot<N> + Sync, const N: usize>(
    robot: &R,
    name: &str,
    duration: f64,
    evaluations: usize,
) -> (f64, f64) {
    let m = motion(name);
    let lim = limits::<N>(
        AnyRobot::by_name(name).expect("robot").limits().as_ref(),
        &m,
    );
    let mut o = Options::new(duration);
    o.evaluations = evaluations;
    let d = design(robot, &lim, &o).unwrap_or_else(|e| panic!("{name}: {e}"));
    // The margin is in the design's limits: compare with them and with the
    // raw limits tightened independently here.
    let tight = lim.with_margin(o.margin);
    assert_eq!(d.limits, tight, "{name}");
    let samples = d.samples(1000.0);
    let states: Vec<_> = samples.iter().map(|s| s.1).collect();
    let c = check(robot, &states, &tight);
    assert!(c.all(), "{name}: {c:?}");
    for j in 0..N {
        assert!(c.min_q[j] >= tight.lower[j] && c.max_q[j] <= tight.upper[j]);
        assert!(c.peak_velocity[j] <= tight.velocity[j]);
        assert!(c.peak_effort[j] <= tight.effort[j]);
    }
    for s in [&samples[0], &samples[samples.len() - 1]] {
        let scale = 1.0 + d.motion.q0.amax();
        assert!(
            (s.1.q - d.motion.q0).amax() < 1e-9 * scale,
            "{name} at {}",
            s.0
        );
        assert!(
            s.1.qd.amax() < 1e-9 && s.1.qdd.amax() < 1e-8,
            "{name} at {}",
            s.0
        );
    }
    assert!((samples[samples.len() - 1].0 - duration).abs() < 1e-12);
    let rate = 200.0 / d.motion.period;
    let default = Figures::of(
        &d.columns
            .stack(robot, &default_states::<N>(&m, duration, rate, 1))
            .expect("stack"),
    )
    .expect("figures");
    (d.figures.condition, default.condition)
}

#[test]
fn designed_motions_keep_every_limit_and_rest_at_both_ends() {
    for (name, _) in ROBOTS {
        let robot = AnyRobot::by_name(name).expect("robot");
        let (c, _) = robots::each_robot!(&robot, r => designed(r, name, 8.0, 40));
        assert!(c.is_finite(), "{name}: {c}");
    }
}

#[test]
fn designed_motions_halve_the_condition_number_of_the_default_sines() {
    for name in ["arm3r", "ur5", "panda"] {
        let robot = AnyRobot::by_name(name).expect("robot");
        let (designed, default) = robots::each_robot!(&robot, r => designed(r, name, 20.0, 2000));
        println!(
            "{name}: 20 s, condition number designed {designed:.1}, default sines {default:.1}"
        );
        assert!(designed <= 0.5 * default, "{name}: {designed} vs {default}");
    }
}
