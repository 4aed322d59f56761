//! Short-horizon simulation error: from the measured state at the start of
//! each window, simulate the model (with or without an effect) under the
//! recorded efforts and compare the predicted positions with the measured.

use nalgebra::SVector;

use super::analysis::Prepared;
use crate::effects::{Effect, Plant};
use dynamics_runtime::ode::Tolerances;
use dynamics_runtime::Robot;

/// Window length, s.
pub const HORIZON: f64 = 0.1;
/// Spacing of window starts, s.
pub const SPACING: f64 = 0.5;

/// RMS position prediction error per joint over windows of [`HORIZON`]
/// seconds, for the model with `effects` attached (none: the nominal model).
pub fn prediction_error<R: Robot<N> + Clone, const N: usize>(
    robot: &R,
    p: &Prepared<N>,
    effects: &[Effect],
) -> SVector<f64, N> {
    let sig = &p.sig;
    let (mut offset, mut delay) = (SVector::<f64, N>::zeros(), 0.0);
    for e in effects {
        match *e {
            Effect::EncoderOffset { joint, offset: o } if joint < N => offset[joint] += o,
            Effect::TimeDelay { delay: d } => delay += d,
            _ => {}
        }
    }
    let sensor: Vec<Effect> = effects.iter().copied().filter(Effect::is_sensor).collect();
    let plant_effects: Vec<Effect> = effects.iter().copied().filter(|e| !e.is_sensor()).collect();
    let Ok(plant) = Plant::new(robot.clone(), plant_effects) else {
        return SVector::repeat(f64::INFINITY);
    };
    let dt = sig.dt;
    let shift = (delay / dt).round() as usize;
    let len = (HORIZON / dt).round() as usize;
    let step = ((SPACING / dt).round() as usize).max(1);
    let (a, z) = sig.range;
    let tol = Tolerances {
        rtol: 1e-7,
        atol: 1e-9,
        ..Default::default()
    };
    let mut sum = SVector::<f64, N>::zeros();
    let mut count = 0usize;
    let mut k0 = a;
    while k0 + shift + len < z {
        if !sig.mask.clear(k0, k0 + shift + len + 1) {
            k0 += step;
            continue;
        }
        // True state at t0 is what the sensors show `delay` later.
        let q0 = sig.q[k0 + shift] - offset;
        let mut sim = plant.start(q0, sig.qd[k0 + shift]);
        for (j, e) in plant.effects.iter().enumerate() {
            let _ = j;
            if let Effect::JointElasticity {
                joint, stiffness, ..
            } = *e
            {
                sim.state.qm[joint] = q0[joint] + sig.model[k0 + shift][joint] / stiffness;
            }
        }
        sim.t = sig.t[k0];
        let mut ok = true;
        for k in k0..k0 + len {
            if sim
                .advance(
                    &plant,
                    sig.t[k + 1],
                    &Effect::applied_effort(&sensor, &sig.tau_raw[k]),
                    tol,
                )
                .is_err()
            {
                ok = false;
                break;
            }
            let predicted = sim.state.q + offset;
            let measured = sig.q[k + 1 + shift];
            sum += (predicted - measured).component_mul(&(predicted - measured));
            count += 1;
        }
        if !ok {
            return SVector::repeat(f64::INFINITY);
        }
        k0 += step;
    }
    if count == 0 {
        return SVector::zeros();
    }
    (sum / count as f64).map(f64::sqrt)
}
