//! A yardstick for the short-horizon prediction error: the error the
//! same procedure shows when the model is exactly right and only the
//! sensors are noisy.
//!
//! For each prediction window, a twin of the data is made that the
//! nominal model explains exactly: the model itself, started from the
//! smoothed measured state, driven by its own efforts along the measured
//! motion (held from sample to sample as the recorded ones are). Sensor
//! noise of the data's levels (`Prepared::levels`: stated by the user, or
//! estimated from raw minus smoothed positions, velocities and efforts)
//! is added to what the twin records;
//! then the twin goes through the procedure of the prediction error
//! (smoothing, the start state from the smoothed samples, open-loop
//! simulation under the recorded efforts, comparison with the smoothed
//! positions). The RMS of that error is the floor: a ratio near 1 means
//! the model predicts the motion as well as an exact model could on
//! these data.

use nalgebra::SVector;
use rayon::prelude::*;

use crate::data::Measured;
use crate::diagnose::candidates::Prepared;
use crate::diagnose::evaluate::horizon::{spread, HORIZON, SPACING};
use crate::effects::Plant;
use crate::synth::Rng;
use dynamics_runtime::ode::Tolerances;
use dynamics_runtime::Robot;

/// Noise draws per window.
const DRAWS: usize = 2;

/// The floor of the short-horizon prediction error per joint (see the
/// module notes) over at most `horizon::WINDOWS` windows, on all cores; the position noise if the model
/// cannot be simulated.
pub fn prediction_floor<R: Robot<N> + Clone + Sync, const N: usize>(
    robot: &R,
    m: &Measured<N>,
    p: &Prepared<N>,
) -> SVector<f64, N> {
    let sig = &p.sig;
    let sg = &sig.sg;
    let h = sg.half();
    let (a, z) = sig.range;
    let [sigma_q, sigma_qd, sigma_tau] = p.levels;
    let Ok(plant) = Plant::new(robot.clone(), vec![]) else {
        return sigma_q;
    };
    let tol = Tolerances {
        rtol: 1e-7,
        atol: 1e-9,
        ..Default::default()
    };
    let len = (HORIZON / sig.dt).round() as usize;
    let step = ((SPACING / sig.dt).round() as usize).max(1);
    let seg = len + 2 * h + 1;
    let smooth = |x: &[SVector<f64, N>], c: usize, d: usize| -> SVector<f64, N> {
        sg.weights(d)
            .iter()
            .zip(&x[c - h..=c + h])
            .fold(SVector::zeros(), |acc, (w, v)| acc + v * *w)
    };
    let plant = &plant;
    // Sum of squared errors and their count over one window from `s0`.
    let window = |s0: usize| -> Option<(SVector<f64, N>, usize)> {
        let mut rng = Rng::new(0x5EED_F100 ^ (s0 as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15));
        // The twin: the nominal model under its own held efforts.
        let efforts: Vec<SVector<f64, N>> = (s0..s0 + seg)
            .map(|k| 0.5 * (sig.model[k] + sig.model[(k + 1).min(z - 1)]))
            .collect();
        let mut sim = plant.start(sig.q(s0), sig.qd(s0));
        sim.t = sig.t[s0];
        let mut truth = vec![(sim.state.q, sim.state.qd)];
        for i in 0..seg - 1 {
            sim.advance(plant, sig.t[s0 + i + 1], &efforts[i], tol)
                .ok()?;
            truth.push((sim.state.q, sim.state.qd));
        }
        let mut sum = SVector::<f64, N>::zeros();
        let mut count = 0;
        for _ in 0..DRAWS {
            // What its sensors record, and the procedure on that.
            let q: Vec<_> = truth
                .iter()
                .map(|x| x.0 + rng.normal_vec(&sigma_q))
                .collect();
            let qd: Vec<_> = truth
                .iter()
                .map(|x| x.1 + rng.normal_vec(&sigma_qd))
                .collect();
            let tau: Vec<_> = efforts
                .iter()
                .map(|e| e + rng.normal_vec(&sigma_tau))
                .collect();
            let v0 = if m.qd_measured {
                smooth(&qd, h, 0)
            } else {
                smooth(&q, h, 1)
            };
            let mut pred = plant.start(smooth(&q, h, 0), v0);
            pred.t = sig.t[s0 + h];
            for i in h..h + len {
                pred.advance(plant, sig.t[s0 + i + 1], &tau[i], tol).ok()?;
                let e = pred.state.q - smooth(&q, i + 1, 0);
                sum += e.component_mul(&e);
                count += 1;
            }
        }
        Some((sum, count))
    };
    // Windows on all cores.
    // Windows as the prediction error takes them (at most
    // `horizon::WINDOWS`, spread evenly over the record).
    let starts: Vec<usize> = spread(
        (a..)
            .step_by(step)
            .take_while(|s0| s0 + seg < z)
            .filter(|&s0| sig.mask.clear(s0, s0 + seg))
            .collect(),
    );
    let results: Vec<Option<(SVector<f64, N>, usize)>> = starts
        .par_iter()
        .with_max_len(1)
        .map(|&s0| window(s0))
        .collect();
    let mut sum = SVector::<f64, N>::zeros();
    let mut count = 0usize;
    for r in results {
        let Some((s, c)) = r else {
            return sigma_q;
        };
        sum += s;
        count += c;
    }
    if count == 0 {
        return sigma_q;
    }
    (sum / count as f64).map(|x| x.sqrt().max(1e-15))
}
