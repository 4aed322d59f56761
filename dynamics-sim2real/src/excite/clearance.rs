//! A simple clearance check of the link frames: the origins of the frames
//! the joints move stay above the ground by a margin, and the origins of
//! two frames whose distance the joints can change stay apart by a minimum
//! distance. Only frame origins are checked (points), not the links'
//! shapes or meshes: a margin of a few centimetres is a margin between
//! frame origins, not between surfaces.
//!
//! - The ground is the plane through the base frame's origin (the world
//!   origin, where the root link sits) normal to gravity; a frame's height
//!   is its origin's position along `-gravity`. Without gravity there is no
//!   ground to check.
//! - Frames fixed to the base (their origin the same over random states
//!   within the limits) are not checked against the ground.
//! - Pairs of frames whose origins keep one distance over those states
//!   (a link and its parent or child, frames on one joint axis, frames
//!   fixed to one link) are not checked against each other: no motion
//!   brings them closer.
//! - A frame already below the ground margin at the start pose (or a pair
//!   already closer than the minimum distance) is not checked: no motion
//!   from that start keeps it (give another start pose); such frames and
//!   pairs are listed ([`Minimum::exempt`]).

use nalgebra::{SVector, Vector3};
use serde::Serialize;

use super::Limits;
use crate::rng::Rng;
use dynamics_runtime::control::Reference;
use dynamics_runtime::Robot;

/// The clearances a designed motion keeps, m.
///
/// ```
/// use dynamics_sim2real::excite::Clearance;
/// let c = Clearance::default();
/// assert_eq!((c.ground, c.distance), (0.05, 0.05));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Clearance {
    /// Least height of a moving frame's origin above the ground, m.
    pub ground: f64,
    /// Least distance between the origins of two frames the joints can
    /// bring together, m.
    pub distance: f64,
}

impl Default for Clearance {
    fn default() -> Self {
        Clearance {
            ground: 0.05,
            distance: 0.05,
        }
    }
}

/// The frames and pairs of a robot a [`Clearance`] applies to, with each
/// one's threshold (see the module docs).
///
/// ```
/// use dynamics_sim2real::excite::{Clearance, Clearances, Limits};
/// use dynamics_runtime::control::Reference;
/// dynamics_macros::robot! {
///     pub robot TwoLink;
///     gravity = [0.0, 0.0, -9.81];
///     link base;
///     link l1 { mass = 1.0; com = [0.5, 0.0, 0.0]; }
///     link l2 { mass = 1.0; com = [0.5, 0.0, 0.0]; }
///     joint j1 = revolute(base -> l1) { transfer = [trans_z(0.3), rot_y(q)]; }
///     joint j2 = revolute(l1 -> l2) { transfer = [trans_z(0.5), rot_y(q)]; }
/// }
/// let arm = TwoLink::default();
/// let limits = Limits::<2>::new([-1.0, -1.0], [1.0, 1.0], [2.0, 2.0], [60.0, 30.0]);
/// let c = Clearances::of(&arm, &limits, &[0.0, 0.0].into(), &Clearance::default());
/// let at = |q: [f64; 2]| Reference { q: q.into(), qd: Default::default(), qdd: Default::default() };
/// let m = c.minimum(&arm, &[at([0.0, 0.0])]);
/// assert!(m.ground.is_some() && c.keeps(&arm, &[at([0.0, 0.0])]));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Clearances {
    /// The clearance asked.
    pub asked: Clearance,
    /// Unit vector up (against gravity); `None` without gravity.
    up: Option<Vector3<f64>>,
    /// Frames checked against the ground, with their least height.
    ground: Vec<(usize, f64)>,
    /// Pairs of frames checked against each other, with their least
    /// distance.
    pairs: Vec<(usize, usize, f64)>,
    /// Frames and pairs not checked because the start pose already breaks
    /// the clearance.
    exempt: Vec<String>,
}

/// The smallest clearances along a motion, and where.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Minimum {
    /// Least height of a checked frame's origin above the ground, m
    /// (`None`: no frame checked).
    pub ground: Option<f64>,
    /// The frame where it is.
    pub lowest: Option<String>,
    /// Least distance between a checked pair's origins, m (`None`: no pair
    /// checked).
    pub distance: Option<f64>,
    /// The pair where it is.
    pub closest: Option<[String; 2]>,
    /// Frames checked against the ground.
    pub frames: usize,
    /// Pairs checked against each other.
    pub pairs: usize,
    /// Frames (and pairs, `a - b`) not checked: the start pose already
    /// breaks the clearance there.
    pub exempt: Vec<String>,
}

/// A figure of the frames' origins in one state (`None`: a frame missing).
type Figure<'a> = &'a dyn Fn(&[Option<Vector3<f64>>]) -> Option<f64>;

fn origin<R: Robot<N>, const N: usize>(
    robot: &R,
    i: usize,
    q: &SVector<f64, N>,
) -> Option<Vector3<f64>> {
    robot
        .frame_pose(i, q)
        .map(|m| Vector3::new(m[(0, 3)], m[(1, 3)], m[(2, 3)]))
}

impl Clearances {
    /// The frames and pairs of `robot` to check (over 64 random states
    /// within `limits`, see the module docs) and their thresholds from
    /// `clearance` and the start pose `q0`.
    pub fn of<R: Robot<N>, const N: usize>(
        robot: &R,
        limits: &Limits<N>,
        q0: &SVector<f64, N>,
        clearance: &Clearance,
    ) -> Self {
        let g = Vector3::from(R::GRAVITY);
        let up = (g.norm() > 0.0).then(|| -g / g.norm());
        let frames = R::FRAME_NAMES.len();
        let mut rng = Rng::new(0x0C1E_A4A7);
        let states: Vec<SVector<f64, N>> = (0..64)
            .map(|_| {
                SVector::from_fn(|j, _| {
                    let (lo, hi) = (limits.lower[j], limits.upper[j]);
                    if lo.is_finite() && hi.is_finite() {
                        rng.uniform(lo, hi)
                    } else {
                        q0[j] + rng.uniform(-1.0, 1.0)
                    }
                })
            })
            .collect();
        let points: Vec<Vec<Option<Vector3<f64>>>> = states
            .iter()
            .map(|q| (0..frames).map(|i| origin(robot, i, q)).collect())
            .collect();
        let start: Vec<Option<Vector3<f64>>> = (0..frames).map(|i| origin(robot, i, q0)).collect();
        let spread = |f: Figure| -> Option<f64> {
            let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
            for p in &points {
                let v = f(p)?;
                lo = lo.min(v);
                hi = hi.max(v);
            }
            Some(hi - lo)
        };
        const STILL: f64 = 1e-9;
        let moving: Vec<usize> = (0..frames)
            .filter(|&i| {
                start[i].is_some()
                    && [0, 1, 2].iter().any(|&k| {
                        spread(&|p: &[Option<Vector3<f64>>]| p[i].map(|v| v[k]))
                            .is_some_and(|s| s > STILL)
                    })
            })
            .collect();
        let mut exempt = Vec::new();
        let mut ground = Vec::new();
        if let Some(u) = up {
            for &i in &moving {
                match start[i].map(|p| p.dot(&u)) {
                    Some(h) if h >= clearance.ground => ground.push((i, clearance.ground)),
                    _ => exempt.push(R::FRAME_NAMES[i].to_string()),
                }
            }
        }
        let mut pairs = Vec::new();
        for a in 0..frames {
            for b in a + 1..frames {
                let d = |p: &[Option<Vector3<f64>>]| Some((p[a]? - p[b]?).norm());
                if spread(&d).is_some_and(|s| s > 1e-6) {
                    match d(&start) {
                        Some(d0) if d0 >= clearance.distance => {
                            pairs.push((a, b, clearance.distance))
                        }
                        _ => exempt.push(format!("{} - {}", R::FRAME_NAMES[a], R::FRAME_NAMES[b])),
                    }
                }
            }
        }
        Clearances {
            asked: *clearance,
            up,
            ground,
            pairs,
            exempt,
        }
    }

    /// Whether every state keeps every checked frame above its least
    /// height and every checked pair apart by its least distance.
    pub fn keeps<R: Robot<N>, const N: usize>(&self, robot: &R, states: &[Reference<N>]) -> bool {
        states.iter().all(|s| self.keeps_at(robot, &s.q))
    }

    fn keeps_at<R: Robot<N>, const N: usize>(&self, robot: &R, q: &SVector<f64, N>) -> bool {
        let p: Vec<Option<Vector3<f64>>> = (0..R::FRAME_NAMES.len())
            .map(|i| origin(robot, i, q))
            .collect();
        let high = match self.up {
            Some(u) => self
                .ground
                .iter()
                .all(|&(i, h)| p[i].is_some_and(|v| v.dot(&u) >= h)),
            None => true,
        };
        high && self.pairs.iter().all(|&(a, b, d)| match (p[a], p[b]) {
            (Some(x), Some(y)) => (x - y).norm() >= d,
            _ => false,
        })
    }

    /// The smallest height and distance along `states`, and where.
    pub fn minimum<R: Robot<N>, const N: usize>(
        &self,
        robot: &R,
        states: &[Reference<N>],
    ) -> Minimum {
        let mut m = Minimum {
            ground: None,
            lowest: None,
            distance: None,
            closest: None,
            frames: if self.up.is_some() {
                self.ground.len()
            } else {
                0
            },
            pairs: self.pairs.len(),
            exempt: self.exempt.clone(),
        };
        let name = |i: usize| R::FRAME_NAMES[i].to_string();
        for s in states {
            let p: Vec<Option<Vector3<f64>>> = (0..R::FRAME_NAMES.len())
                .map(|i| origin(robot, i, &s.q))
                .collect();
            if let Some(u) = self.up {
                for &(i, _) in &self.ground {
                    if let Some(h) = p[i].map(|v| v.dot(&u)) {
                        if m.ground.is_none_or(|g| h < g) {
                            m.ground = Some(h);
                            m.lowest = Some(name(i));
                        }
                    }
                }
            }
            for &(a, b, _) in &self.pairs {
                if let (Some(x), Some(y)) = (p[a], p[b]) {
                    let d = (x - y).norm();
                    if m.distance.is_none_or(|v| d < v) {
                        m.distance = Some(d);
                        m.closest = Some([name(a), name(b)]);
                    }
                }
            }
        }
        m
    }
}
