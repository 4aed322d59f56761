//! The plant's total mechanical energy, for energy-balance tests.

use nalgebra::Vector3;

use super::{Plant, PlantState};
use crate::effects::Effect;
use dynamics_runtime::Robot;

impl<R: Robot<N>, const N: usize> Plant<R, N> {
    /// Total mechanical energy: the robot's, the payload's, the rotors',
    /// the changed links' and the drive springs' (for energy-balance tests).
    pub fn energy(&self, x: &PlantState<N>, contact: &[i8; N]) -> f64 {
        let mut e = self.robot.total_energy(&x.q, &x.qd);
        for eff in &self.effects {
            match *eff {
                Effect::Armature { joint, inertia } => e += 0.5 * inertia * x.qd[joint].powi(2),
                Effect::InertialParameters { link, ref delta } => {
                    e += crate::effects::inertial::energy(&self.robot, link, delta, &x.q, &x.qd)
                }
                Effect::PayloadMass { mass, com } => {
                    let (p, jac) =
                        self.tip
                            .position_jacobian_at(&self.robot, &x.q, &Vector3::from(com));
                    let g = Vector3::from(R::GRAVITY);
                    e += 0.5 * mass * (jac * x.qd).norm_squared() - mass * g.dot(&p);
                }
                Effect::JointElasticity {
                    joint,
                    stiffness,
                    motor_inertia,
                    ..
                } => {
                    e += 0.5 * motor_inertia * x.qmd[joint].powi(2)
                        + 0.5 * stiffness * (x.qm[joint] - x.q[joint]).powi(2)
                }
                Effect::Backlash {
                    joint,
                    half_width,
                    motor_inertia,
                    contact_stiffness,
                    ..
                } => {
                    let d = x.qm[joint] - x.q[joint];
                    let pen = match contact[joint] {
                        1 => d - half_width,
                        -1 => d + half_width,
                        _ => 0.0,
                    };
                    e += 0.5 * motor_inertia * x.qmd[joint].powi(2)
                        + 0.5 * contact_stiffness * pen * pen
                }
                _ => {}
            }
        }
        e
    }
}
