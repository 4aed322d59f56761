//! How far the gap shrinks on the held-out data once the explanation's
//! effects are added: the torque residual above noise and the
//! short-horizon simulation error, per joint and overall.

use nalgebra::SVector;

use super::horizon;
use crate::data::Measured;
use crate::diagnose::candidates::Prepared;
use crate::diagnose::signals::robust_std;
use crate::effects::Effect;
use crate::Warning;
use dynamics_runtime::Robot;

/// The shrink of one joint: the held-out torque residual's RMS and the
/// short-horizon simulation error before and after the explanation.
#[derive(Debug, Clone, Copy)]
pub struct JointFigures {
    /// Torque residual RMS, nominal model.
    pub torque_before: f64,
    /// Torque residual RMS with the explanation.
    pub torque_after: f64,
    /// Simulation error, nominal model (`None`: not made).
    pub simulation_before: Option<f64>,
    /// Simulation error with the explanation (`None`: not made).
    pub simulation_after: Option<f64>,
}

/// How far the gap shrinks on the held-out record.
#[derive(Debug, Clone)]
pub struct ShrinkFigures<const N: usize> {
    /// Per joint.
    pub joints: [JointFigures; N],
    /// 1 - after / before of the torque gap above noise.
    pub torque_fraction: f64,
    /// The same of the simulation error (`None`: a simulation not made).
    pub simulation_fraction: Option<f64>,
}

/// The shrink on `holdout` (prepared as `h`) of the explanation: `after`,
/// the held-out torque residual it leaves at the rows of `h` (one entry a
/// row; `None`: nothing added, no shrink), `effects` its effects. A simulation that cannot be
/// made leaves its figures out and says why in `warnings`.
pub fn shrink<R: Robot<N> + Clone + Sync, const N: usize>(
    robot: &R,
    holdout: &Measured<N>,
    h: &Prepared<N>,
    after: Option<Vec<SVector<f64, N>>>,
    effects: &[Effect],
    warnings: &mut Vec<Warning>,
) -> ShrinkFigures<N> {
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
    let joints = std::array::from_fn(|j| {
        let before = h.rms(&h.sig.residual, j);
        let aft = after.as_ref().map(|a| h.rms_rows(a, j)).unwrap_or(before);
        let above = |x: f64, floor: f64| (x * x - floor * floor).max(0.0).sqrt() / floor;
        gap[0] += above(before, h.sig.floor[j]).powi(2);
        gap[1] += above(aft, h.sig.floor[j]).powi(2);
        let (sb, sa) = (sim_before.map(|s| s[j]), sim_after.map(|s| s[j]));
        gap[2] += sb.map_or(0.0, |x| above(x, hq_noise[j]).powi(2));
        gap[3] += sa.map_or(0.0, |x| above(x, hq_noise[j]).powi(2));
        JointFigures {
            torque_before: before,
            torque_after: aft,
            simulation_before: sb,
            simulation_after: sa,
        }
    });
    let frac = |b: f64, a: f64| if b > 0.0 { 1.0 - (a / b).sqrt() } else { 0.0 };
    let torque_fraction = frac(gap[0], gap[1]);
    ShrinkFigures {
        joints,
        torque_fraction,
        simulation_fraction: (sim_before.is_some() && sim_after.is_some())
            .then(|| frac(gap[2], gap[3])),
    }
}

/// Position noise per joint: robust spread of raw minus smoothed positions.
fn position_noise<const N: usize>(m: &Measured<N>, p: &Prepared<N>) -> SVector<f64, N> {
    let (a, z) = p.sig.range;
    SVector::from_fn(|j, _| {
        let d: Vec<f64> = (a..z)
            .map(|k| m.q[k][j] - p.sig.motion.q_at(k, j))
            .collect();
        robust_std(&d).max(1e-12)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synth::{synthesize, SynthOptions};
    use crate::test_robots::Pendulum;

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
        let s = shrink(&arm, &m, &h, None, &away, &mut warnings);
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
        let s = shrink(&arm, &m, &h, None, &[], &mut none);
        assert!(none.is_empty() && s.simulation_fraction.is_some());
    }
}
