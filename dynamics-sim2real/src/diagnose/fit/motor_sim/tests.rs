//! The lanes against the simulation of one guess at a time.

use super::*;
use crate::data::Measured;
use crate::diagnose::signals::{Motion, Times};
use crate::smoothing::SavitzkyGolay;
use nalgebra::SVector;
use std::sync::Arc;

/// The simulation of one guess as it was written before lanes: the
/// reference each lane must reproduce bit for bit.
#[allow(clippy::needless_range_loop)]
fn one_at_a_time<const N: usize>(
    sig: &Signals<N>,
    j: usize,
    g: &MotorGuess,
    backlash: bool,
    compliance: &SVector<f64, N>,
) -> Vec<f64> {
    let n = sig.t.len();
    let (a, z) = sig.range;
    let mut out = vec![f64::NAN; n];
    if z <= a + 1 {
        return out;
    }
    let force = |e: f64, ed: f64| -> f64 {
        if backlash {
            if e > g.half_width {
                (g.stiffness * (e - g.half_width) + g.damping * ed).max(0.0)
            } else if e < -g.half_width {
                (g.stiffness * (e + g.half_width) + g.damping * ed).min(0.0)
            } else {
                0.0
            }
        } else {
            g.stiffness * e + g.damping * ed
        }
    };
    let load = sig.model[a][j];
    let mut th = if backlash {
        sig.motion.q_at(a, j) + load.signum() * (g.half_width + load.abs() / g.stiffness)
    } else {
        sig.motion.q_at(a, j) + load / g.stiffness
    };
    let mut thd = sig.motion.qd_at(a, j);
    let (mut ql, mut vl) = (sig.motion.q_at(a, j), sig.motion.qd_at(a, j));
    let wo = 2.0 * PI * OBSERVER_HZ;
    // Two RK4 steps a sample: omega h <= 0.8 up to the 250 Hz stiff rotor,
    // well inside RK4's stability (|R(z)| < 1 for |z| < 2.78 on the
    // imaginary axis).
    const SUB: usize = 2;
    // A multiply, not a divide, on the integration's dependent chain.
    let inv_jm = 1.0 / g.jm;
    for k in a..z {
        out[k] = force(th - ql, thd - vl);
        if k + 1 >= z {
            break;
        }
        let (q0, v0, a0, m0) = (
            sig.motion.q_at(k, j),
            sig.motion.qd_at(k, j),
            sig.motion.qdd_at(k, j),
            sig.model[k][j],
        );
        let (q1, v1, a1, m1) = (
            sig.motion.q_at(k + 1, j),
            sig.motion.qd_at(k + 1, j),
            sig.motion.qdd_at(k + 1, j),
            sig.model[k + 1][j],
        );
        let h = (sig.t[k + 1] - sig.t[k]) / SUB as f64;
        let tau = sig.tau_raw()[k][j];
        let inv_i = compliance[j];
        // State derivative of (motor angle, motor rate, link angle, link
        // rate) at fraction s of the interval: the link follows the
        // measured motion plus what the transmitted effort adds over the
        // model's, pulled back to the measurement at OBSERVER_HZ.
        let d = |x: [f64; 4], s: f64| -> [f64; 4] {
            let qs = q0 + (q1 - q0) * s;
            let vs = v0 + (v1 - v0) * s;
            let as_ = a0 + (a1 - a0) * s;
            let ms = m0 + (m1 - m0) * s;
            let f = force(x[0] - x[2], x[1] - x[3]);
            [
                x[1],
                (tau - f) * inv_jm,
                x[3],
                as_ + (f - ms) * inv_i + wo * wo * (qs - x[2]) + 2.0 * wo * (vs - x[3]),
            ]
        };
        let mut x = [th, thd, ql, vl];
        for i in 0..SUB {
            let s0 = i as f64 / SUB as f64;
            let sm = (i as f64 + 0.5) / SUB as f64;
            let s1 = (i + 1) as f64 / SUB as f64;
            let add = |x: [f64; 4], k: [f64; 4], c: f64| -> [f64; 4] {
                [
                    x[0] + c * k[0],
                    x[1] + c * k[1],
                    x[2] + c * k[2],
                    x[3] + c * k[3],
                ]
            };
            let k1 = d(x, s0);
            let k2 = d(add(x, k1, 0.5 * h), sm);
            let k3 = d(add(x, k2, 0.5 * h), sm);
            let k4 = d(add(x, k3, h), s1);
            for c in 0..4 {
                x[c] += h / 6.0 * (k1[c] + 2.0 * k2[c] + 2.0 * k3[c] + k4[c]);
            }
        }
        [th, thd, ql, vl] = x;
        if !th.is_finite() || !thd.is_finite() || !ql.is_finite() {
            return vec![f64::NAN; n];
        }
    }
    out
}

/// A joint swinging with a slow drift, its efforts a noisy law of the
/// motion, over 3 s at 1 kHz.
fn signals() -> Signals<1> {
    swinging(3.0)
}

/// The swinging joint of [`signals`] over `seconds` at 1 kHz.
pub(super) fn swinging(seconds: f64) -> Signals<1> {
    let dt = 1e-3;
    let n = (seconds / dt).round() as usize;
    let mut rng = crate::synth::Rng::new(11);
    let t: Vec<f64> = (0..n).map(|k| k as f64 * dt).collect();
    let v = |x: f64| SVector::<f64, 1>::new(x);
    let q: Vec<_> = t.iter().map(|&s| v((3.0 * s).sin() + 0.1 * s)).collect();
    let qd: Vec<_> = t.iter().map(|&s| v(3.0 * (3.0 * s).cos() + 0.1)).collect();
    let qdd: Vec<_> = t.iter().map(|&s| v(-9.0 * (3.0 * s).sin())).collect();
    let model: Vec<_> = qdd.iter().map(|a| a * 0.8 + v(2.0)).collect();
    let tau_raw: Vec<_> = model
        .iter()
        .zip(&qd)
        .map(|(m, w)| m + v(0.3 * w[0].signum() + 0.02 * rng.normal()))
        .collect();
    let record = Arc::new(Measured {
        t,
        q,
        qd,
        tau: tau_raw,
        qd_measured: true,
        ..Default::default()
    });
    let sg = SavitzkyGolay::new(40, dt);
    Signals {
        dt,
        range: (40, n - 40),
        t: Times::of(&record),
        motion: Motion::of(&record, &sg),
        qd_measured: true,
        light: SavitzkyGolay::new(4, dt),
        record,
        model: model.clone(),
        residual: model,
        floor: v(1.0),
        sg,
        mask: Default::default(),
    }
}

fn guesses(backlash: bool) -> Vec<MotorGuess> {
    let inertia = 0.8;
    (0..7)
        .map(|i| {
            let jm = inertia * (0.05 + 0.05 * i as f64);
            let w = 2.0 * PI * (5.0 + 12.0 * i as f64);
            let stiffness = w * w / (1.0 / jm + 1.0 / inertia);
            MotorGuess {
                jm,
                stiffness,
                damping: 2.0 * 0.1 * (stiffness * jm).sqrt(),
                half_width: if backlash { 1e-3 * (1 + i) as f64 } else { 0.0 },
            }
        })
        .collect()
}

/// Lanes side by side reproduce the one-at-a-time simulation exactly,
/// in any grouping, a diverging companion included.
#[test]
fn every_lane_is_the_simulation_of_its_guess_alone() {
    let sig = signals();
    // A link of inertia 0.8.
    let compliance = SVector::<f64, 1>::new(1.0 / 0.8);
    for backlash in [false, true] {
        let mut gs = guesses(backlash);
        // A guess whose integration blows up (a rotor of no inertia).
        gs[3].jm = 1e-12;
        let alone: Vec<Vec<f64>> = gs
            .iter()
            .map(|g| one_at_a_time(&sig, 0, g, backlash, &compliance))
            .collect();
        assert!(alone[3].iter().all(|x| x.is_nan()));
        assert!(alone[0][100].is_finite() && alone[0][100] != 0.0);
        for group in [1, 2, 3, 7] {
            let mut together = Vec::new();
            for c in gs.chunks(group) {
                together.extend(transmitted_raw_many(&sig, 0, c, backlash, &compliance));
            }
            assert_eq!(together.len(), gs.len());
            for (a, b) in alone.iter().zip(&together) {
                assert_eq!(a.len(), b.len());
                for (x, y) in a.iter().zip(b) {
                    assert!(x.to_bits() == y.to_bits(), "{backlash} {group}: {x} vs {y}");
                }
            }
        }
    }
}

/// A joint's track over a span is the motion made where asked, to the
/// bit; a thread keeps it for the next lanes over the same span and
/// joint of the same motion, and makes another for another span or
/// record.
#[test]
fn a_kept_track_is_the_motion_of_its_span() {
    let sig = signals();
    let other = swinging(2.0);
    let span = (100, 900);
    let same = |t: &Track, s: &Signals<1>| {
        let m = &s.motion;
        assert_eq!(t.q.len(), span.1 - span.0);
        for (i, k) in (span.0..span.1).enumerate() {
            assert_eq!(t.q[i].to_bits(), m.q_at(k, 0).to_bits(), "{k}");
            assert_eq!(t.qd[i].to_bits(), m.qd_at(k, 0).to_bits(), "{k}");
            assert_eq!(t.qdd[i].to_bits(), m.qdd_at(k, 0).to_bits(), "{k}");
        }
    };
    let t = Track::of(&sig, 0, span);
    same(&t, &sig);
    assert!(t.qdd.iter().any(|x| x.abs() > 1.0));
    assert!(Rc::ptr_eq(&t, &Track::of(&sig, 0, span)));
    assert!(Rc::ptr_eq(&t, &Track::of(&sig.clone(), 0, span)));
    assert!(!Rc::ptr_eq(&t, &Track::of(&sig, 0, (100, 901))));
    let o = Track::of(&other, 0, span);
    assert!(!Rc::ptr_eq(&t, &o));
    same(&o, &other);
}
