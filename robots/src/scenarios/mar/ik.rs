//! Inverse kinematics of the MAR's second step of motion (vibration paper, Fig. 4):
//! q1 stays fixed, q2 and q3 place the gripper on the flat path.
//!
//! In the plane of links 2 and 3 (link 1's x-y plane) the gripper sits at
//! `P = (0, L1) + Rot(q2) (r, L2)` with `r = q3 + S3 + L3/2` (the slide
//! offset plus the gripper's distance along link 3, `mar.rs`). So
//! `r = sqrt(|P - (0, L1)|^2 - L2^2)` and `q2 = atan2(P - (0, L1)) -
//! atan2(L2, r)`. Velocities and accelerations come from the 2x2 Jacobian
//! `J = [Rot'(q2) (r, L2), Rot(q2) (1, 0)]` (det J = -r) and its time
//! derivative.

use nalgebra::{Matrix2, Vector2, Vector3};
use thiserror::Error;

use super::path::{PathPoint, L, R};

/// Height of joint 2 above joint 1, m (`mar.rs` L1).
pub const L1: f64 = 0.15;
/// Offset of the slide from joint 2's axis, m (`mar.rs` L2).
pub const L2: f64 = 0.18;
/// Distance from the slide origin to the gripper, m (S3 + L3 / 2).
pub const GRIPPER: f64 = 0.18 + 0.21;
/// Where the path's origin O1 lies in link 1's plane, m: the portal is
/// centred under joint 2, its pick and place points 0.55 m below joint 2's
/// axis, so the gripper hangs below the arm and q3 stays within 0.02..0.18 m.
pub const ORIGIN: Vector2<f64> = Vector2::new(-(L + 2.0 * R) / 2.0, L1 - 0.55);

/// Why a gripper position has no joint solution.
#[derive(Debug, Clone, Copy, PartialEq, Error)]
pub enum IkError {
    /// The point is closer to joint 2's axis than the slide's offset L2.
    #[error("gripper target ({x:.4}, {y:.4}) m in link 1's plane is within L2 = {L2} m of joint 2's axis: out of reach")]
    Unreachable {
        /// x in link 1's frame, m.
        x: f64,
        /// y in link 1's frame, m.
        y: f64,
    },
}

/// Joint positions, velocities and accelerations of the nominal motion.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointMotion {
    /// q (q1 fixed), rad, rad, m.
    pub q: Vector3<f64>,
    /// qd.
    pub qd: Vector3<f64>,
    /// qdd.
    pub qdd: Vector3<f64>,
}

/// A path point (local frame X1 Y1 O1) in link 1's frame.
///
/// ```
/// use robots::scenarios::mar::ik::{in_link1, ORIGIN};
/// assert_eq!(in_link1(&nalgebra::Vector2::zeros()), ORIGIN);
/// ```
pub fn in_link1(p: &Vector2<f64>) -> Vector2<f64> {
    ORIGIN + p
}

/// q2, q3 and their rates putting the gripper at `pt`, q1 held at `q1`.
///
/// ```
/// use robots::scenarios::mar::{ik, path};
/// let m = ik::joints(0.0, &path::at(0.0)).unwrap();
/// assert!(m.qd.norm() == 0.0 && m.q[2] > 0.0 && m.q[2] < 0.4);
/// ```
pub fn joints(q1: f64, pt: &PathPoint) -> Result<JointMotion, IkError> {
    let w = in_link1(&pt.p) - Vector2::new(0.0, L1);
    let rr = w.norm_squared() - L2 * L2;
    if rr.is_nan() || rr <= 0.0 {
        return Err(IkError::Unreachable {
            x: w.x,
            y: w.y + L1,
        });
    }
    let r = rr.sqrt();
    let q2 = w.y.atan2(w.x) - L2.atan2(r);
    let q3 = r - GRIPPER;
    let (s, c) = q2.sin_cos();
    let j = Matrix2::new(-r * s - L2 * c, c, r * c - L2 * s, s);
    let inv = Matrix2::new(s, -c, L2 * s - r * c, -r * s - L2 * c) / (-r);
    debug_assert!((inv * j - Matrix2::identity()).norm() < 1e-9);
    let rate = inv * pt.v;
    let (w2, v3) = (rate.x, rate.y);
    // dJ/dt qd: the centripetal and Coriolis parts of the gripper acceleration.
    let bias = Vector2::new(
        -2.0 * w2 * v3 * s - w2 * w2 * (r * c - L2 * s),
        2.0 * w2 * v3 * c - w2 * w2 * (r * s + L2 * c),
    );
    let acc = inv * (pt.a - bias);
    Ok(JointMotion {
        q: Vector3::new(q1, q2, q3),
        qd: Vector3::new(0.0, w2, v3),
        qdd: Vector3::new(0.0, acc.x, acc.y),
    })
}
