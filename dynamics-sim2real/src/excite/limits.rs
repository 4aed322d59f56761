//! The limits a designed motion keeps: positions, velocities, efforts (the
//! URDF's `LOWER`, `UPPER`, `VELOCITY`, `EFFORT`) and an optional
//! acceleration limit, tightened by a margin.

use nalgebra::SVector;

use super::ExciteError;

/// Per-joint limits (`f64::INFINITY` where there is none).
///
/// ```
/// use dynamics_sim2real::excite::Limits;
/// let l = Limits::<2>::new([-1.0, -2.0], [1.0, 2.0], [2.0, 3.0], [10.0, f64::INFINITY]);
/// let m = l.with_margin(0.1);
/// assert!((m.upper[0] - 0.9).abs() < 1e-12 && (m.lower[1] + 1.8).abs() < 1e-12);
/// assert!((m.velocity[1] - 2.7).abs() < 1e-12 && m.effort[1].is_infinite());
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limits<const N: usize> {
    /// Lower position limits, rad or m.
    pub lower: SVector<f64, N>,
    /// Upper position limits.
    pub upper: SVector<f64, N>,
    /// Velocity limits (magnitude).
    pub velocity: SVector<f64, N>,
    /// Effort limits (magnitude), N m or N.
    pub effort: SVector<f64, N>,
    /// Acceleration limits (magnitude); `None`: not limited.
    pub acceleration: Option<SVector<f64, N>>,
}

impl<const N: usize> Limits<N> {
    /// Limits from the four arrays `robot!` emits for a URDF robot
    /// (`Robot::LOWER`, `UPPER`, `VELOCITY`, `EFFORT`), without an
    /// acceleration limit.
    ///
    /// ```
    /// use dynamics_sim2real::excite::Limits;
    /// let l = Limits::<1>::new([-1.0], [1.0], [2.0], [5.0]);
    /// assert!(l.acceleration.is_none());
    /// ```
    pub fn new(lower: [f64; N], upper: [f64; N], velocity: [f64; N], effort: [f64; N]) -> Self {
        Limits {
            lower: lower.into(),
            upper: upper.into(),
            velocity: velocity.into(),
            effort: effort.into(),
            acceleration: None,
        }
    }

    /// Limits for a robot whose description has none: the box today's
    /// default excitation of that amplitude (`synth`'s three sines from
    /// 0.15 to 1 Hz, see [`crate::synth::Excitation`]) can reach: positions
    /// `home +- 2 amplitude`, velocities `pi * amplitude`; no effort limit.
    ///
    /// ```
    /// use dynamics_sim2real::excite::Limits;
    /// let l = Limits::<1>::around([0.5].into(), [0.2].into());
    /// assert!((l.upper[0] - 0.9).abs() < 1e-12);
    /// assert!((l.velocity[0] - 0.2 * std::f64::consts::PI).abs() < 1e-12);
    /// ```
    pub fn around(home: SVector<f64, N>, amplitude: SVector<f64, N>) -> Self {
        let a = amplitude.abs();
        Limits {
            lower: home - a * 2.0,
            upper: home + a * 2.0,
            velocity: a * std::f64::consts::PI,
            effort: SVector::repeat(f64::INFINITY),
            acceleration: None,
        }
    }

    /// Missing (infinite) position and velocity limits of `self` taken from
    /// `fallback`.
    ///
    /// ```
    /// use dynamics_sim2real::excite::Limits;
    /// let urdf = Limits::<2>::new([-1.0, f64::NEG_INFINITY], [1.0, f64::INFINITY], [2.0, f64::INFINITY], [3.0, 3.0]);
    /// let l = urdf.or(&Limits::around([0.0, 0.0].into(), [0.5, 0.5].into()));
    /// assert_eq!((l.lower[0], l.upper[1]), (-1.0, 1.0));
    /// ```
    pub fn or(&self, fallback: &Limits<N>) -> Self {
        let pick = |a: f64, b: f64| if a.is_finite() { a } else { b };
        let mut out = *self;
        for j in 0..N {
            out.lower[j] = pick(self.lower[j], fallback.lower[j]);
            out.upper[j] = pick(self.upper[j], fallback.upper[j]);
            out.velocity[j] = pick(self.velocity[j], fallback.velocity[j]);
            out.effort[j] = pick(self.effort[j], fallback.effort[j]);
        }
        if out.acceleration.is_none() {
            out.acceleration = fallback.acceleration;
        }
        out
    }

    /// The limits tightened by `margin` (a fraction in [0, 1)): the position
    /// range shrinks by `margin` of its width (half on each side),
    /// velocity, effort and acceleration limits by the factor `1 - margin`.
    pub fn with_margin(&self, margin: f64) -> Self {
        let keep = 1.0 - margin;
        let half = (self.upper - self.lower) * (0.5 * margin);
        Limits {
            lower: self.lower + half,
            upper: self.upper - half,
            velocity: self.velocity * keep,
            effort: self.effort * keep,
            acceleration: self.acceleration.map(|a| a * keep),
        }
    }

    /// The middle of the position range where it is finite; the URDF's zero
    /// where zero lies inside the range and the range is unbounded on a side.
    ///
    /// ```
    /// use dynamics_sim2real::excite::Limits;
    /// let l = Limits::<2>::new([-1.0, 0.2], [3.0, 0.4], [1.0; 2], [1.0; 2]);
    /// assert!((l.middle() - nalgebra::Vector2::new(1.0, 0.3)).norm() < 1e-12);
    /// ```
    pub fn middle(&self) -> SVector<f64, N> {
        SVector::from_fn(|j, _| {
            let (lo, hi) = (self.lower[j], self.upper[j]);
            if lo.is_finite() && hi.is_finite() {
                0.5 * (lo + hi)
            } else {
                0.0_f64.clamp(lo, hi)
            }
        })
    }

    /// Errors when a position or velocity limit is not finite (the design
    /// fills the room the limits leave, so it needs them).
    pub(crate) fn require_finite(&self, names: &[&str]) -> Result<(), ExciteError> {
        for j in 0..N {
            let joint = names.get(j).copied().unwrap_or("?").to_string();
            if !(self.lower[j].is_finite() && self.upper[j].is_finite()) {
                return Err(ExciteError::Unbounded {
                    joint,
                    what: "position",
                });
            }
            if !self.velocity[j].is_finite() {
                return Err(ExciteError::Unbounded {
                    joint,
                    what: "velocity",
                });
            }
        }
        Ok(())
    }
}
