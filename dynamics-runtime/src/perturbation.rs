//! Perturbation analysis about a nominal motion (vibration paper, eqs. 5-6, 9):
//! the linear time-varying equation `A dxdd + D dxd + K dx = dU`, with
//! `A`, `K = dF/dq`, `D = dF/dqd` evaluated on the nominal motion, which is
//! integrated alongside (one Dormand-Prince state holds both).

use nalgebra::SVector;

use crate::ode::{JointState, Tolerances};
use crate::simulate::{check_span, sampled, SimError, Trajectory};
use crate::Robot;

/// The nominal motion and the perturbation at the output times.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Perturbed<const N: usize> {
    /// The nominal motion.
    pub nominal: Trajectory<N>,
    /// dx at each sample.
    pub dx: Vec<SVector<f64, N>>,
    /// d(dx)/dt.
    pub dxd: Vec<SVector<f64, N>>,
    /// d2(dx)/dt2.
    pub dxdd: Vec<SVector<f64, N>>,
}

/// Integrates the nominal motion under `input` from (q0, qd0) and the
/// linearised response to the disturbance `du(t)` from `dx0`.
///
/// ```
/// use dynamics_runtime::{perturbation_response, ode::{JointState, Tolerances}};
/// dynamics_macros::robot! {
///     pub robot Pendulum;
///     gravity = [0.0, -9.81, 0.0];
///     link base;
///     link rod { mass = 1.0; com = [1.0, 0.0, 0.0]; }
///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
/// }
/// // Hanging down at rest, a torque pulse makes it swing: dx oscillates.
/// let down = -std::f64::consts::FRAC_PI_2;
/// let zero = JointState { q: [0.0].into(), qd: [0.0].into() };
/// let r = perturbation_response(&Pendulum::default(), [down].into(), [0.0].into(),
///     |_, _, _| [0.0].into(), |t| [if t < 0.1 { 1.0 } else { 0.0 }].into(), zero,
///     2.0, 0.1, Tolerances::default()).unwrap();
/// // Impulse 0.1 N m s on I = 1 kg m^2, natural frequency sqrt(9.81): amplitude ~0.032 rad.
/// let peak = r.dx.iter().fold(0.0f64, |m, d| m.max(d[0].abs()));
/// assert!((peak - 0.1 / 9.81f64.sqrt()).abs() < 0.003, "{peak}");
/// ```
#[allow(clippy::too_many_arguments)]
pub fn perturbation_response<R: Robot<N>, const N: usize>(
    robot: &R,
    q0: SVector<f64, N>,
    qd0: SVector<f64, N>,
    mut input: impl FnMut(f64, &SVector<f64, N>, &SVector<f64, N>) -> SVector<f64, N>,
    mut du: impl FnMut(f64) -> SVector<f64, N>,
    dx0: JointState<N>,
    t_end: f64,
    dt: f64,
    tol: Tolerances,
) -> Result<Perturbed<N>, SimError> {
    check_span(t_end, dt)?;
    type Pair<const N: usize> = (JointState<N>, JointState<N>);
    // Nominal acceleration, perturbation acceleration, input.
    type Rates<const N: usize> = (SVector<f64, N>, SVector<f64, N>, SVector<f64, N>);
    let mut eval = |t: f64, x: &Pair<N>| -> Result<Rates<N>, SimError> {
        let (n, p) = x;
        let u = input(t, &n.q, &n.qd);
        if let Some(i) = u.iter().position(|v| !v.is_finite()) {
            return Err(SimError::Input {
                t,
                joint: R::JOINT_NAMES[i],
            });
        }
        let qdd = robot
            .forward_dynamics(&n.q, &n.qd, &u)
            .map_err(|source| SimError::Dynamics { t, source })?;
        let pj = robot.perturbation_jacobians(&n.q, &n.qd, &qdd);
        let a = robot.mass_matrix(&n.q);
        let rhs = du(t) - pj.d * p.qd - pj.k * p.q;
        let chol = a.cholesky().ok_or(SimError::Dynamics {
            t,
            source: crate::DynamicsError::SingularMassMatrix {
                q: crate::Coordinates::new(n.q.as_slice()),
            },
        })?;
        Ok((qdd, chol.solve(&rhs), u))
    };
    let x0: Pair<N> = (JointState { q: q0, qd: qd0 }, dx0);
    let mut rhs = |t: f64, x: &Pair<N>| -> Result<Pair<N>, SimError> {
        let (qdd, dxdd, _) = eval(t, x)?;
        Ok((
            JointState { q: x.0.qd, qd: qdd },
            JointState {
                q: x.1.qd,
                qd: dxdd,
            },
        ))
    };
    let (samples, failure) = sampled(&mut rhs, x0, t_end, dt, tol);
    let mut out = Perturbed::default();
    for (t, x) in samples {
        let (qdd, dxdd, u) = eval(t, &x)?;
        out.nominal.t.push(t);
        out.nominal.q.push(x.0.q);
        out.nominal.qd.push(x.0.qd);
        out.nominal.qdd.push(qdd);
        out.nominal.tau.push(u);
        out.dx.push(x.1.q);
        out.dxd.push(x.1.qd);
        out.dxdd.push(dxdd);
    }
    match failure {
        Some(e) => Err(e),
        None => Ok(out),
    }
}
