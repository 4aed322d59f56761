//! A force the motion takes, against the residual of a one-joint plant
//! integrated finely: `through_motion` reproduces it, the efforts'
//! smoothing does not.

use super::through_motion;
use crate::smoothing::SavitzkyGolay;

/// The force: a friction turning over 5 ms at `t0`, with a Stribeck
/// breakaway of 60 % more over 15 ms.
fn force(t: f64) -> f64 {
    let t0 = 0.5;
    let s = (t - t0) / 0.005;
    -(1.0 + 0.6 * (-((t - t0) / 0.015).powi(2)).exp()) * s.tanh()
}

/// A smooth effort.
fn effort(t: f64) -> f64 {
    3.0 * (2.0 * t).sin() + 1.0
}

/// Samples 1 ms apart of the plant `m a = effort + force`, integrated
/// with 50 steps a sample (midpoint rule): times, positions, velocities,
/// and the force's mean over each sample's own interval.
fn plant(m: f64) -> (Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>) {
    let (dt, sub, n) = (1e-3, 50, 1000);
    let h = dt / sub as f64;
    let (mut q, mut v, mut t) = (0.0, 0.2, 0.0);
    let (mut ts, mut qs, mut vs, mut fs) = (vec![], vec![], vec![], vec![]);
    for _ in 0..n {
        ts.push(t);
        qs.push(q);
        vs.push(v);
        let mean: f64 = (0..sub)
            .map(|i| force(t + (i as f64 + 0.5) * h - 0.5 * dt))
            .sum::<f64>()
            / sub as f64;
        fs.push(mean);
        for _ in 0..sub {
            let a = |s: f64| (effort(s) + force(s)) / m;
            let vm = v + 0.5 * h * a(t);
            q += h * vm;
            v += h * a(t + 0.5 * h);
            t += h;
        }
    }
    (ts, qs, vs, fs)
}

/// Around the turn, the residual `effort - m qdd` (smoothed effort, the
/// acceleration from the velocities' fit, or the positions') against
/// minus the force filtered by `through_motion`: within 0.005 (of a turn
/// from 1.6 to -1.6 at its breakaway); against the force smoothed like
/// the efforts: off by more than 0.1 (0.17 here).
#[test]
fn the_residual_holds_the_force_as_the_motion_carries_it() {
    let m = 2.0;
    let dt = 1e-3;
    let (t, q, v, f) = plant(m);
    let sg = SavitzkyGolay::analysis(dt);
    let tau: Vec<f64> = t.iter().map(|&s| effort(s)).collect();
    let tau_s = sg.apply(&tau, 0);
    let smoothed = sg.apply(&f, 0);
    for measured in [true, false] {
        let qdd = if measured {
            sg.apply(&v, 1)
        } else {
            sg.apply(&q, 2)
        };
        let shown = through_motion(&sg, &f, dt, measured);
        let (mut worst, mut worst_smoothed) = (0.0f64, 0.0f64);
        for k in 400..600 {
            let residual = tau_s[k] - m * qdd[k];
            worst = worst.max((residual + shown[k]).abs());
            worst_smoothed = worst_smoothed.max((residual + smoothed[k]).abs());
        }
        assert!(worst < 0.005, "measured {measured}: {worst}");
        assert!(
            worst_smoothed > 0.1,
            "measured {measured}: {worst_smoothed}"
        );
    }
}
