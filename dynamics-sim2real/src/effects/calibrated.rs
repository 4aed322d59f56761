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

use nalgebra::{Matrix4, SMatrix, SVector, Vector3};

use super::{Effect, EffectKind, Tip};
use dynamics_runtime::{DynamicsError, MotionTerms, PerturbationJacobians, Robot};

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
    /// Folds `effects` into `robot`'s nominal model.
    pub fn new(robot: R, effects: Vec<Effect>) -> Result<Self, CalibratedError> {
        for e in &effects {
            let kind = e.kind().name();
            match e.kind() {
                EffectKind::CoulombFriction
                | EffectKind::ViscousFriction
                | EffectKind::StribeckFriction
                | EffectKind::Armature
                | EffectKind::PayloadMass
                | EffectKind::EnvironmentResistance => {}
                _ => return Err(CalibratedError::NotNominal { kind }),
            }
            if let Some(joint) = e.joint().filter(|&j| j >= N) {
                return Err(CalibratedError::Joint { kind, joint, n: N });
            }
            e.validate()
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

impl<R: Robot<N>, const N: usize> Robot<N> for Calibrated<R, N> {
    type Params = R::Params;
    const NAME: &'static str = R::NAME;
    const JOINT_NAMES: [&'static str; N] = R::JOINT_NAMES;
    const JOINT_KINDS: [dynamics_runtime::JointKind; N] = R::JOINT_KINDS;
    const FRAME_NAMES: &'static [&'static str] = R::FRAME_NAMES;
    const POINT_NAMES: &'static [&'static str] = R::POINT_NAMES;
    const GRAVITY: [f64; 3] = R::GRAVITY;
    const LINK_NAMES: &'static [&'static str] = R::LINK_NAMES;

    fn params(&self) -> &Self::Params {
        self.robot.params()
    }
    fn params_mut(&mut self) -> &mut Self::Params {
        self.robot.params_mut()
    }
    fn mass_matrix(&self, q: &SVector<f64, N>) -> SMatrix<f64, N, N> {
        self.robot.mass_matrix(q) + self.extra(q, &SVector::zeros()).a
    }
    /// The wrapped model's: a payload's velocity terms all go to [`Robot::qqt2`].
    fn qqt1(&self, q: &SVector<f64, N>, qd: &SVector<f64, N>) -> SVector<f64, N> {
        self.robot.qqt1(q, qd)
    }
    /// The wrapped model's plus all of a payload's velocity terms (their
    /// sum with [`Robot::qqt1`] is right; the split is not kept).
    fn qqt2(&self, q: &SVector<f64, N>, qd: &SVector<f64, N>) -> SVector<f64, N> {
        self.robot.qqt2(q, qd) + self.extra(q, qd).qqt
    }
    fn qqt(&self, q: &SVector<f64, N>, qd: &SVector<f64, N>) -> SVector<f64, N> {
        self.robot.qqt(q, qd) + self.extra(q, qd).qqt
    }
    /// The wrapped model's plus a payload's `m J^T Jd` (`Jd` by a central
    /// difference of the tip Jacobian along `qd`).
    fn coriolis_matrix(&self, q: &SVector<f64, N>, qd: &SVector<f64, N>) -> SMatrix<f64, N, N> {
        let mut c = self.robot.coriolis_matrix(q, qd);
        let mass = self.payload();
        let norm = qd.norm();
        if mass != 0.0 && norm > 0.0 {
            let h = 1e-5 / norm;
            let (_, jac) = self.tip.position_jacobian(&self.robot, q);
            let (_, jp) = self.tip.position_jacobian(&self.robot, &(q + qd * h));
            let (_, jm) = self.tip.position_jacobian(&self.robot, &(q - qd * h));
            c += jac.transpose() * ((jp - jm) / (2.0 * h)) * mass;
        }
        c
    }
    fn gravity(&self, q: &SVector<f64, N>) -> SVector<f64, N> {
        let mut g = self.robot.gravity(q);
        let mass = self.payload();
        if mass != 0.0 {
            let (_, jac) = self.tip.position_jacobian(&self.robot, q);
            g -= jac.transpose() * (Vector3::from(R::GRAVITY) * mass);
        }
        g
    }
    fn generalized_forces(&self, q: &SVector<f64, N>, qd: &SVector<f64, N>) -> SVector<f64, N> {
        self.robot.generalized_forces(q, qd) + self.extra(q, qd).q0
    }
    fn inverse_dynamics(
        &self,
        q: &SVector<f64, N>,
        qd: &SVector<f64, N>,
        qdd: &SVector<f64, N>,
    ) -> SVector<f64, N> {
        self.robot.inverse_dynamics(q, qd, qdd) + self.extra_residual(q, qd, qdd)
    }
    /// The wrapped model's plus the effects' share by central differences.
    fn perturbation_jacobians(
        &self,
        q: &SVector<f64, N>,
        qd: &SVector<f64, N>,
        qdd: &SVector<f64, N>,
    ) -> PerturbationJacobians<N> {
        let mut pj = self.robot.perturbation_jacobians(q, qd, qdd);
        if self.effects.is_empty() {
            return pj;
        }
        for k in 0..N {
            let h = 1e-6 * (1.0 + q[k].abs());
            let (mut qp, mut qm) = (*q, *q);
            qp[k] += h;
            qm[k] -= h;
            let dq =
                (self.extra_residual(&qp, qd, qdd) - self.extra_residual(&qm, qd, qdd)) / (2.0 * h);
            let h = 1e-6 * (1.0 + qd[k].abs());
            let (mut vp, mut vm) = (*qd, *qd);
            vp[k] += h;
            vm[k] -= h;
            let dv =
                (self.extra_residual(q, &vp, qdd) - self.extra_residual(q, &vm, qdd)) / (2.0 * h);
            for i in 0..N {
                pj.k[(i, k)] += dq[i];
                pj.d[(i, k)] += dv[i];
            }
        }
        pj
    }
    fn parameter_sensitivity(
        &self,
        index: usize,
        q: &SVector<f64, N>,
        qd: &SVector<f64, N>,
        qdd: &SVector<f64, N>,
    ) -> Option<SVector<f64, N>> {
        self.robot.parameter_sensitivity(index, q, qd, qdd)
    }
    /// The wrapped model's: the regressor of its links, without the
    /// effects folded in.
    fn inertial_regressor(
        &self,
        q: &SVector<f64, N>,
        qd: &SVector<f64, N>,
        qdd: &SVector<f64, N>,
        out: &mut [SMatrix<f64, N, 10>],
    ) -> Result<(), DynamicsError> {
        self.robot.inertial_regressor(q, qd, qdd, out)
    }
    /// The wrapped model's (a folded-in payload is not in them).
    fn inertial_parameters(&self, out: &mut [SVector<f64, 10>]) -> Result<(), DynamicsError> {
        self.robot.inertial_parameters(out)
    }
    fn motion_terms(&self, q: &SVector<f64, N>, qd: &SVector<f64, N>) -> MotionTerms<N> {
        let mut t = self.robot.motion_terms(q, qd);
        let x = self.extra(q, qd);
        t.a += x.a;
        t.q0 += x.q0;
        t.qqt += x.qqt;
        t
    }
    fn kinetic_energy(&self, q: &SVector<f64, N>, qd: &SVector<f64, N>) -> f64 {
        let a = self.extra(q, &SVector::zeros()).a;
        self.robot.kinetic_energy(q, qd) + 0.5 * qd.dot(&(a * qd))
    }
    fn potential_energy(&self, q: &SVector<f64, N>) -> f64 {
        let mass = self.payload();
        let mut v = self.robot.potential_energy(q);
        if mass != 0.0 {
            v -= mass * Vector3::from(R::GRAVITY).dot(&self.tip.position(&self.robot, q));
        }
        v
    }
    fn frame_pose(&self, index: usize, q: &SVector<f64, N>) -> Option<Matrix4<f64>> {
        self.robot.frame_pose(index, q)
    }
    fn point_position(&self, index: usize, q: &SVector<f64, N>) -> Option<Vector3<f64>> {
        self.robot.point_position(index, q)
    }
    fn point_jacobian(&self, index: usize, q: &SVector<f64, N>) -> Option<SMatrix<f64, 3, N>> {
        self.robot.point_jacobian(index, q)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use dynamics_runtime::Parameters;
    use nalgebra::Vector3 as V3;

    dynamics_macros::robot! {
        pub robot Arm;
        gravity = [0.0, 0.0, -9.81];
        param load = 0.0;
        link base;
        link a { mass = 2.0; com = [0.0, 0.0, 0.2]; inertia = [0.02, 0.02, 0.01]; }
        link b { mass = 1.0; com = [0.2, 0.0, 0.0]; inertia = [0.005, 0.01, 0.01]; }
        link c {
            mass = 0.5; com = [0.15, 0.0, 0.0]; inertia = [0.002, 0.004, 0.004];
            point_mass tool = load at [0.3, 0.0, 0.0];
        }
        joint j1 = revolute(base -> a) { transfer = [rot_z(q)]; }
        joint j2 = revolute(a -> b) { transfer = [trans_z(0.4), rot_y(q)]; }
        joint j3 = revolute(b -> c) { transfer = [trans_x(0.4), rot_y(q)]; }
    }

    /// A payload folded in equals the same mass written into the model
    /// (`point_mass` at the tip, derived symbolically): every quantity.
    #[test]
    fn a_payload_folded_in_matches_the_model_with_the_mass_written_in() {
        let mut truth = Arm::default();
        truth.params_mut().set("load", 1.7).expect("param");
        let folded = Calibrated::new(Arm::default(), vec![Effect::PayloadMass { mass: 1.7 }])
            .expect("nominal");
        assert_eq!(Tip::of::<Arm, 3>().name::<Arm, 3>(), "tool");
        let q = V3::new(0.3, -0.7, 1.1);
        let qd = V3::new(0.8, -1.2, 0.5);
        let qdd = V3::new(-0.4, 2.0, 1.5);
        // The tip's velocity terms come from a central difference of its
        // Jacobian (1e-6 relative), K and D from one more (1e-5).
        let near = |a: f64, b: f64, tol: f64, what: &str| {
            assert!((a - b).abs() <= tol * (1.0 + b.abs()), "{what}: {a} vs {b}")
        };
        let close = |a: f64, b: f64, what: &str| near(a, b, 1e-6, what);
        let id = (
            folded.inverse_dynamics(&q, &qd, &qdd),
            truth.inverse_dynamics(&q, &qd, &qdd),
        );
        let m = (folded.mass_matrix(&q), truth.mass_matrix(&q));
        let g = (folded.gravity(&q), truth.gravity(&q));
        let cv = (
            folded.coriolis_matrix(&q, &qd) * qd,
            truth.coriolis_matrix(&q, &qd) * qd,
        );
        let nle = (
            folded.nonlinear_effects(&q, &qd),
            truth.nonlinear_effects(&q, &qd),
        );
        let pj = (
            folded.perturbation_jacobians(&q, &qd, &qdd),
            truth.perturbation_jacobians(&q, &qd, &qdd),
        );
        for i in 0..3 {
            close(id.0[i], id.1[i], "tau");
            close(g.0[i], g.1[i], "g");
            close(cv.0[i], cv.1[i], "C qd");
            close(nle.0[i], nle.1[i], "nle");
            for j in 0..3 {
                close(m.0[(i, j)], m.1[(i, j)], "M");
                near(pj.0.k[(i, j)], pj.1.k[(i, j)], 1e-5, "K");
                near(pj.0.d[(i, j)], pj.1.d[(i, j)], 1e-5, "D");
            }
        }
        close(
            folded.kinetic_energy(&q, &qd),
            truth.kinetic_energy(&q, &qd),
            "T",
        );
        close(folded.potential_energy(&q), truth.potential_energy(&q), "V");
    }

    /// Friction and rotor inertia enter the residual as the plant adds them.
    #[test]
    fn friction_and_armature_add_what_the_plant_adds() {
        let effects = vec![
            Effect::coulomb(0, 0.4),
            Effect::ViscousFriction { joint: 1, fv: 0.3 },
            Effect::Armature {
                joint: 2,
                inertia: 0.05,
            },
        ];
        let r = Calibrated::new(Arm::default(), effects.clone()).expect("nominal");
        let plant = crate::effects::Plant::new(Arm::default(), effects).expect("plant");
        let (q, qd, qdd) = (
            V3::new(0.1, 0.2, 0.3),
            V3::new(1.0, -2.0, 0.5),
            V3::new(0.3, 0.1, -0.2),
        );
        let (a, f) = plant.mass_and_forces(&q, &qd);
        assert!((r.inverse_dynamics(&q, &qd, &qdd) - (a * qdd - f)).norm() < 1e-12);
        let fwd = r
            .forward_dynamics(&q, &qd, &V3::new(1.0, 2.0, 3.0))
            .expect("fwd");
        assert!((r.inverse_dynamics(&q, &qd, &fwd) - V3::new(1.0, 2.0, 3.0)).norm() < 1e-10);
    }

    #[test]
    fn state_and_sensor_effects_are_refused_by_name() {
        let e = Calibrated::new(Arm::default(), vec![Effect::TimeDelay { delay: 0.01 }]);
        assert!(e.expect_err("refused").to_string().contains("time_delay"));
        let e = Calibrated::new(
            Arm::default(),
            vec![Effect::Armature {
                joint: 5,
                inertia: 0.1,
            }],
        );
        assert!(matches!(
            e,
            Err(CalibratedError::Joint { joint: 5, n: 3, .. })
        ));
    }
}
