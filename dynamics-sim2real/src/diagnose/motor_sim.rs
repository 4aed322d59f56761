//! The motor-side simulation behind elasticity, backlash and the stiff
//! rotor (`motor.rs` says what it models), run for several guesses at
//! once: the guesses of a grid, of a compass step or of a finite
//! difference share the measured signals and differ only in their
//! parameters, and one integration step is a chain of dependent
//! operations, so lanes integrated side by side keep the processor's
//! units busy where one lane waits on its own chain. Every lane does
//! exactly the operations, in the same order, of a simulation on its own:
//! its result does not depend on its companions.

use std::f64::consts::PI;

use super::motor::{MotorGuess, OBSERVER_HZ};
use super::signals::Signals;

/// Lanes integrated side by side.
pub const LANES: usize = 4;

/// The raw transmitted effort (see `motor::motor_transmitted_raw`) of
/// every guess of `gs` at joint `j`, in their order.
pub fn transmitted_raw_many<const N: usize>(
    sig: &Signals<N>,
    j: usize,
    gs: &[MotorGuess],
    backlash: bool,
    inertia: f64,
) -> Vec<Vec<f64>> {
    let mut out = Vec::with_capacity(gs.len());
    let mut rest = gs;
    while !rest.is_empty() {
        let take = rest.len().min(LANES);
        let (now, later) = rest.split_at(take);
        match (take, backlash) {
            (1, false) => out.extend(lanes::<N, 1, false>(sig, j, now, inertia)),
            (1, true) => out.extend(lanes::<N, 1, true>(sig, j, now, inertia)),
            (2, false) => out.extend(lanes::<N, 2, false>(sig, j, now, inertia)),
            (2, true) => out.extend(lanes::<N, 2, true>(sig, j, now, inertia)),
            (_, false) => out.extend(lanes::<N, LANES, false>(sig, j, now, inertia)),
            (_, true) => out.extend(lanes::<N, LANES, true>(sig, j, now, inertia)),
        }
        rest = later;
    }
    out
}

/// The force the coupling of lane parameters `(k, c, w)` (stiffness,
/// damping, half-width) passes for deflection `e` and its rate `ed`, of
/// one of `L` lanes, `B` backlash.
#[inline(always)]
fn force<const L: usize, const B: bool>(k: f64, c: f64, w: f64, e: f64, ed: f64) -> f64 {
    if !B {
        return k * e + c * ed;
    }
    if L == 1 {
        return if e > w {
            (k * (e - w) + c * ed).max(0.0)
        } else if e < -w {
            (k * (e + w) + c * ed).min(0.0)
        } else {
            0.0
        };
    }
    // Lanes side by side: both sides computed and one selected, no
    // branch for the lanes to mispredict (a half-width is positive, so at
    // most one side is in contact); the same values.
    let pushing = (k * (e - w) + c * ed).max(0.0);
    let pulling = (k * (e + w) + c * ed).min(0.0);
    let f = if e < -w { pulling } else { 0.0 };
    if e > w {
        pushing
    } else {
        f
    }
}

/// What the lanes' state derivative needs besides the state: each lane's
/// coupling and motor inertia, and the interval's measured effort.
struct Lanes<'a, const L: usize> {
    k: &'a [f64; L],
    c: &'a [f64; L],
    w: &'a [f64; L],
    inv_jm: &'a [f64; L],
    inv_i: f64,
    wo2: f64,
    two_wo: f64,
    tau: f64,
}

impl<const L: usize> Lanes<'_, L> {
    /// State derivative of every lane (motor angle, motor rate, link
    /// angle, link rate) where the measured motion and the model's effort
    /// are `m` (q, qd, qdd, effort): the link follows the measured motion
    /// plus what the transmitted effort adds over the model's, pulled back
    /// to the measurement at OBSERVER_HZ.
    #[inline(always)]
    fn derivative<const B: bool>(&self, x: &[[f64; L]; 4], m: &[f64; 4]) -> [[f64; L]; 4] {
        let [qs, vs, as_, ms] = *m;
        let mut dx = [[0.0; L]; 4];
        for l in 0..L {
            let f = force::<L, B>(
                self.k[l],
                self.c[l],
                self.w[l],
                x[0][l] - x[2][l],
                x[1][l] - x[3][l],
            );
            dx[0][l] = x[1][l];
            dx[1][l] = (self.tau - f) * self.inv_jm[l];
            dx[2][l] = x[3][l];
            dx[3][l] = as_
                + (f - ms) * self.inv_i
                + self.wo2 * (qs - x[2][l])
                + self.two_wo * (vs - x[3][l]);
        }
        dx
    }
}

/// `x + c k`, lane by lane.
#[inline(always)]
fn add<const L: usize>(x: &[[f64; L]; 4], k: &[[f64; L]; 4], c: f64) -> [[f64; L]; 4] {
    let mut y = *x;
    for i in 0..4 {
        for l in 0..L {
            y[i][l] = x[i][l] + c * k[i][l];
        }
    }
    y
}

/// `L` lanes side by side, `B` backlash; `gs` has 1 to `L` guesses (the
/// last repeated to fill the lanes, its copies dropped).
fn lanes<const N: usize, const L: usize, const B: bool>(
    sig: &Signals<N>,
    j: usize,
    gs: &[MotorGuess],
    inertia: f64,
) -> Vec<Vec<f64>> {
    let n = sig.t.len();
    let (a, z) = sig.range;
    let used = gs.len().min(L);
    let nan = || vec![vec![f64::NAN; n]; used];
    if z <= a + 1 || used == 0 {
        return nan();
    }
    let g: [MotorGuess; L] = std::array::from_fn(|l| gs[l.min(used - 1)]);
    let (k_, c_, w_) = (
        g.map(|g| g.stiffness),
        g.map(|g| g.damping),
        g.map(|g| g.half_width),
    );
    let mut out = nan();
    let mut lane_out: [Vec<f64>; L] = std::array::from_fn(|_| vec![f64::NAN; n]);
    let load = sig.model[a][j];
    // State per lane: motor angle, motor rate, link angle, link rate.
    let mut x = [[0.0f64; L]; 4];
    for l in 0..L {
        x[0][l] = if B {
            sig.q[a][j] + load.signum() * (g[l].half_width + load.abs() / g[l].stiffness)
        } else {
            sig.q[a][j] + load / g[l].stiffness
        };
        x[1][l] = sig.qd[a][j];
        x[2][l] = sig.q[a][j];
        x[3][l] = sig.qd[a][j];
    }
    let mut dead = [false; L];
    let wo = 2.0 * PI * OBSERVER_HZ;
    let (wo2, two_wo) = (wo * wo, 2.0 * wo);
    // Two RK4 steps a sample: omega h <= 0.8 up to the 250 Hz stiff rotor,
    // well inside RK4's stability; the scoring named the same effects on
    // five seed bases as with four steps.
    const SUB: usize = 2;
    // A multiply, not a divide, on the integration's dependent chain.
    let inv_jm = g.map(|g| 1.0 / g.jm);
    let inv_i = 1.0 / inertia;
    for k in a..z {
        for l in 0..L {
            lane_out[l][k] =
                force::<L, B>(k_[l], c_[l], w_[l], x[0][l] - x[2][l], x[1][l] - x[3][l]);
        }
        if k + 1 >= z {
            break;
        }
        let (q0, v0, a0, m0) = (sig.q[k][j], sig.qd[k][j], sig.qdd[k][j], sig.model[k][j]);
        let (q1, v1, a1, m1) = (
            sig.q[k + 1][j],
            sig.qd[k + 1][j],
            sig.qdd[k + 1][j],
            sig.model[k + 1][j],
        );
        let h = (sig.t[k + 1] - sig.t[k]) / SUB as f64;
        let tau = sig.tau_raw[k][j];
        // The measured motion and the model's effort at fraction s of the
        // interval.
        let at = |s: f64| -> [f64; 4] {
            [
                q0 + (q1 - q0) * s,
                v0 + (v1 - v0) * s,
                a0 + (a1 - a0) * s,
                m0 + (m1 - m0) * s,
            ]
        };
        let lane = Lanes {
            k: &k_,
            c: &c_,
            w: &w_,
            inv_jm: &inv_jm,
            inv_i,
            wo2,
            two_wo,
            tau,
        };
        for i in 0..SUB {
            let s0 = i as f64 / SUB as f64;
            let sm = (i as f64 + 0.5) / SUB as f64;
            let s1 = (i + 1) as f64 / SUB as f64;
            let (m0s, mms, m1s) = (at(s0), at(sm), at(s1));
            let k1 = lane.derivative::<B>(&x, &m0s);
            let k2 = lane.derivative::<B>(&add(&x, &k1, 0.5 * h), &mms);
            let k3 = lane.derivative::<B>(&add(&x, &k2, 0.5 * h), &mms);
            let k4 = lane.derivative::<B>(&add(&x, &k3, h), &m1s);
            for c in 0..4 {
                for l in 0..L {
                    x[c][l] += h / 6.0 * (k1[c][l] + 2.0 * k2[c][l] + 2.0 * k3[c][l] + k4[c][l]);
                }
            }
        }
        let mut all_dead = true;
        for l in 0..L {
            if !x[0][l].is_finite() || !x[1][l].is_finite() || !x[2][l].is_finite() {
                dead[l] = true;
                // (A diverged lane goes on from rest, its result dropped.)
                for row in x.iter_mut() {
                    row[l] = 0.0;
                }
            }
            all_dead &= dead[l];
        }
        if all_dead {
            break;
        }
    }
    for (l, o) in out.iter_mut().enumerate() {
        if !dead[l] {
            std::mem::swap(o, &mut lane_out[l]);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnose::filter::SavitzkyGolay;
    use nalgebra::SVector;

    /// The simulation of one guess as it was written before lanes: the
    /// reference each lane must reproduce bit for bit.
    #[allow(clippy::needless_range_loop)]
    fn one_at_a_time<const N: usize>(
        sig: &Signals<N>,
        j: usize,
        g: &MotorGuess,
        backlash: bool,
        inertia: f64,
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
            sig.q[a][j] + load.signum() * (g.half_width + load.abs() / g.stiffness)
        } else {
            sig.q[a][j] + load / g.stiffness
        };
        let mut thd = sig.qd[a][j];
        let (mut ql, mut vl) = (sig.q[a][j], sig.qd[a][j]);
        let wo = 2.0 * PI * OBSERVER_HZ;
        // Two RK4 steps a sample: omega h <= 0.8 up to the 250 Hz stiff rotor,
        // well inside RK4's stability; the scoring named the same effects on
        // five seed bases as with four steps.
        const SUB: usize = 2;
        // A multiply, not a divide, on the integration's dependent chain.
        let (inv_jm, inv_i) = (1.0 / g.jm, 1.0 / inertia);
        for k in a..z {
            out[k] = force(th - ql, thd - vl);
            if k + 1 >= z {
                break;
            }
            let (q0, v0, a0, m0) = (sig.q[k][j], sig.qd[k][j], sig.qdd[k][j], sig.model[k][j]);
            let (q1, v1, a1, m1) = (
                sig.q[k + 1][j],
                sig.qd[k + 1][j],
                sig.qdd[k + 1][j],
                sig.model[k + 1][j],
            );
            let h = (sig.t[k + 1] - sig.t[k]) / SUB as f64;
            let tau = sig.tau_raw[k][j];
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
        let n = 3000;
        let dt = 1e-3;
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
        Signals {
            dt,
            range: (40, n - 40),
            t,
            q,
            qd: qd.clone(),
            qdd,
            qd_light: qd,
            tau: tau_raw.clone(),
            tau_raw,
            model: model.clone(),
            model_rate: model.clone(),
            residual: model,
            floor: v(1.0),
            sg: SavitzkyGolay::new(40, dt),
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
        for backlash in [false, true] {
            let mut gs = guesses(backlash);
            // A guess whose integration blows up (a rotor of no inertia).
            gs[3].jm = 1e-12;
            let alone: Vec<Vec<f64>> = gs
                .iter()
                .map(|g| one_at_a_time(&sig, 0, g, backlash, 0.8))
                .collect();
            assert!(alone[3].iter().all(|x| x.is_nan()));
            assert!(alone[0][100].is_finite() && alone[0][100] != 0.0);
            for group in [1, 2, 3, 7] {
                let mut together = Vec::new();
                for c in gs.chunks(group) {
                    together.extend(transmitted_raw_many(&sig, 0, c, backlash, 0.8));
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
}
