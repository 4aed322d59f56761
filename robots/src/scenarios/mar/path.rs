//! The gripper's flat trajectory of the vibration paper, Table 2 (Q = 0.05, L = 0.35,
//! K = 0.05, R = 0.05 m), with its stops and start-ups, as a function of
//! time and of the cycle angle beta.
//!
//! The vibration paper shows the path only in its Fig. 2 and gives the formula in its
//! reference [13], which we do not have. The choice made here fits the
//! description (a flat path of straight runs and circular arcs, "described
//! with a combination of trigonometric functions", with stops and
//! start-ups) and reads Table 2's four lengths as a pick-and-place portal
//! in the local frame `X1 Y1 O1` (O1 the pick point, X1 horizontal, Y1 up):
//!
//! ```text
//!            R    L     R
//!          .-'-----------'-.
//!          |               |        1. lift   Q straight up
//!        Q |               | K      2. arc    radius R, quarter turn
//!          |               |        3. run    L straight along X1
//!         O1               place    4. arc    radius R, quarter turn
//!                                   5. lower  K straight down
//! ```
//!
//! The gripper stops at the end of every segment and starts up again: each
//! segment is one rest-to-rest move with the cycloidal law
//! `s = l (phi - sin phi) / (2 pi)`, `phi` from 0 to 2 pi, whose velocity
//! `l (1 - cos phi) / T` and acceleration `2 pi l sin phi / T^2` vanish at
//! both ends. So position, velocity and acceleration are continuous along
//! the whole cycle although the path's curvature jumps where an arc meets a
//! straight run (the speed is zero there). Every move reaches the same peak
//! tangential acceleration [`A_MAX`]: its duration is
//! `T = sqrt(2 pi l / A_MAX)`. The cycle starts with [`REST_START`] at rest,
//! dwells [`DWELL`] at every stop and ends with [`REST_END`] at rest.
//!
//! beta is the angle of the working cycle: `beta = 2 pi t / T_cycle`; the
//! position on the path is a function of beta through the moves' laws.

use std::f64::consts::{FRAC_PI_2, PI};

use nalgebra::Vector2;

/// Table 2: lift height Q, m.
pub const Q: f64 = 0.05;
/// Table 2: length L of the straight transfer run, m.
pub const L: f64 = 0.35;
/// Table 2: lowering depth K, m.
pub const K: f64 = 0.05;
/// Table 2: radius R of the arcs, m.
pub const R: f64 = 0.05;
/// Peak tangential acceleration of every move, m/s^2 (our choice).
pub const A_MAX: f64 = 6.0;
/// Rest before the first move, s.
pub const REST_START: f64 = 0.1;
/// Dwell at each intermediate stop, s.
pub const DWELL: f64 = 0.05;
/// Rest after the last move, s.
pub const REST_END: f64 = 0.3;

/// A straight run or a circular arc of the path, in the local frame.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Segment {
    Line {
        from: Vector2<f64>,
        to: Vector2<f64>,
    },
    Arc {
        centre: Vector2<f64>,
        a0: f64,
        a1: f64,
    },
}

impl Segment {
    fn length(&self) -> f64 {
        match self {
            Segment::Line { from, to } => (to - from).norm(),
            Segment::Arc { a0, a1, .. } => R * (a1 - a0).abs(),
        }
    }

    /// Position, unit tangent and d2p/ds2 at arc length `s`.
    fn at(&self, s: f64) -> (Vector2<f64>, Vector2<f64>, Vector2<f64>) {
        match self {
            Segment::Line { from, to } => {
                let u = (to - from) / self.length();
                (from + u * s, u, Vector2::zeros())
            }
            Segment::Arc { centre, a0, a1 } => {
                let dir = (a1 - a0).signum();
                let a = a0 + dir * s / R;
                let radial = Vector2::new(a.cos(), a.sin());
                let tangent = Vector2::new(-a.sin(), a.cos()) * dir;
                (centre + radial * R, tangent, -radial / R)
            }
        }
    }
}

/// The five segments of the portal, in order.
fn segments() -> [Segment; 5] {
    let top = Q + R;
    [
        Segment::Line {
            from: Vector2::zeros(),
            to: Vector2::new(0.0, Q),
        },
        Segment::Arc {
            centre: Vector2::new(R, Q),
            a0: PI,
            a1: FRAC_PI_2,
        },
        Segment::Line {
            from: Vector2::new(R, top),
            to: Vector2::new(R + L, top),
        },
        Segment::Arc {
            centre: Vector2::new(R + L, top - R),
            a0: FRAC_PI_2,
            a1: 0.0,
        },
        Segment::Line {
            from: Vector2::new(2.0 * R + L, top - R),
            to: Vector2::new(2.0 * R + L, top - R - K),
        },
    ]
}

/// The gripper at one instant, in the local frame `X1 Y1 O1`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathPoint {
    /// Time, s.
    pub t: f64,
    /// Cycle angle beta, rad.
    pub beta: f64,
    /// Position, m.
    pub p: Vector2<f64>,
    /// Velocity, m/s.
    pub v: Vector2<f64>,
    /// Acceleration, m/s^2.
    pub a: Vector2<f64>,
    /// Path speed ds/dt, m/s.
    pub speed: f64,
    /// Tangential acceleration d2s/dt2, m/s^2.
    pub accel: f64,
    /// Index of the segment (0..5) the gripper is on or last finished.
    pub segment: usize,
}

/// Duration of the rest-to-rest move over a segment of length `l`.
fn duration(l: f64) -> f64 {
    (2.0 * PI * l / A_MAX).sqrt()
}

/// Start times and durations of the five moves.
fn schedule() -> [(f64, f64); 5] {
    let mut out = [(0.0, 0.0); 5];
    let mut t = REST_START;
    for (slot, seg) in out.iter_mut().zip(segments()) {
        let d = duration(seg.length());
        *slot = (t, d);
        t += d + DWELL;
    }
    out
}

/// Length of one working cycle, s.
///
/// ```
/// let t = robots::scenarios::mar::path::cycle_time();
/// assert!(t > 1.5 && t < 3.0);
/// ```
pub fn cycle_time() -> f64 {
    let (t0, d) = schedule()[4];
    t0 + d + REST_END
}

/// Total path length, m: Q + L + K + pi R.
///
/// ```
/// let l = robots::scenarios::mar::path::length();
/// assert!((l - (0.05 + 0.35 + 0.05 + std::f64::consts::PI * 0.05)).abs() < 1e-12);
/// ```
pub fn length() -> f64 {
    segments().iter().map(Segment::length).sum()
}

/// The gripper at time `t` (clamped to one cycle).
///
/// ```
/// use robots::scenarios::mar::path::{at, cycle_time, L, R};
/// let end = at(cycle_time());
/// assert!((end.p.x - (L + 2.0 * R)).abs() < 1e-12 && end.p.y.abs() < 1e-12);
/// assert!(end.v.norm() == 0.0 && end.a.norm() == 0.0);
/// ```
pub fn at(t: f64) -> PathPoint {
    let period = cycle_time();
    let t = t.clamp(0.0, period);
    let segs = segments();
    let sched = schedule();
    // The last move that has started (the first one before it starts).
    let i = sched.iter().rposition(|(t0, _)| t >= *t0).unwrap_or(0);
    let (t0, d) = sched[i];
    let seg = segs[i];
    let l = seg.length();
    let phi = (2.0 * PI * (t - t0) / d).clamp(0.0, 2.0 * PI);
    let (s, sd, sdd) = if phi >= 2.0 * PI {
        (l, 0.0, 0.0)
    } else {
        (
            l * (phi - phi.sin()) / (2.0 * PI),
            l * (1.0 - phi.cos()) / d,
            2.0 * PI * l * phi.sin() / (d * d),
        )
    };
    let (p, tangent, curv) = seg.at(s);
    PathPoint {
        t,
        beta: 2.0 * PI * t / period,
        p,
        v: tangent * sd,
        a: tangent * sdd + curv * (sd * sd),
        speed: sd,
        accel: sdd,
        segment: i,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn segments_join_end_to_start_with_common_tangents() {
        let segs = segments();
        for w in segs.windows(2) {
            let (end, t_end, _) = w[0].at(w[0].length());
            let (start, t_start, _) = w[1].at(0.0);
            assert!((end - start).norm() < 1e-15, "{end} {start}");
            assert!((t_end - t_start).norm() < 1e-15);
        }
        assert!((length() - (Q + L + K + PI * R)).abs() < 1e-15);
    }
}
