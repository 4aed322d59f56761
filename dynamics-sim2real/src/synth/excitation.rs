//! Smooth exciting reference motions for identification experiments.

use std::f64::consts::PI;
use std::str::FromStr;

use nalgebra::SVector;

use super::Rng;
use dynamics_runtime::control::Reference;

/// Which kind of reference motion.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ExcitationKind {
    /// Three sines per joint at distinct frequencies (0.15-0.9 Hz).
    Sines,
    /// A sine sweeping 0.1 -> 1.5 Hz over the run.
    Chirp,
    /// Rest-to-rest quintic moves between random waypoints, with holds.
    PickPlace,
}

impl FromStr for ExcitationKind {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "sines" => Ok(ExcitationKind::Sines),
            "chirp" => Ok(ExcitationKind::Chirp),
            "pick-place" => Ok(ExcitationKind::PickPlace),
            _ => Err(format!(
                "unknown excitation `{s}`; known: sines, chirp, pick-place"
            )),
        }
    }
}

#[derive(Debug, Clone)]
enum Joint {
    Sines {
        a: [f64; 3],
        w: [f64; 3],
        phi: [f64; 3],
    },
    Chirp {
        a: f64,
        f0: f64,
        f1: f64,
        t_end: f64,
        phi: f64,
    },
    Moves {
        knots: Vec<(f64, f64)>,
    },
}

/// A reference motion: home pose plus a per-joint pattern of amplitude
/// `amplitude[j]`.
///
/// ```
/// use dynamics_sim2real::synth::{Excitation, ExcitationKind, Rng};
/// let ex = Excitation::<2>::new(ExcitationKind::PickPlace, [0.0, 1.0].into(), [0.5, 0.5].into(), 8.0, &mut Rng::new(3));
/// let r0 = ex.at(0.0);
/// assert_eq!(r0.qd.norm(), 0.0); // starts at rest
/// assert!((r0.q[1] - 1.0).abs() < 1e-12);
/// ```
#[derive(Debug, Clone)]
pub struct Excitation<const N: usize> {
    home: SVector<f64, N>,
    joints: Vec<Joint>,
}

impl<const N: usize> Excitation<N> {
    /// Draws a reference of `kind` lasting `duration` seconds.
    pub fn new(
        kind: ExcitationKind,
        home: SVector<f64, N>,
        amplitude: SVector<f64, N>,
        duration: f64,
        rng: &mut Rng,
    ) -> Self {
        let joints = (0..N)
            .map(|j| {
                let amp = amplitude[j];
                match kind {
                    ExcitationKind::Sines => {
                        let base = rng.uniform(0.15, 0.3);
                        let w = [
                            2.0 * PI * base,
                            2.0 * PI * base * rng.uniform(1.7, 2.1),
                            2.0 * PI * base * rng.uniform(2.9, 3.3),
                        ];
                        let a = [amp * 0.55, amp * 0.3, amp * 0.15];
                        let phi = [
                            rng.uniform(0.0, 2.0 * PI),
                            rng.uniform(0.0, 2.0 * PI),
                            rng.uniform(0.0, 2.0 * PI),
                        ];
                        Joint::Sines { a, w, phi }
                    }
                    ExcitationKind::Chirp => Joint::Chirp {
                        a: amp,
                        f0: 0.1,
                        f1: 1.5,
                        t_end: duration,
                        phi: rng.uniform(0.0, 2.0 * PI),
                    },
                    ExcitationKind::PickPlace => {
                        let mut knots = vec![(0.0, 0.0)];
                        let mut t = rng.uniform(0.1, 0.3);
                        knots.push((t, 0.0));
                        while t < duration {
                            t += rng.uniform(0.6, 1.1);
                            knots.push((t, amp * rng.uniform(-1.0, 1.0)));
                            t += rng.uniform(0.2, 0.5);
                            let last = knots[knots.len() - 1].1;
                            knots.push((t, last));
                        }
                        Joint::Moves { knots }
                    }
                }
            })
            .collect();
        Excitation { home, joints }
    }

    /// Desired position, velocity and acceleration at time `t`.
    pub fn at(&self, t: f64) -> Reference<N> {
        let mut r = Reference {
            q: self.home,
            qd: SVector::zeros(),
            qdd: SVector::zeros(),
        };
        for (j, joint) in self.joints.iter().enumerate() {
            let (p, v, a) = match joint {
                Joint::Sines { a, w, phi } => (0..3).fold((0.0, 0.0, 0.0), |acc, k| {
                    let (s, c) = (w[k] * t + phi[k]).sin_cos();
                    let (s0, _) = phi[k].sin_cos();
                    (
                        acc.0 + a[k] * (s - s0),
                        acc.1 + a[k] * w[k] * c,
                        acc.2 - a[k] * w[k] * w[k] * s,
                    )
                }),
                Joint::Chirp {
                    a,
                    f0,
                    f1,
                    t_end,
                    phi,
                } => {
                    let rate = (f1 - f0) / t_end;
                    let ph = 2.0 * PI * (f0 * t + 0.5 * rate * t * t) + phi;
                    let w = 2.0 * PI * (f0 + rate * t);
                    let wd = 2.0 * PI * rate;
                    let (s, c) = ph.sin_cos();
                    (a * (s - phi.sin()), a * w * c, a * (wd * c - w * w * s))
                }
                Joint::Moves { knots } => moves(knots, t),
            };
            r.q[j] += p;
            r.qd[j] = v;
            r.qdd[j] = a;
        }
        r
    }
}

/// Quintic rest-to-rest blend between consecutive knots (time, position).
fn moves(knots: &[(f64, f64)], t: f64) -> (f64, f64, f64) {
    let i = knots.partition_point(|k| k.0 <= t);
    if i == 0 {
        return (knots[0].1, 0.0, 0.0);
    }
    if i >= knots.len() {
        return (knots[knots.len() - 1].1, 0.0, 0.0);
    }
    let ((t0, p0), (t1, p1)) = (knots[i - 1], knots[i]);
    let h = t1 - t0;
    let s = (t - t0) / h;
    let d = p1 - p0;
    let pos = s * s * s * (10.0 - 15.0 * s + 6.0 * s * s);
    let vel = 30.0 * s * s * (1.0 - s) * (1.0 - s) / h;
    let acc = 60.0 * s * (1.0 - s) * (1.0 - 2.0 * s) / (h * h);
    (p0 + d * pos, d * vel, d * acc)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn derivatives_match_finite_differences() {
        for kind in [
            ExcitationKind::Sines,
            ExcitationKind::Chirp,
            ExcitationKind::PickPlace,
        ] {
            let ex = Excitation::<2>::new(
                kind,
                [0.1, -0.2].into(),
                [0.5, 0.3].into(),
                6.0,
                &mut Rng::new(9),
            );
            for &t in &[0.05, 1.234, 3.3, 5.7] {
                let h = 1e-5;
                let (a, b, c) = (ex.at(t - h), ex.at(t), ex.at(t + h));
                let v = (c.q - a.q) / (2.0 * h);
                let acc = (c.qd - a.qd) / (2.0 * h);
                assert!((v - b.qd).norm() < 1e-6, "{kind:?} t={t}");
                assert!((acc - b.qdd).norm() < 1e-5, "{kind:?} t={t}");
            }
        }
    }
}
