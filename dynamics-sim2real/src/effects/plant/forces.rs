//! The plant's equations of motion: the link-side inertia and forces with
//! every effect added, and the motor sides driven through their elastic or
//! backlash coupling.

use nalgebra::{SMatrix, SVector, Vector3};

use super::{Plant, PlantState};
use crate::effects::Effect;
use dynamics_runtime::{DynamicsError, Robot};

impl<R: Robot<N>, const N: usize> Plant<R, N> {
    /// The time derivative of the state under drive efforts `tau` (applied
    /// to the motor side of motor joints, to the link elsewhere).
    pub fn derivative(
        &self,
        x: &PlantState<N>,
        tau: &SVector<f64, N>,
        contact: &[i8; N],
    ) -> Result<PlantState<N>, DynamicsError> {
        let (a, f) = self.mass_and_forces(&x.q, &x.qd);
        let mut u = *tau;
        let mut qmdd = SVector::<f64, N>::zeros();
        for j in 0..N {
            let Some(k) = self.motor[j] else { continue };
            let e = &self.effects[k];
            let passed = e.transmitted(x.qm[j] - x.q[j], x.qmd[j] - x.qd[j], contact[j]);
            let jm = match *e {
                Effect::JointElasticity { motor_inertia, .. }
                | Effect::Backlash { motor_inertia, .. } => motor_inertia,
                _ => 1.0,
            };
            u[j] = passed;
            qmdd[j] = (tau[j] - passed) / jm;
        }
        let chol = a
            .cholesky()
            .ok_or_else(|| DynamicsError::SingularMassMatrix {
                q: dynamics_runtime::Coordinates::new(x.q.as_slice()),
            })?;
        let qdd = chol.solve(&(f + u));
        if let Some(index) = qdd.iter().position(|v| !v.is_finite()) {
            return Err(DynamicsError::Diverged {
                quantity: "qdd",
                index,
            });
        }
        Ok(PlantState {
            q: x.qd,
            qd: qdd,
            qm: x.qmd,
            qmd: qmdd,
        })
    }

    /// The link-side inertia (robot + armature + payload + changed link
    /// inertials) and the forces other than the drive: Q(0), Qqt1, Qqt2,
    /// friction, the payload's and changed links' gravity and velocity
    /// terms, environment resistance.
    pub fn mass_and_forces(
        &self,
        q: &SVector<f64, N>,
        qd: &SVector<f64, N>,
    ) -> (SMatrix<f64, N, N>, SVector<f64, N>) {
        let terms = self.robot.motion_terms(q, qd);
        let mut a = terms.a;
        let mut f = terms.bias();
        for e in &self.effects {
            match *e {
                Effect::CoulombFriction { joint, .. }
                | Effect::ViscousFriction { joint, .. }
                | Effect::StribeckFriction { joint, .. } => f[joint] += e.joint_force(qd[joint]),
                Effect::Armature { joint, inertia } => a[(joint, joint)] += inertia,
                Effect::JointSpring {
                    joint,
                    stiffness,
                    preload,
                } => f[joint] -= stiffness * q[joint] + preload,
                Effect::PayloadMass { mass, com } => {
                    let c = Vector3::from(com);
                    let (_, jac) = self.tip.position_jacobian_at(&self.robot, q, &c);
                    let bias = self.tip.bias_acceleration_at(&self.robot, q, qd, &c);
                    let g = Vector3::from(R::GRAVITY);
                    a += jac.transpose() * jac * mass;
                    f += jac.transpose() * ((g - bias) * mass);
                }
                Effect::InertialParameters { link, ref delta } => {
                    let (da, df) = crate::effects::inertial::terms(&self.robot, link, delta, q, qd);
                    a += da;
                    f += df;
                }
                Effect::EnvironmentResistance { .. } => {
                    let (_, jac) = self.tip.position_jacobian(&self.robot, q);
                    f += jac.transpose() * e.resistance(&(jac * qd));
                }
                _ => {}
            }
        }
        (a, f)
    }
}
