//! d(qdd)/dq and d(qdd)/dqd of the forward dynamics, and the continuous-time
//! state-space matrices built from them.

use nalgebra::{SMatrix, SVector};

use super::ldlt::Ldlt;
use super::BlockMatrix;
use crate::{DynamicsError, Robot};

/// The derivatives of the forward dynamics `qdd = f(q, qd, tau)` at one
/// state, at fixed `tau` (Pinocchio's `computeABADerivatives`: `ddq_dq`,
/// `ddq_dv`).
///
/// ```
/// use dynamics_runtime::linearize::forward_dynamics_derivatives;
/// dynamics_macros::robot! {
///     pub robot Pendulum;
///     gravity = [0.0, -9.81, 0.0];
///     link base;
///     link rod { mass = 2.0; com = [0.5, 0.0, 0.0]; }
///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; damping = 0.3; }
/// }
/// // qdd = (-m g l cos q - b qd + tau) / (m l^2)
/// let (q, qd, tau) = (0.4f64, 1.5f64, 0.2f64);
/// let d = forward_dynamics_derivatives(&Pendulum::default(), &[q].into(), &[qd].into(), &[tau].into())
///     .unwrap();
/// let ml2 = 2.0 * 0.25;
/// assert!((d.qdd[0] - (-2.0 * 9.81 * 0.5 * q.cos() - 0.3 * qd + tau) / ml2).abs() < 1e-12);
/// assert!((d.ddq_dq[(0, 0)] - 2.0 * 9.81 * 0.5 * q.sin() / ml2).abs() < 1e-12);
/// assert!((d.ddq_dv[(0, 0)] + 0.3 / ml2).abs() < 1e-12);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ForwardDerivatives<const N: usize> {
    /// The forward dynamics themselves, `qdd = f(q, qd, tau)`.
    pub qdd: SVector<f64, N>,
    /// d(qdd)/dq = -A^-1 K(q, qd, qdd).
    pub ddq_dq: SMatrix<f64, N, N>,
    /// d(qdd)/dqd = -A^-1 D(q, qd, qdd).
    pub ddq_dv: SMatrix<f64, N, N>,
}

/// The continuous-time linearisation `dx' = a dx + b du` of `x' = f(x, u)`,
/// `x = [q; qd]`, `u = tau`, about one state and input.
///
/// `a = [[0, I], [d(qdd)/dq, d(qdd)/dqd]]` (`2N x 2N`), `b = [[0], [A^-1]]`
/// (`2N x N`), as matrices of `N x N` blocks.
///
/// ```
/// use dynamics_runtime::linearize::state_space;
/// dynamics_macros::robot! {
///     pub robot Cart;
///     gravity = [0.0, 0.0, -9.81];
///     link base;
///     link cart { mass = 2.0; }
///     joint x = prismatic(base -> cart) { axis = [1.0, 0.0, 0.0]; damping = 0.5; }
/// }
/// let z = nalgebra::Vector1::zeros();
/// let ss = state_space(&Cart::default(), &z, &z, &z).unwrap();
/// // x'' = (tau - b x') / m
/// assert_eq!((ss.a[(0, 0)], ss.a[(0, 1)], ss.a[(1, 0)]), (0.0, 1.0, 0.0));
/// assert!((ss.a[(1, 1)] + 0.25).abs() < 1e-15 && (ss.b[(1, 0)] - 0.5).abs() < 1e-15);
/// assert_eq!(ss.derivatives().ddq_dv, ss.a.blocks[1][1]);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StateSpace<const N: usize> {
    /// `A_c = [[0, I], [d(qdd)/dq, d(qdd)/dqd]]`.
    pub a: BlockMatrix<N, 2, 2>,
    /// `B_c = [[0], [A^-1]]`.
    pub b: BlockMatrix<N, 2, 1>,
    /// The accelerations at the linearisation point (`x' = [qd; qdd]` there).
    pub qdd: SVector<f64, N>,
}

impl<const N: usize> StateSpace<N> {
    /// The forward-dynamics derivatives inside `a`.
    pub fn derivatives(&self) -> ForwardDerivatives<N> {
        ForwardDerivatives {
            qdd: self.qdd,
            ddq_dq: self.a.blocks[1][0],
            ddq_dv: self.a.blocks[1][1],
        }
    }
}

/// The forward dynamics at (q, qd, tau) with their derivatives
/// d(qdd)/dq and d(qdd)/dqd (see [`ForwardDerivatives`]).
///
/// Errors like [`Robot::forward_dynamics`]: an input that is not finite,
/// an inertia matrix that is not positive definite, a result that is not
/// finite.
pub fn forward_dynamics_derivatives<R: Robot<N>, const N: usize>(
    robot: &R,
    q: &SVector<f64, N>,
    qd: &SVector<f64, N>,
    tau: &SVector<f64, N>,
) -> Result<ForwardDerivatives<N>, DynamicsError> {
    Ok(solved(robot, q, qd, tau)?.0)
}

/// The continuous-time state-space linearisation about (q, qd, tau) (see
/// [`StateSpace`]). Errors as [`forward_dynamics_derivatives`].
pub fn state_space<R: Robot<N>, const N: usize>(
    robot: &R,
    q: &SVector<f64, N>,
    qd: &SVector<f64, N>,
    tau: &SVector<f64, N>,
) -> Result<StateSpace<N>, DynamicsError> {
    let (d, ldlt) = solved(robot, q, qd, tau)?;
    let mut a = BlockMatrix::zeros();
    a.blocks[0][1] = SMatrix::identity();
    a.blocks[1][0] = d.ddq_dq;
    a.blocks[1][1] = d.ddq_dv;
    let mut b = BlockMatrix::zeros();
    b.blocks[1][0] = ldlt.solve_matrix(&SMatrix::identity(), 1.0);
    finite("ddq_dtau", &b.blocks[1][0])?;
    Ok(StateSpace { a, b, qdd: d.qdd })
}

/// The derivatives and the factorisation of A they were solved with
/// (inlined: the caller keeps what it needs without copying the rest).
#[inline(always)]
fn solved<R: Robot<N>, const N: usize>(
    robot: &R,
    q: &SVector<f64, N>,
    qd: &SVector<f64, N>,
    tau: &SVector<f64, N>,
) -> Result<(ForwardDerivatives<N>, Ldlt<N>), DynamicsError> {
    crate::check::finite("q", q)?;
    crate::check::finite("qd", qd)?;
    crate::check::finite("tau", tau)?;
    // One pass: A and the bias, the factorisation and qdd, then K and D
    // with the kinematics of A reused. The closure keeps the factors, or
    // why it stopped (no factors and no failure: A is not positive definite).
    let mut factors = None;
    let mut failure = None;
    let solved = robot.motion_and_jacobians(q, qd, |terms| {
        let ldlt = Ldlt::new(&terms.a)?;
        factors = Some(ldlt);
        let qdd = ldlt.solve(&(terms.bias() + tau));
        finite("qdd", &qdd)
            .map(|()| qdd)
            .map_err(|e| failure = Some(e))
            .ok()
    });
    let (Some((qdd, pj)), Some(ldlt)) = (solved, factors) else {
        return Err(failure.unwrap_or(DynamicsError::SingularMassMatrix {
            q: crate::Coordinates::new(q.as_slice()),
        }));
    };
    // Both solves before either check: the check reads a solution in wide
    // loads, which stall on the narrow stores that wrote it while they are
    // still in flight.
    let ddq_dq = ldlt.solve_matrix(&pj.k, -1.0);
    let ddq_dv = ldlt.solve_matrix(&pj.d, -1.0);
    finite("ddq_dq", &ddq_dq)?;
    finite("ddq_dv", &ddq_dv)?;
    Ok((
        ForwardDerivatives {
            qdd,
            ddq_dq,
            ddq_dv,
        },
        ldlt,
    ))
}

/// [`DynamicsError::Diverged`] naming the first non-finite entry of `x`
/// (column-major index), if any.
fn finite<const R: usize, const C: usize>(
    quantity: &'static str,
    x: &SMatrix<f64, R, C>,
) -> Result<(), DynamicsError> {
    match crate::check::first_non_finite(x.as_slice()) {
        Some(index) => Err(DynamicsError::Diverged { quantity, index }),
        None => Ok(()),
    }
}
