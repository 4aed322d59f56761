//! The robot's tip: where payload and environment effects act.

use nalgebra::{SMatrix, SVector, Vector3};

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
        match *self {
            Tip::Point(i) => robot.point_position(i, q),
            Tip::Frame(i) => robot
                .frame_pose(i, q)
                .map(|m| Vector3::new(m[(0, 3)], m[(1, 3)], m[(2, 3)])),
        }
        .unwrap_or_else(Vector3::zeros)
    }

    /// World position and its Jacobian d(position)/dq.
    pub fn position_jacobian<R: Robot<N>, const N: usize>(
        &self,
        robot: &R,
        q: &SVector<f64, N>,
    ) -> (Vector3<f64>, SMatrix<f64, 3, N>) {
        let x = self.position(robot, q);
        if let Tip::Point(i) = *self {
            if let Some(j) = robot.point_jacobian(i, q) {
                return (x, j);
            }
        }
        let mut jac = SMatrix::<f64, 3, N>::zeros();
        for k in 0..N {
            let h = 1e-6 * (1.0 + q[k].abs());
            let mut qp = *q;
            let mut qm = *q;
            qp[k] += h;
            qm[k] -= h;
            let d = (self.position(robot, &qp) - self.position(robot, &qm)) / (2.0 * h);
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
        let norm = qd.norm();
        if norm == 0.0 {
            return Vector3::zeros();
        }
        let h = 1e-5 / norm;
        let (_, jp) = self.position_jacobian(robot, &(q + qd * h));
        let (_, jm) = self.position_jacobian(robot, &(q - qd * h));
        (jp - jm) * qd / (2.0 * h)
    }
}
