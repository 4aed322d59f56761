//! Smooth exciting reference motions for identification experiments:
//! drawn at random of a kind ([`ExcitationKind`]), or given in full (a
//! designed [`Fourier`] motion, or samples of a motion read from a file).

use std::f64::consts::PI;
use std::str::FromStr;

use nalgebra::SVector;

use super::Rng;
use crate::excite::Fourier;
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

#[derive(Debug, Clone, PartialEq)]
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

/// Where a reference motion comes from.
#[derive(Debug, Clone, PartialEq)]
enum Source<const N: usize> {
    /// Drawn of a kind: the home pose plus a pattern per joint.
    Drawn {
        home: SVector<f64, N>,
        joints: Vec<Joint>,
    },
    /// A designed motion (`dynamics excite`), repeated period after period.
    Designed(Fourier<N>),
    /// Samples `(t, reference)` in increasing time, interpolated between
    /// them by the quintic that matches position, velocity and acceleration
    /// at both ends; held at the first (last) sample's position, at rest,
    /// before (after) them.
    Samples(Vec<(f64, Reference<N>)>),
}

/// A reference motion: home pose plus a per-joint pattern of amplitude
/// `amplitude[j]` ([`Excitation::new`]), a designed motion
/// ([`Excitation::designed`]) or samples of one ([`Excitation::samples`]).
///
/// ```
/// use dynamics_sim2real::synth::{Excitation, ExcitationKind, Rng};
/// let ex = Excitation::<2>::new(ExcitationKind::PickPlace, [0.0, 1.0].into(), [0.5, 0.5].into(), 8.0, &mut Rng::new(3));
/// let r0 = ex.at(0.0);
/// assert_eq!(r0.qd.norm(), 0.0); // starts at rest
/// assert!((r0.q[1] - 1.0).abs() < 1e-12);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Excitation<const N: usize> {
    source: Source<N>,
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
        Excitation {
            source: Source::Drawn { home, joints },
        }
    }

    /// The designed motion `motion` (what `dynamics excite` writes as
    /// JSON), repeated period after period.
    ///
    /// ```
    /// use dynamics_sim2real::excite::Fourier;
    /// use dynamics_sim2real::synth::Excitation;
    /// let mut f = Fourier::<1>::new([0.2].into(), 2.0, 3);
    /// f.sin[0][0] = 0.3;
    /// f.to_rest();
    /// let ex = Excitation::designed(f.clone());
    /// assert_eq!(ex.at(0.7), f.at(0.7));
    /// assert!(ex.at(0.0).qd[0].abs() < 1e-12); // at rest at the start
    /// ```
    pub fn designed(motion: Fourier<N>) -> Self {
        Excitation {
            source: Source::Designed(motion),
        }
    }

    /// A motion given by its samples `(t, reference)` (a motion file:
    /// `t, q_<joint>, qd_<joint>, qdd_<joint>`), interpolated between
    /// samples by the quintic that matches position, velocity and
    /// acceleration at both ends of each interval; before the first sample
    /// (after the last) at rest at its position. `Err` names the first
    /// sample out of order or not finite.
    ///
    /// ```
    /// use dynamics_runtime::control::Reference;
    /// use dynamics_sim2real::synth::Excitation;
    /// let r = |q: f64, qd: f64| Reference { q: [q].into(), qd: [qd].into(), qdd: [0.0].into() };
    /// let ex = Excitation::samples(vec![(0.0, r(0.0, 0.0)), (1.0, r(1.0, 0.0))]).unwrap();
    /// assert!((ex.at(0.5).q[0] - 0.5).abs() < 1e-12); // the rest-to-rest quintic's midpoint
    /// assert_eq!(ex.at(3.0).q[0], 1.0);
    /// assert!(Excitation::samples(vec![(1.0, r(0.0, 0.0)), (0.5, r(1.0, 0.0))]).is_err());
    /// ```
    pub fn samples(samples: Vec<(f64, Reference<N>)>) -> Result<Self, String> {
        if samples.is_empty() {
            return Err("no samples".into());
        }
        for (i, (t, r)) in samples.iter().enumerate() {
            let finite = t.is_finite()
                && r.q
                    .iter()
                    .chain(r.qd.iter())
                    .chain(r.qdd.iter())
                    .all(|v| v.is_finite());
            if !finite {
                return Err(format!("sample {i} (t = {t}): a value is not finite"));
            }
            if i > 0 && *t <= samples[i - 1].0 {
                return Err(format!(
                    "sample {i}: t = {t} does not follow t = {}",
                    samples[i - 1].0
                ));
            }
        }
        Ok(Excitation {
            source: Source::Samples(samples),
        })
    }

    /// Desired position, velocity and acceleration at time `t`.
    pub fn at(&self, t: f64) -> Reference<N> {
        let (home, joints) = match &self.source {
            Source::Drawn { home, joints } => (home, joints),
            Source::Designed(f) => return f.at(t),
            Source::Samples(s) => return interpolate(s, t),
        };
        let mut r = Reference {
            q: *home,
            qd: SVector::zeros(),
            qdd: SVector::zeros(),
        };
        for (j, joint) in joints.iter().enumerate() {
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

/// The samples' motion at `t` (see [`Excitation::samples`]).
fn interpolate<const N: usize>(s: &[(f64, Reference<N>)], t: f64) -> Reference<N> {
    let rest = |r: &Reference<N>| Reference {
        q: r.q,
        qd: SVector::zeros(),
        qdd: SVector::zeros(),
    };
    let i = s.partition_point(|k| k.0 <= t);
    if i == 0 {
        return rest(&s[0].1);
    }
    if i >= s.len() {
        let (t_last, r) = &s[s.len() - 1];
        return if t == *t_last { *r } else { rest(r) };
    }
    let ((t0, a), (t1, b)) = (&s[i - 1], &s[i]);
    let h = t1 - t0;
    let u = (t - t0) / h;
    // Quintic Hermite basis on [0, 1] and its first two derivatives.
    let (u2, u3, u4, u5) = (u * u, u * u * u, u.powi(4), u.powi(5));
    let p = [
        1.0 - 10.0 * u3 + 15.0 * u4 - 6.0 * u5,
        u - 6.0 * u3 + 8.0 * u4 - 3.0 * u5,
        0.5 * (u2 - 3.0 * u3 + 3.0 * u4 - u5),
        10.0 * u3 - 15.0 * u4 + 6.0 * u5,
        -4.0 * u3 + 7.0 * u4 - 3.0 * u5,
        0.5 * (u3 - 2.0 * u4 + u5),
    ];
    let d = [
        -30.0 * u2 + 60.0 * u3 - 30.0 * u4,
        1.0 - 18.0 * u2 + 32.0 * u3 - 15.0 * u4,
        0.5 * (2.0 * u - 9.0 * u2 + 12.0 * u3 - 5.0 * u4),
        30.0 * u2 - 60.0 * u3 + 30.0 * u4,
        -12.0 * u2 + 28.0 * u3 - 15.0 * u4,
        0.5 * (3.0 * u2 - 8.0 * u3 + 5.0 * u4),
    ];
    let dd = [
        -60.0 * u + 180.0 * u2 - 120.0 * u3,
        -36.0 * u + 96.0 * u2 - 60.0 * u3,
        0.5 * (2.0 - 18.0 * u + 36.0 * u2 - 20.0 * u3),
        60.0 * u - 180.0 * u2 + 120.0 * u3,
        -24.0 * u + 84.0 * u2 - 60.0 * u3,
        0.5 * (6.0 * u - 24.0 * u2 + 20.0 * u3),
    ];
    // The end values in the unit interval's scale: velocity x h,
    // acceleration x h^2.
    let ends = [
        a.q,
        a.qd * h,
        a.qdd * (h * h),
        b.q,
        b.qd * h,
        b.qdd * (h * h),
    ];
    let mix = |w: &[f64; 6]| -> SVector<f64, N> {
        ends.iter()
            .zip(w)
            .fold(SVector::zeros(), |acc, (e, w)| acc + e * *w)
    };
    Reference {
        q: mix(&p),
        qd: mix(&d) / h,
        qdd: mix(&dd) / (h * h),
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

    #[test]
    fn samples_are_interpolated_through_their_values_and_derivatives() {
        // Samples of a cubic in time: the quintic through two of its
        // samples (values, first and second derivatives) is the cubic.
        let cubic = |t: f64| Reference::<1> {
            q: [0.3 * t * t * t - t * t + 0.5 * t + 0.2].into(),
            qd: [0.9 * t * t - 2.0 * t + 0.5].into(),
            qdd: [1.8 * t - 2.0].into(),
        };
        let times = [0.0, 0.4, 1.1, 2.0];
        let ex = Excitation::samples(times.iter().map(|&t| (t, cubic(t))).collect()).unwrap();
        for t in [0.0, 0.13, 0.4, 0.77, 1.5, 2.0] {
            let (a, b) = (ex.at(t), cubic(t));
            assert!((a.q - b.q).norm() < 1e-12, "t={t}");
            assert!((a.qd - b.qd).norm() < 1e-11, "t={t}");
            assert!((a.qdd - b.qdd).norm() < 1e-10, "t={t}");
        }
        assert_eq!(ex.at(-1.0).q, cubic(0.0).q);
        assert_eq!(ex.at(5.0).qd[0], 0.0);
    }
}
