//! The robot's tip: where payload and environment effects act.

use nalgebra::{Matrix3, Matrix4, SMatrix, SVector, Vector3};

use dynamics_runtime::Robot;

/// The tip of a robot: its last named point, or, when it has none, the
/// origin of its tool frame: the last frame named as ROS names a flange or
/// tool frame (REP 199: `tool0`, `flange`; also `..._flange`, `..._tcp`,
/// `ee_link`), else its last frame (Jacobian by central differences
/// then). A URDF's frames come in the file's order, where a fixed frame
/// near the base (UR's `base`) can come last: the names keep the payload
/// at the flange.
///
/// ```
/// use dynamics_sim2real::effects::Tip;
/// dynamics_macros::robot! {
///     pub robot Pendulum;
///     gravity = [0.0, -9.81, 0.0];
///     link base;
///     link rod { mass = 1.0; com = [1.0, 0.0, 0.0]; point end = [2.0, 0.0, 0.0]; }
///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
/// }
/// let p = Pendulum::default();
/// let q = nalgebra::Vector1::new(0.0);
/// let (x, jac) = Tip::of::<Pendulum, 1>().position_jacobian(&p, &q);
/// assert!((x - nalgebra::Vector3::new(2.0, 0.0, 0.0)).norm() < 1e-12);
/// assert!((jac[(1, 0)] - 2.0).abs() < 1e-12);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Tip {
    /// Named point `index`.
    Point(usize),
    /// Origin of frame `index`.
    Frame(usize),
}

impl Tip {
    /// The tip of robot type `R`.
    pub fn of<R: Robot<N>, const N: usize>() -> Tip {
        if R::POINT_NAMES.is_empty() {
            let tool = |name: &str| {
                let n = name.to_ascii_lowercase();
                n == "tool0"
                    || n == "flange"
                    || n == "ee_link"
                    || n == "tcp"
                    || n.ends_with("_flange")
                    || n.ends_with("_tcp")
            };
            let last = R::FRAME_NAMES.len().saturating_sub(1);
            Tip::Frame(R::FRAME_NAMES.iter().rposition(|n| tool(n)).unwrap_or(last))
        } else {
            Tip::Point(R::POINT_NAMES.len() - 1)
        }
    }

    /// The modelled mass of the body that carries the tip: the last link
    /// of `Robot::LINK_NAMES` (the distal link of a serial chain, with
    /// every body welded to it on fixed joints: a hand, a flange, a tool),
    /// 0 when the robot lists no link. A payload relative to the model may
    /// take away no more than this ([`crate::effects::Effect::within_tip_body`]):
    /// beyond it the tip body would have negative mass.
    ///
    /// ```
    /// use dynamics_sim2real::effects::Tip;
    /// dynamics_macros::robot! {
    ///     pub robot Pendulum;
    ///     gravity = [0.0, -9.81, 0.0];
    ///     link base;
    ///     link rod { mass = 1.5; com = [1.0, 0.0, 0.0]; inertia = [1e-4, 0.1, 0.1]; }
    ///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
    /// }
    /// assert!((Tip::body_mass::<Pendulum, 1>(&Pendulum::default()) - 1.5).abs() < 1e-12);
    /// ```
    pub fn body_mass<R: Robot<N>, const N: usize>(robot: &R) -> f64 {
        let mut pi = vec![nalgebra::SVector::<f64, 10>::zeros(); R::LINK_NAMES.len()];
        match (robot.inertial_parameters(&mut pi), pi.last()) {
            (Ok(()), Some(p)) if p[0].is_finite() => p[0].max(0.0),
            _ => 0.0,
        }
    }

    /// Its name (point or frame name).
    pub fn name<R: Robot<N>, const N: usize>(&self) -> &'static str {
        match *self {
            Tip::Point(i) => R::POINT_NAMES.get(i).copied().unwrap_or("tip"),
            Tip::Frame(i) => R::FRAME_NAMES.get(i).copied().unwrap_or("tip"),
        }
    }

    /// World position.
    pub fn position<R: Robot<N>, const N: usize>(
        &self,
        robot: &R,
        q: &SVector<f64, N>,
    ) -> Vector3<f64> {
        self.position_at(robot, q, &Vector3::zeros())
    }

    /// World position of the point at `offset` in the tip's frame (a
    /// frame tip; a point tip has no frame, and the offset is ignored).
    pub fn position_at<R: Robot<N>, const N: usize>(
        &self,
        robot: &R,
        q: &SVector<f64, N>,
        offset: &Vector3<f64>,
    ) -> Vector3<f64> {
        match *self {
            Tip::Point(i) => robot.point_position(i, q),
            Tip::Frame(i) => robot.frame_pose(i, q).map(|m| pose_position(&m, offset)),
        }
        .unwrap_or_else(Vector3::zeros)
    }

    /// World position and its Jacobian d(position)/dq.
    pub fn position_jacobian<R: Robot<N>, const N: usize>(
        &self,
        robot: &R,
        q: &SVector<f64, N>,
    ) -> (Vector3<f64>, SMatrix<f64, 3, N>) {
        self.position_jacobian_at(robot, q, &Vector3::zeros())
    }

    /// [`Tip::position_at`] and its Jacobian d(position)/dq (by central
    /// differences, except at a point tip whose Jacobian the robot gives).
    pub fn position_jacobian_at<R: Robot<N>, const N: usize>(
        &self,
        robot: &R,
        q: &SVector<f64, N>,
        offset: &Vector3<f64>,
    ) -> (Vector3<f64>, SMatrix<f64, 3, N>) {
        let x = self.position_at(robot, q, offset);
        if let Tip::Point(i) = *self {
            if let Some(j) = robot.point_jacobian(i, q) {
                return (x, j);
            }
        }
        let mut jac = SMatrix::<f64, 3, N>::zeros();
        for k in 0..N {
            let (qp, qm, h) = super::central_step(q, k);
            let d = (self.position_at(robot, &qp, offset) - self.position_at(robot, &qm, offset))
                / (2.0 * h);
            jac.set_column(k, &d);
        }
        (x, jac)
    }

    /// `Jd qd`, the velocity-product part of the tip acceleration
    /// (`a = J qdd + Jd qd`), by a central difference of `J qd` along qd.
    pub fn bias_acceleration<R: Robot<N>, const N: usize>(
        &self,
        robot: &R,
        q: &SVector<f64, N>,
        qd: &SVector<f64, N>,
    ) -> Vector3<f64> {
        self.bias_acceleration_at(robot, q, qd, &Vector3::zeros())
    }

    /// [`Tip::bias_acceleration`] of the point at `offset` in the tip's
    /// frame.
    pub fn bias_acceleration_at<R: Robot<N>, const N: usize>(
        &self,
        robot: &R,
        q: &SVector<f64, N>,
        qd: &SVector<f64, N>,
        offset: &Vector3<f64>,
    ) -> Vector3<f64> {
        let norm = qd.norm();
        if norm == 0.0 {
            return Vector3::zeros();
        }
        let h = 1e-5 / norm;
        let (_, jp) = self.position_jacobian_at(robot, &(q + qd * h), offset);
        let (_, jm) = self.position_jacobian_at(robot, &(q - qd * h), offset);
        (jp - jm) * qd / (2.0 * h)
    }

    /// A frame tip's position Jacobian, acceleration `J qdd + Jd qd`,
    /// orientation, angular-velocity Jacobian and angular acceleration
    /// `J_w qdd + Jd_w qd` at one state: the values of
    /// [`Tip::position_jacobian`], [`Tip::bias_acceleration`],
    /// [`Tip::angular_jacobian`] and [`Tip::angular_bias`] to the bit (the
    /// same operations), the position's and the orientation's central
    /// differences sharing each pose they both read (half the poses of
    /// the four on their own). `None` for a point tip.
    pub(crate) fn frame_motion<R: Robot<N>, const N: usize>(
        &self,
        robot: &R,
        q: &SVector<f64, N>,
        qd: &SVector<f64, N>,
        qdd: &SVector<f64, N>,
    ) -> Option<FrameMotion<N>> {
        let Tip::Frame(i) = *self else { return None };
        let (jac, rotation) = frame_jacobians(robot, i, q);
        let norm = qd.norm();
        let (bias, angular_bias) = if norm == 0.0 {
            (Vector3::zeros(), Vector3::zeros())
        } else {
            let h = 1e-5 / norm;
            let (jp, rp) = frame_jacobians(robot, i, &(q + qd * h));
            let (jm, rm) = frame_jacobians(robot, i, &(q - qd * h));
            let bias = (jp - jm) * qd / (2.0 * h);
            let angular = match (rp, rm) {
                (Some((_, wp)), Some((_, wm))) => (wp - wm) * qd / (2.0 * h),
                _ => Vector3::zeros(),
            };
            (bias, angular)
        };
        let alpha = match rotation {
            Some((_, jw)) => jw * *qdd + angular_bias,
            None => Vector3::zeros(),
        };
        Some(FrameMotion {
            jac,
            acc: jac * *qdd + bias,
            rotation,
            alpha,
        })
    }

    /// The tip frame's orientation R (world from tip) and its angular
    /// velocity Jacobian (world axes, `omega = J_w qd`), by central
    /// differences of R: `dR/dq_k R^T` is the skew matrix of column k.
    /// `None` for a point tip (no frame).
    ///
    /// ```
    /// use dynamics_sim2real::effects::Tip;
    /// dynamics_macros::robot! {
    ///     pub robot Pendulum;
    ///     gravity = [0.0, -9.81, 0.0];
    ///     link base;
    ///     link rod { mass = 1.0; com = [1.0, 0.0, 0.0]; }
    ///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
    /// }
    /// let p = Pendulum::default();
    /// let q = nalgebra::Vector1::new(0.3);
    /// let (_, jw) = Tip::Frame(Pendulum::FRAME_NAMES.len() - 1)
    ///     .angular_jacobian(&p, &q)
    ///     .unwrap();
    /// assert!((jw[(2, 0)] - 1.0).abs() < 1e-8 && jw[(0, 0)].abs() < 1e-8);
    /// # use dynamics_runtime::Robot;
    /// ```
    pub fn angular_jacobian<R: Robot<N>, const N: usize>(
        &self,
        robot: &R,
        q: &SVector<f64, N>,
    ) -> Option<(Matrix3<f64>, SMatrix<f64, 3, N>)> {
        let Tip::Frame(i) = *self else { return None };
        let rot = |q: &SVector<f64, N>| -> Option<Matrix3<f64>> {
            robot
                .frame_pose(i, q)
                .map(|m| m.fixed_view::<3, 3>(0, 0).into_owned())
        };
        let r = rot(q)?;
        let mut jac = SMatrix::<f64, 3, N>::zeros();
        for k in 0..N {
            let (qp, qm, h) = super::central_step(q, k);
            let w = (rot(&qp)? - rot(&qm)?) / (2.0 * h) * r.transpose();
            let w = 0.5 * (w - w.transpose());
            jac.set_column(k, &Vector3::new(w[(2, 1)], w[(0, 2)], w[(1, 0)]));
        }
        Some((r, jac))
    }

    /// `Jd_w qd`, the velocity-product part of the tip frame's angular
    /// acceleration, by a central difference of `J_w qd` along qd (zero
    /// for a point tip).
    pub fn angular_bias<R: Robot<N>, const N: usize>(
        &self,
        robot: &R,
        q: &SVector<f64, N>,
        qd: &SVector<f64, N>,
    ) -> Vector3<f64> {
        let norm = qd.norm();
        if norm == 0.0 {
            return Vector3::zeros();
        }
        let h = 1e-5 / norm;
        match (
            self.angular_jacobian(robot, &(q + qd * h)),
            self.angular_jacobian(robot, &(q - qd * h)),
        ) {
            (Some((_, jp)), Some((_, jm))) => (jp - jm) * qd / (2.0 * h),
            _ => Vector3::zeros(),
        }
    }
}

/// World position of the point at `offset` in the frame of pose `m`.
fn pose_position(m: &Matrix4<f64>, offset: &Vector3<f64>) -> Vector3<f64> {
    Vector3::new(m[(0, 3)], m[(1, 3)], m[(2, 3)]) + m.fixed_view::<3, 3>(0, 0) * offset
}

/// The orientation (world from frame) of pose `m`.
fn pose_rotation(m: &Matrix4<f64>) -> Matrix3<f64> {
    m.fixed_view::<3, 3>(0, 0).into_owned()
}

/// A frame tip's motion at one state ([`Tip::frame_motion`]).
#[derive(Debug, Clone, Copy)]
pub(crate) struct FrameMotion<const N: usize> {
    /// Position Jacobian ([`Tip::position_jacobian`]).
    pub jac: SMatrix<f64, 3, N>,
    /// `J qdd + Jd qd` ([`Tip::bias_acceleration`] added).
    pub acc: Vector3<f64>,
    /// Orientation and angular-velocity Jacobian ([`Tip::angular_jacobian`]).
    pub rotation: Option<(Matrix3<f64>, SMatrix<f64, 3, N>)>,
    /// `J_w qdd + Jd_w qd` ([`Tip::angular_bias`] added; zero bias when
    /// the orientation is not given at the bias's states).
    pub alpha: Vector3<f64>,
}

/// Frame `i`'s position Jacobian and (when every pose is given) its
/// orientation and angular-velocity Jacobian at `q`: what
/// [`Tip::position_jacobian`] and [`Tip::angular_jacobian`] compute, with
/// each of the `2N + 1` poses both read evaluated once.
#[allow(clippy::type_complexity)]
fn frame_jacobians<R: Robot<N>, const N: usize>(
    robot: &R,
    i: usize,
    q: &SVector<f64, N>,
) -> (
    SMatrix<f64, 3, N>,
    Option<(Matrix3<f64>, SMatrix<f64, 3, N>)>,
) {
    let position = |m: &Option<Matrix4<f64>>| {
        m.map(|m| pose_position(&m, &Vector3::zeros()))
            .unwrap_or_else(Vector3::zeros)
    };
    let r = robot.frame_pose(i, q).map(|m| pose_rotation(&m));
    let mut jac = SMatrix::<f64, 3, N>::zeros();
    let mut jac_w = r.map(|_| SMatrix::<f64, 3, N>::zeros());
    for k in 0..N {
        let (qp, qm, h) = super::central_step(q, k);
        let (mp, mm) = (robot.frame_pose(i, &qp), robot.frame_pose(i, &qm));
        let d = (position(&mp) - position(&mm)) / (2.0 * h);
        jac.set_column(k, &d);
        jac_w = match (jac_w, r, mp, mm) {
            (Some(mut jw), Some(r), Some(mp), Some(mm)) => {
                let w = (pose_rotation(&mp) - pose_rotation(&mm)) / (2.0 * h) * r.transpose();
                let w = 0.5 * (w - w.transpose());
                jw.set_column(k, &Vector3::new(w[(2, 1)], w[(0, 2)], w[(1, 0)]));
                Some(jw)
            }
            _ => None,
        };
    }
    (jac, r.zip(jac_w))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_robots::Arm2;

    fn same<const R: usize, const C: usize>(
        a: &SMatrix<f64, R, C>,
        b: &SMatrix<f64, R, C>,
    ) -> bool {
        a.iter()
            .zip(b.iter())
            .all(|(x, y)| x.to_bits() == y.to_bits())
    }

    /// The frame tip's motion with its poses shared is the four
    /// functions' to the bit, at rest and moving; a point tip has none.
    #[test]
    fn a_frame_tips_motion_is_the_four_functions_to_the_bit() {
        let robot = Arm2::default();
        let tip = Tip::of::<Arm2, 2>();
        assert!(matches!(tip, Tip::Frame(_)));
        let states = [
            ([0.3, -1.1], [0.0, 0.0], [0.4, -2.0]),
            ([0.3, -1.1], [1.7, -0.6], [0.4, -2.0]),
            ([-2.5, 0.01], [-0.02, 3.3], [-5.0, 0.7]),
        ];
        for (q, qd, qdd) in states {
            let (q, qd, qdd) = (
                SVector::<f64, 2>::from(q),
                SVector::<f64, 2>::from(qd),
                SVector::<f64, 2>::from(qdd),
            );
            let m = tip
                .frame_motion(&robot, &q, &qd, &qdd)
                .expect("a frame tip");
            let (_, jac) = tip.position_jacobian(&robot, &q);
            let acc = jac * qdd + tip.bias_acceleration(&robot, &q, &qd);
            let (rot, jac_w) = tip.angular_jacobian(&robot, &q).expect("a frame");
            let alpha = jac_w * qdd + tip.angular_bias(&robot, &q, &qd);
            let (mrot, mjac_w) = m.rotation.expect("an orientation");
            assert!(same(&m.jac, &jac) && same(&m.acc, &acc), "{q:?} {qd:?}");
            assert!(same(&mrot, &rot) && same(&mjac_w, &jac_w), "{q:?} {qd:?}");
            assert!(same(&m.alpha, &alpha), "{q:?} {qd:?}");
            assert!(m.acc.norm() > 0.0 && m.alpha.norm() > 0.0);
        }
        let zero = SVector::<f64, 2>::zeros();
        assert!(Tip::Point(0)
            .frame_motion(&robot, &zero, &zero, &zero)
            .is_none());
    }
}
