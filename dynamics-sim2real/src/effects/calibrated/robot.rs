//! [`Robot`] for [`Calibrated`]: every quantity of the wrapped model plus
//! what the folded-in effects add (a payload's velocity terms and
//! Coriolis share, the effects' share of the perturbation Jacobians by
//! central differences).

use nalgebra::{Matrix4, SMatrix, SVector, Vector3};

use super::Calibrated;
use crate::effects::Effect;
use dynamics_runtime::{DynamicsError, MotionTerms, PerturbationJacobians, Robot};

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
        let norm = qd.norm();
        for (mass, com) in self.payloads().into_iter().filter(|_| norm > 0.0) {
            let h = 1e-5 / norm;
            let (_, jac) = self.tip.position_jacobian_at(&self.robot, q, &com);
            let (_, jp) = self
                .tip
                .position_jacobian_at(&self.robot, &(q + qd * h), &com);
            let (_, jm) = self
                .tip
                .position_jacobian_at(&self.robot, &(q - qd * h), &com);
            c += jac.transpose() * ((jp - jm) / (2.0 * h)) * mass;
        }
        c + self.links_coriolis(q, qd)
    }
    fn gravity(&self, q: &SVector<f64, N>) -> SVector<f64, N> {
        let mut g = self.robot.gravity(q) - self.links_at_rest(q);
        for (mass, com) in self.payloads() {
            let (_, jac) = self.tip.position_jacobian_at(&self.robot, q, &com);
            g -= jac.transpose() * (Vector3::from(R::GRAVITY) * mass);
        }
        g
    }
    fn generalized_forces(&self, q: &SVector<f64, N>, qd: &SVector<f64, N>) -> SVector<f64, N> {
        self.robot.generalized_forces(q, qd) + self.extra(q, qd).q0
    }
    /// The wrapped model's and the folded-in friction effects': the
    /// environment's resistance at the tip is not the joints' friction.
    fn joint_friction(&self, q: &SVector<f64, N>, qd: &SVector<f64, N>) -> SVector<f64, N> {
        let mut f = self.robot.joint_friction(q, qd);
        for e in &self.effects {
            match *e {
                Effect::CoulombFriction { joint, .. }
                | Effect::ViscousFriction { joint, .. }
                | Effect::StribeckFriction { joint, .. } => f[joint] += e.joint_force(qd[joint]),
                _ => {}
            }
        }
        f
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
            let (qp, qm, h) = crate::effects::central_step(q, k);
            let dq =
                (self.extra_residual(&qp, qd, qdd) - self.extra_residual(&qm, qd, qdd)) / (2.0 * h);
            let (vp, vm, h) = crate::effects::central_step(qd, k);
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
        let mut v = self.robot.potential_energy(q) + self.links_potential(q);
        for (mass, com) in self.payloads() {
            let p = self.tip.position_at(&self.robot, q, &com);
            v -= mass * Vector3::from(R::GRAVITY).dot(&p);
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
