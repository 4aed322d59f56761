//! A robot with known effects folded into its nominal model: what a
//! previous diagnosis found (a calibrated baseline), so that the next one
//! compares data against the calibrated robot and names only what changed.
//!
//! [`Calibrated`] implements [`Robot`] by adding the effects that act as
//! forces or inertia (friction laws, rotor inertia, a payload at the tip,
//! environment resistance) to every quantity of the wrapped model, the way
//! the plant adds them ([`crate::effects::Plant::mass_and_forces`]).
//! Effects with a state of their own (elasticity, backlash) or on the
//! sensors (encoder offset, delay) are not a nominal model's and are
//! refused.
//!
//! Here: the folding (which effects, what they add at a state); the
//! [`Robot`] implementation in `robot.rs`.

mod robot;
#[cfg(test)]
mod tests;

use nalgebra::{SMatrix, SVector, Vector3};

use super::{Effect, EffectKind, Tip};
use dynamics_runtime::Robot;

/// Why effects cannot be folded into a nominal model.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CalibratedError {
    /// An effect that is not a force or inertia.
    #[error("effect `{kind}` cannot be part of a nominal model (kinds that can: coulomb_friction, viscous_friction, stribeck_friction, armature, payload_mass, environment_resistance)")]
    NotNominal {
        /// Its kind's name.
        kind: &'static str,
    },
    /// An effect on a joint the robot does not have.
    #[error("effect `{kind}` at joint index {joint}: the robot has {n} joints")]
    Joint {
        /// Its kind's name.
        kind: &'static str,
        /// The joint index.
        joint: usize,
        /// The robot's joint count.
        n: usize,
    },
    /// An unphysical parameter.
    #[error("effect `{kind}`: {reason}")]
    Invalid {
        /// Its kind's name.
        kind: &'static str,
        /// What is wrong.
        reason: String,
    },
}

/// `robot` with `effects` added to its nominal model.
///
/// ```
/// use dynamics_runtime::Robot;
/// use dynamics_sim2real::effects::{Calibrated, Effect};
/// dynamics_macros::robot! {
///     pub robot Pendulum; gravity = [0.0, -9.81, 0.0];
///     link base; link rod { mass = 1.0; com = [1.0, 0.0, 0.0]; }
///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
/// }
/// let friction = Effect::ViscousFriction { joint: 0, fv: 0.5 };
/// let r = Calibrated::new(Pendulum::default(), vec![friction]).unwrap();
/// let (q, qd, qdd) = (nalgebra::Vector1::new(0.0), nalgebra::Vector1::new(2.0), nalgebra::Vector1::new(0.0));
/// // m g l cos q to hold it, plus fv qd to overcome the friction:
/// assert!((r.inverse_dynamics(&q, &qd, &qdd)[0] - (9.81 + 1.0)).abs() < 1e-12);
/// ```
#[derive(Debug, Clone)]
pub struct Calibrated<R, const N: usize> {
    robot: R,
    effects: Vec<Effect>,
    tip: Tip,
}

/// What the effects add at one state: to A, to Q(0), to Qqt1 + Qqt2.
struct Extra<const N: usize> {
    a: SMatrix<f64, N, N>,
    q0: SVector<f64, N>,
    qqt: SVector<f64, N>,
}

impl<R: Robot<N>, const N: usize> Calibrated<R, N> {
    /// Folds `effects` into `robot`'s nominal model. A friction correction
    /// may take away friction the nominal model has (a URDF's `<dynamics
    /// damping friction>`), no more ([`Effect::within_nominal_friction`]).
    pub fn new(robot: R, effects: Vec<Effect>) -> Result<Self, CalibratedError> {
        let (coulomb, viscous) = super::nominal_friction(&robot, &SVector::zeros());
        for e in &effects {
            let kind = e.kind().name();
            match e.kind() {
                EffectKind::CoulombFriction
                | EffectKind::ViscousFriction
                | EffectKind::StribeckFriction
                | EffectKind::Armature
                | EffectKind::PayloadMass
                | EffectKind::EnvironmentResistance
                | EffectKind::JointSpring => {}
                _ => return Err(CalibratedError::NotNominal { kind }),
            }
            if let Some(joint) = e.joint().filter(|&j| j >= N) {
                return Err(CalibratedError::Joint { kind, joint, n: N });
            }
            e.validate_beside_friction(coulomb.as_slice(), viscous.as_slice())
                .map_err(|reason| CalibratedError::Invalid { kind, reason })?;
        }
        Ok(Calibrated {
            robot,
            effects,
            tip: Tip::of::<R, N>(),
        })
    }

    /// The wrapped nominal model.
    pub fn nominal(&self) -> &R {
        &self.robot
    }

    /// The effects folded in.
    pub fn effects(&self) -> &[Effect] {
        &self.effects
    }

    fn extra(&self, q: &SVector<f64, N>, qd: &SVector<f64, N>) -> Extra<N> {
        let mut x = Extra {
            a: SMatrix::zeros(),
            q0: SVector::zeros(),
            qqt: SVector::zeros(),
        };
        for e in &self.effects {
            match *e {
                Effect::CoulombFriction { joint, .. }
                | Effect::ViscousFriction { joint, .. }
                | Effect::StribeckFriction { joint, .. } => x.q0[joint] += e.joint_force(qd[joint]),
                Effect::Armature { joint, inertia } => x.a[(joint, joint)] += inertia,
                Effect::JointSpring {
                    joint,
                    stiffness,
                    preload,
                } => x.q0[joint] -= stiffness * q[joint] + preload,
                Effect::PayloadMass { mass } => {
                    let (_, jac) = self.tip.position_jacobian(&self.robot, q);
                    let bias = self.tip.bias_acceleration(&self.robot, q, qd);
                    x.a += jac.transpose() * jac * mass;
                    x.q0 += jac.transpose() * (Vector3::from(R::GRAVITY) * mass);
                    x.qqt -= jac.transpose() * (bias * mass);
                }
                Effect::EnvironmentResistance { .. } => {
                    let (_, jac) = self.tip.position_jacobian(&self.robot, q);
                    x.q0 += jac.transpose() * e.resistance(&(jac * qd));
                }
                _ => {}
            }
        }
        x
    }

    /// What the effects add to the residual `F = A qdd - Q - Qqt - U`.
    fn extra_residual(
        &self,
        q: &SVector<f64, N>,
        qd: &SVector<f64, N>,
        qdd: &SVector<f64, N>,
    ) -> SVector<f64, N> {
        let x = self.extra(q, qd);
        x.a * qdd - x.q0 - x.qqt
    }

    fn payload(&self) -> f64 {
        self.effects
            .iter()
            .map(|e| match *e {
                Effect::PayloadMass { mass } => mass,
                _ => 0.0,
            })
            .sum()
    }
}
