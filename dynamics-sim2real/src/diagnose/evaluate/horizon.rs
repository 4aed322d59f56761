//! Short-horizon simulation error: from the measured state at the start of
//! each window, simulate the model (with or without an effect) under the
//! recorded efforts and compare the predicted positions with the measured
//! (windows on all cores). A delay shifts the recorded motion against the
//! recorded efforts: a positive one reads the motion that many samples
//! later, a negative one (the effort late, `late.rs`) the efforts.
//!
//! A window starts every [`SPACING`] seconds where the samples are clear;
//! a record with more than [`WINDOWS`] such windows (some two minutes of
//! record) is sampled at [`WINDOWS`] of them spread evenly over it
//! ([`spread`]), so that the error's cost stops growing with the log.

use nalgebra::SVector;
use rayon::prelude::*;

use crate::diagnose::candidates::Prepared;
use crate::effects::{Effect, Plant};
use dynamics_runtime::ode::Tolerances;
use dynamics_runtime::Robot;

/// Window length, s.
pub const HORIZON: f64 = 0.1;
/// Spacing of window starts, s.
pub const SPACING: f64 = 0.5;
/// Most windows an error is averaged over (120 s of record at
/// [`SPACING`]).
pub const WINDOWS: usize = 240;

/// The window starts `starts` (increasing) kept when there are more than
/// [`WINDOWS`]: `WINDOWS` of them spread evenly, the `i`-th being entry
/// `i * n / WINDOWS` of the `n` (the first one always among them); all of
/// them otherwise.
pub fn spread(starts: Vec<usize>) -> Vec<usize> {
    let n = starts.len();
    if n <= WINDOWS {
        return starts;
    }
    (0..WINDOWS).map(|i| starts[i * n / WINDOWS]).collect()
}

/// RMS position prediction error per joint over windows of [`HORIZON`]
/// seconds (at most [`WINDOWS`] of them, [`spread`]), for the model with `effects` attached (none: the nominal model);
/// why not, when a plant cannot be built or a window not simulated.
pub fn prediction_error<R: Robot<N> + Clone + Sync, const N: usize>(
    robot: &R,
    p: &Prepared<N>,
    effects: &[Effect],
) -> Result<SVector<f64, N>, String> {
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
    let plant = Plant::new(robot.clone(), plant_effects).map_err(|e| e.to_string())?;
    let dt = sig.dt;
    // Samples the motion (`m`) or the efforts (`e`) are read later.
    let shift = (delay / dt).round();
    let (m, e) = if shift >= 0.0 {
        (shift as usize, 0)
    } else {
        (0, (-shift) as usize)
    };
    let shift = m.max(e);
    let len = (HORIZON / dt).round() as usize;
    let step = ((SPACING / dt).round() as usize).max(1);
    let (a, z) = sig.range;
    let tol = Tolerances {
        rtol: 1e-7,
        atol: 1e-9,
        ..Default::default()
    };
    // Window starts, each window simulated on its own (on all cores).
    let mut starts = Vec::new();
    let mut k0 = a;
    while k0 + shift + len < z {
        if sig.mask.clear(k0, k0 + shift + len + 1) {
            starts.push(k0);
        }
        k0 += step;
    }
    let starts = spread(starts);
    let plant = &plant;
    let window = |&k0: &usize| -> Result<Vec<SVector<f64, N>>, String> {
        // True state at t0 is what the sensors show `delay` later.
        let q0 = sig.q(k0 + m) - offset;
        let mut sim = plant.start(q0, sig.qd(k0 + m));
        for e in plant.effects.iter() {
            if let Effect::JointElasticity {
                joint, stiffness, ..
            } = *e
            {
                sim.state.qm[joint] = q0[joint] + sig.model[k0 + m][joint] / stiffness;
            }
        }
        sim.t = sig.t[k0];
        let mut errors = Vec::with_capacity(len);
        for k in k0..k0 + len {
            sim.advance(
                plant,
                sig.t[k + 1],
                &Effect::applied_effort(&sensor, &sig.tau_raw()[k + e]),
                tol,
            )
            .map_err(|e| format!("the window from t = {:.3} s: {e}", sig.t[k0]))?;
            let predicted = sim.state.q + offset;
            let measured = sig.q(k + 1 + m);
            errors.push((predicted - measured).component_mul(&(predicted - measured)));
        }
        Ok(errors)
    };
    let windows: Vec<_> = starts.par_iter().with_max_len(1).map(window).collect();
    // Summed in the order of the samples, as one pass over them would.
    let mut sum = SVector::<f64, N>::zeros();
    let mut count = 0usize;
    for w in windows {
        for e in w? {
            sum += e;
            count += 1;
        }
    }
    if count == 0 {
        return Ok(SVector::zeros());
    }
    let rms = (sum / count as f64).map(f64::sqrt);
    if rms.iter().all(|x| x.is_finite()) {
        Ok(rms)
    } else {
        Err("a simulated position is not finite".into())
    }
}

#[cfg(test)]
mod tests {
    use super::{spread, WINDOWS};

    /// Up to [`WINDOWS`] starts are all kept; more are thinned to
    /// [`WINDOWS`] of them, increasing, the first among them, each step
    /// over the kept ones `n / WINDOWS` entries rounded down or up.
    #[test]
    fn a_long_records_windows_are_spread_evenly() {
        let few: Vec<usize> = (0..WINDOWS).map(|i| 3 + 500 * i).collect();
        assert_eq!(spread(few.clone()), few);
        for n in [WINDOWS + 1, 2 * WINDOWS, 3 * WINDOWS + 7, 7200] {
            let starts: Vec<usize> = (0..n).map(|i| 10 + 500 * i).collect();
            let kept = spread(starts.clone());
            assert_eq!(kept.len(), WINDOWS, "{n}");
            assert_eq!(kept[0], starts[0]);
            let (lo, hi) = (n / WINDOWS, n.div_ceil(WINDOWS));
            for w in kept.windows(2) {
                let step = (w[1] - w[0]) / 500;
                assert!((lo..=hi).contains(&step), "{n}: step {step}");
            }
            assert!(*kept.last().unwrap() >= starts[n - hi]);
        }
    }
}
