//! Program (constrained) motion, dissertation, eqs. 2.43-2.46: the control
//! forces that keep the robot on a program `f(t, q) = 0`.
//!
//! With ideal program constraints the control force is `U_c = J^T lambda`
//! (it does no work along the motions the program allows, i.e. `D U_c = 0`
//! for the dissertation's null-space matrix D). lambda follows from
//! `A qdd = Q + Qqt + U + J^T lambda` and the constraint acceleration
//! `J qdd + bias = -2 alpha (J qd) - beta^2 f` (Baumgarte's drift control):
//! `(J A^-1 J^T) lambda = -bias - 2 alpha J qd - beta^2 f - J A^-1 (Q + Qqt + U)`.
//! Everything is fixed-size (Cholesky of A, then of the M x M matrix).

use nalgebra::{SMatrix, SVector};

use crate::ode::{JointState, Tolerances};
use crate::simulate::{check_span, sampled, SimError, Trajectory};
use crate::{Constrained, DynamicsError};

/// A constrained simulation: the motion, the constraint forces and how far
/// the motion strayed from the program.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ProgramMotion<const N: usize, const M: usize> {
    /// The motion; `tau` holds the applied input plus the control forces `J^T lambda`.
    pub trajectory: Trajectory<N>,
    /// The multipliers lambda at each sample.
    pub lambda: Vec<SVector<f64, M>>,
    /// The control forces `J^T lambda` at each sample.
    pub control: Vec<SVector<f64, N>>,
    /// Largest |f(t, q)| over the samples.
    pub max_violation: f64,
}

/// Drift control gains (Baumgarte): `alpha` on the constraint velocity,
/// `beta` on the constraint itself.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Baumgarte {
    /// Velocity gain, 1/s.
    pub alpha: f64,
    /// Position gain, 1/s.
    pub beta: f64,
}

impl Default for Baumgarte {
    fn default() -> Self {
        Baumgarte {
            alpha: 20.0,
            beta: 20.0,
        }
    }
}

fn accelerations<R: Constrained<N, M>, const N: usize, const M: usize>(
    robot: &R,
    t: f64,
    q: &SVector<f64, N>,
    qd: &SVector<f64, N>,
    u: &SVector<f64, N>,
    gains: Baumgarte,
) -> Result<(SVector<f64, N>, SVector<f64, M>), DynamicsError> {
    let terms = robot.motion_terms(q, qd);
    let chol = terms
        .a
        .cholesky()
        .ok_or_else(|| DynamicsError::SingularMassMatrix {
            q: crate::Coordinates::new(q.as_slice()),
        })?;
    let j: SMatrix<f64, M, N> = robot.constraint_jacobian(t, q);
    let f = robot.constraint_residual(t, q);
    let bias = robot.constraint_bias(t, q, qd);
    let rhs = terms.bias() + u;
    let a_inv_rhs = chol.solve(&rhs);
    let a_inv_jt: SMatrix<f64, N, M> = chol.solve(&j.transpose());
    let s: SMatrix<f64, M, M> = j * a_inv_jt;
    let target =
        -bias - (j * qd) * (2.0 * gains.alpha) - f * (gains.beta * gains.beta) - j * a_inv_rhs;
    let lambda = s
        .cholesky()
        .ok_or(DynamicsError::Diverged {
            quantity: "constraint Jacobian (J A^-1 J^T singular)",
            index: 0,
        })?
        .solve(&target);
    let qdd = a_inv_rhs + a_inv_jt * lambda;
    match qdd.iter().position(|x| !x.is_finite()) {
        Some(index) => Err(DynamicsError::Diverged {
            quantity: "qdd",
            index,
        }),
        None => Ok((qdd, lambda)),
    }
}

/// Simulates `robot` on its program constraints under the applied input
/// `input(t, q, qd)` (the drive efforts besides the control forces).
///
/// ```
/// use dynamics_runtime::{simulate_program, ode::Tolerances, Baumgarte};
/// dynamics_macros::robot! {
///     pub robot Slider;
///     gravity = [0.0, -9.81, 0.0];
///     link base;
///     link a { mass = 1.0; }
///     link b { mass = 1.0; }
///     joint x = prismatic(base -> a) { transfer = [trans_x(q)]; }
///     joint y = prismatic(a -> b) { transfer = [trans_y(q)]; }
///     constraint slope = y + 0.5 * x;   // slide down a slope
/// }
/// let run = simulate_program(&Slider::default(), [0.0, 0.0].into(), [0.0, 0.0].into(),
///     |_, _, _| [0.0, 0.0].into(), 1.0, 0.1, Tolerances::default(), Baumgarte::default()).unwrap();
/// assert!(run.max_violation < 1e-8);
/// assert!(run.trajectory.q[10][0] > 0.5); // it slides in +x
/// ```
#[allow(clippy::too_many_arguments)]
pub fn simulate_program<R: Constrained<N, M>, const N: usize, const M: usize>(
    robot: &R,
    q0: SVector<f64, N>,
    qd0: SVector<f64, N>,
    mut input: impl FnMut(f64, &SVector<f64, N>, &SVector<f64, N>) -> SVector<f64, N>,
    t_end: f64,
    dt: f64,
    tol: Tolerances,
    gains: Baumgarte,
) -> Result<ProgramMotion<N, M>, SimError> {
    check_span(t_end, dt)?;
    // Accelerations, multipliers, control forces.
    type Rates<const N: usize, const M: usize> =
        (SVector<f64, N>, SVector<f64, M>, SVector<f64, N>);
    let mut eval = |t: f64, x: &JointState<N>| -> Result<Rates<N, M>, SimError> {
        let u = input(t, &x.q, &x.qd);
        if let Some(i) = u.iter().position(|v| !v.is_finite()) {
            return Err(SimError::Input {
                t,
                joint: R::JOINT_NAMES[i],
            });
        }
        let (qdd, lambda) = accelerations(robot, t, &x.q, &x.qd, &u, gains)
            .map_err(|source| SimError::Dynamics { t, source })?;
        Ok((qdd, lambda, u))
    };
    let mut rhs = |t: f64, x: &JointState<N>| -> Result<JointState<N>, SimError> {
        let (qdd, _, _) = eval(t, x)?;
        Ok(JointState { q: x.qd, qd: qdd })
    };
    let (samples, failure) = sampled(&mut rhs, JointState { q: q0, qd: qd0 }, t_end, dt, tol);
    let mut out = ProgramMotion::default();
    for (t, x) in samples {
        let (qdd, lambda, u) = eval(t, &x)?;
        let j = robot.constraint_jacobian(t, &x.q);
        let control = j.transpose() * lambda;
        let f = robot.constraint_residual(t, &x.q);
        out.max_violation = out.max_violation.max(f.abs().max());
        out.trajectory.t.push(t);
        out.trajectory.q.push(x.q);
        out.trajectory.qd.push(x.qd);
        out.trajectory.qdd.push(qdd);
        out.trajectory.tau.push(u + control);
        out.lambda.push(lambda);
        out.control.push(control);
    }
    match failure {
        Some(e) => Err(e),
        None => Ok(out),
    }
}
