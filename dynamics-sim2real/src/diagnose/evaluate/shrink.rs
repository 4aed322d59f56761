//! How far the gap shrinks on the held-out data once the explanation's
//! effects are added: the torque residual above noise and the
//! short-horizon simulation error, per joint and overall.

use nalgebra::SVector;

use super::analysis::Prepared;
use super::report::{JointShrink, Shrink, ShrinkStep};
use super::signals::robust_std;
use super::{horizon, rms};
use crate::data::Measured;
use crate::effects::Effect;
use crate::Warning;
use dynamics_runtime::Robot;

/// The shrink on `holdout` (prepared as `h`) of the explanation: `after`,
/// the held-out torque residual it leaves at every sample (`None`: nothing
/// added, no shrink), `effects` its effects, `rms_fraction` and `steps`
/// the plain figure and the gap after each added effect (`explain.rs`).
/// A simulation that cannot be made leaves its figures out and says why
/// in `warnings`.
#[allow(clippy::too_many_arguments)]
pub fn shrink<R: Robot<N> + Clone + Sync, const N: usize>(
    robot: &R,
    holdout: &Measured<N>,
    h: &Prepared<N>,
    after: Option<Vec<SVector<f64, N>>>,
    effects: &[Effect],
    rms_fraction: f64,
    steps: Vec<ShrinkStep>,
    warnings: &mut Vec<Warning>,
) -> Shrink {
    let mut made = |model: &str, r: Result<SVector<f64, N>, String>| match r {
        Ok(x) => Some(x),
        Err(reason) => {
            warnings.push(Warning::SimulationNotMade {
                model: format!("{model} (held-out data)"),
                reason,
            });
            None
        }
    };
    let sim_before = made(
        "the nominal model",
        horizon::prediction_error(robot, h, &[]),
    );
    let sim_after = if effects.is_empty() {
        sim_before
    } else {
        made(
            "the model with the explanation",
            horizon::prediction_error(robot, h, effects),
        )
    };
    let hq_noise = position_noise(holdout, h);
    let mut gap = [0.0f64; 4];
    let shrink_joints = (0..N)
        .map(|j| {
            let before = rms(h, &h.sig.residual, j);
            let aft = after.as_ref().map(|a| rms(h, a, j)).unwrap_or(before);
            let above = |x: f64, floor: f64| (x * x - floor * floor).max(0.0).sqrt() / floor;
            gap[0] += above(before, h.sig.floor[j]).powi(2);
            gap[1] += above(aft, h.sig.floor[j]).powi(2);
            let (sb, sa) = (sim_before.map(|s| s[j]), sim_after.map(|s| s[j]));
            gap[2] += sb.map_or(0.0, |x| above(x, hq_noise[j]).powi(2));
            gap[3] += sa.map_or(0.0, |x| above(x, hq_noise[j]).powi(2));
            JointShrink {
                joint: R::JOINT_NAMES[j].to_string(),
                torque_before: before,
                torque_after: aft,
                simulation_before: sb,
                simulation_after: sa,
            }
        })
        .collect();
    let frac = |b: f64, a: f64| if b > 0.0 { 1.0 - (a / b).sqrt() } else { 0.0 };
    let torque_fraction = frac(gap[0], gap[1]);
    Shrink {
        joints: shrink_joints,
        torque_fraction,
        simulation_fraction: (sim_before.is_some() && sim_after.is_some())
            .then(|| frac(gap[2], gap[3])),
        fraction: torque_fraction,
        rms_fraction,
        steps,
    }
}

/// Position noise per joint: robust spread of raw minus smoothed positions.
fn position_noise<const N: usize>(m: &Measured<N>, p: &Prepared<N>) -> SVector<f64, N> {
    let (a, z) = p.sig.range;
    SVector::from_fn(|j, _| {
        let d: Vec<f64> = (a..z).map(|k| m.q[k][j] - p.sig.q[k][j]).collect();
        robust_std(&d).max(1e-12)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synth::{synthesize, SynthOptions};

    dynamics_macros::robot! {
        robot Pendulum;
        gravity = [0.0, -9.81, 0.0];
        link base;
        link rod { mass = 1.0; com = [0.2, 0.0, 0.0]; inertia = [1e-3, 1e-2, 1e-2]; }
        joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
    }

    /// Effects no plant can take (taking away damping the pendulum does
    /// not have): the simulation after is left out, the fraction too, and
    /// a warning says why; the one before is made.
    #[test]
    fn a_simulation_that_cannot_be_made_is_left_out_and_said() {
        let arm = Pendulum::default();
        let opts = SynthOptions {
            duration: 2.0,
            seed: 4,
            ..Default::default()
        };
        let m = synthesize(&arm, &[], &opts).expect("synthesizes");
        let h = Prepared::new(&arm, &m);
        let away = [Effect::ViscousFriction { joint: 0, fv: -0.5 }];
        let mut warnings = Vec::new();
        let s = shrink(&arm, &m, &h, None, &away, 0.0, vec![], &mut warnings);
        assert!(s.joints[0].simulation_before.is_some_and(f64::is_finite));
        assert_eq!(s.joints[0].simulation_after, None);
        assert_eq!(s.simulation_fraction, None);
        match &warnings[..] {
            [Warning::SimulationNotMade { model, reason }] => {
                assert!(
                    model.starts_with("the model with the explanation"),
                    "{model}"
                );
                assert!(reason.contains("fv"), "{reason}");
            }
            other => panic!("{other:?}"),
        }
        // Nothing made: no warning, both figures.
        let mut none = Vec::new();
        let s = shrink(&arm, &m, &h, None, &[], 0.0, vec![], &mut none);
        assert!(none.is_empty() && s.simulation_fraction.is_some());
    }
}
