//! The constraint check of a sampled motion: positions, velocities and
//! efforts (inverse dynamics of the nominal model along the motion) within
//! the limits, margin included, and accelerations against an optional
//! limit; and the largest scaling of a Fourier motion that keeps the
//! kinematic limits.

use nalgebra::SVector;
use serde::Serialize;

use super::{Fourier, Limits};
use dynamics_runtime::control::Reference;
use dynamics_runtime::Robot;

/// Extremes of a sampled motion and whether they keep the limits.
///
/// ```
/// use dynamics_sim2real::excite::{check, Limits};
/// use dynamics_runtime::control::Reference;
/// dynamics_macros::robot! {
///     pub robot Pendulum;
///     gravity = [0.0, -9.81, 0.0];
///     link base;
///     link rod { mass = 1.0; com = [1.0, 0.0, 0.0]; }
///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
/// }
/// let limits = Limits::<1>::new([-1.0], [1.0], [2.0], [5.0]);
/// let at = |q: f64| Reference { q: [q].into(), qd: [0.0].into(), qdd: [0.0].into() };
/// // Held horizontal: 9.81 N m > 5 N m.
/// let c = check(&Pendulum::default(), &[at(0.0)], &limits);
/// assert!(c.position && c.velocity && !c.effort && !c.all());
/// assert!((c.peak_effort[0] - 9.81).abs() < 1e-9);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Check<const N: usize> {
    /// Every position within `[lower, upper]`.
    pub position: bool,
    /// Every velocity within the velocity limit.
    pub velocity: bool,
    /// Every effort within the effort limit.
    pub effort: bool,
    /// Every acceleration within the acceleration limit (`true` without one).
    pub acceleration: bool,
    /// Smallest position per joint.
    #[serde(serialize_with = "super::report::vector")]
    pub min_q: SVector<f64, N>,
    /// Largest position per joint.
    #[serde(serialize_with = "super::report::vector")]
    pub max_q: SVector<f64, N>,
    /// Largest velocity magnitude per joint.
    #[serde(serialize_with = "super::report::vector")]
    pub peak_velocity: SVector<f64, N>,
    /// Largest acceleration magnitude per joint.
    #[serde(serialize_with = "super::report::vector")]
    pub peak_acceleration: SVector<f64, N>,
    /// Largest effort magnitude per joint (nominal inverse dynamics).
    #[serde(serialize_with = "super::report::vector")]
    pub peak_effort: SVector<f64, N>,
}

impl<const N: usize> Check<N> {
    /// Whether every limit holds.
    pub fn all(&self) -> bool {
        self.position && self.velocity && self.effort && self.acceleration
    }
}

/// Checks `samples` against `limits` (give the limits with their margin
/// applied: [`Limits::with_margin`]).
pub fn check<R: Robot<N>, const N: usize>(
    robot: &R,
    samples: &[Reference<N>],
    limits: &Limits<N>,
) -> Check<N> {
    let mut c = Check {
        position: true,
        velocity: true,
        effort: true,
        acceleration: true,
        min_q: SVector::repeat(f64::INFINITY),
        max_q: SVector::repeat(f64::NEG_INFINITY),
        peak_velocity: SVector::zeros(),
        peak_acceleration: SVector::zeros(),
        peak_effort: SVector::zeros(),
    };
    for s in samples {
        let tau = robot.inverse_dynamics(&s.q, &s.qd, &s.qdd);
        for j in 0..N {
            c.min_q[j] = c.min_q[j].min(s.q[j]);
            c.max_q[j] = c.max_q[j].max(s.q[j]);
            c.peak_velocity[j] = c.peak_velocity[j].max(s.qd[j].abs());
            c.peak_acceleration[j] = c.peak_acceleration[j].max(s.qdd[j].abs());
            // NaN compares false: a NaN effort fails the check.
            let e = tau[j].abs();
            c.peak_effort[j] = if e.is_nan() {
                f64::NAN
            } else {
                c.peak_effort[j].max(e)
            };
        }
    }
    for j in 0..N {
        c.position &= c.min_q[j] >= limits.lower[j] && c.max_q[j] <= limits.upper[j];
        c.velocity &= c.peak_velocity[j] <= limits.velocity[j];
        c.effort &= c.peak_effort[j] <= limits.effort[j];
        if let Some(a) = limits.acceleration {
            c.acceleration &= c.peak_acceleration[j] <= a[j];
        }
    }
    c
}

/// Per joint, the largest factor by which the displacement of `motion`
/// from its start pose can be multiplied while positions, velocities and
/// (when limited) accelerations stay within `limits` at the times `ts`.
/// A joint that does not move gets 0.
pub fn room<const N: usize>(
    motion: &Fourier<N>,
    ts: &[f64],
    limits: &Limits<N>,
) -> SVector<f64, N> {
    let (mut up, mut down) = (SVector::<f64, N>::zeros(), SVector::<f64, N>::zeros());
    let (mut v, mut a) = (SVector::<f64, N>::zeros(), SVector::<f64, N>::zeros());
    for &t in ts {
        let r = motion.at(t);
        let d = r.q - motion.q0;
        for j in 0..N {
            up[j] = up[j].max(d[j]);
            down[j] = down[j].max(-d[j]);
            v[j] = v[j].max(r.qd[j].abs());
            a[j] = a[j].max(r.qdd[j].abs());
        }
    }
    SVector::from_fn(|j, _| {
        let mut s = f64::INFINITY;
        let mut cap = |need: f64, have: f64| {
            if need > 0.0 {
                s = s.min(have.max(0.0) / need);
            }
        };
        cap(up[j], limits.upper[j] - motion.q0[j]);
        cap(down[j], motion.q0[j] - limits.lower[j]);
        cap(v[j], limits.velocity[j]);
        if let Some(al) = limits.acceleration {
            cap(a[j], al[j]);
        }
        if s.is_finite() {
            s
        } else {
            0.0
        }
    })
}
