//! `dynamics eval`: every dynamics quantity of a robot at given states,
//! under the field names of the Pinocchio reference files, so that our models
//! can be compared with other toolkits.

use dynamics_runtime::{linearize, DynamicsError, Robot};
use nalgebra::SVector;
use serde::Serialize;

use crate::states::State;

/// Quantities at one state (matrices row-major).
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct Evaluated {
    /// Position.
    pub q: Vec<f64>,
    /// Velocity.
    pub v: Vec<f64>,
    /// Acceleration.
    pub a: Vec<f64>,
    /// Inverse dynamics U = A a - Q(0) - Qqt1 - Qqt2.
    pub tau: Vec<f64>,
    /// Inertia matrix A.
    #[serde(rename = "M")]
    pub m: Vec<Vec<f64>>,
    /// Gravity torques.
    pub g: Vec<f64>,
    /// Christoffel Coriolis matrix.
    #[serde(rename = "C")]
    pub c: Vec<Vec<f64>>,
    /// Efforts at zero acceleration: -(Q(0) + Qqt1 + Qqt2) (= C v + g for a rigid robot).
    pub nle: Vec<f64>,
    /// Forward dynamics of `tau`.
    pub ddq: Vec<f64>,
    /// Perturbation Jacobian K = d tau/dq (Pinocchio's `dtau_dq`).
    pub dtau_dq: Vec<Vec<f64>>,
    /// Perturbation Jacobian D = d tau/dqd (Pinocchio's `dtau_dv`).
    pub dtau_dv: Vec<Vec<f64>>,
    /// d(ddq)/dq of the forward dynamics at fixed `tau`, = -A^-1 K at
    /// (q, v, ddq) (Pinocchio's `computeABADerivatives`).
    pub ddq_dq: Vec<Vec<f64>>,
    /// d(ddq)/dv at fixed `tau`, = -A^-1 D.
    pub ddq_dv: Vec<Vec<f64>>,
    /// T.
    pub kinetic_energy: f64,
    /// Pi.
    pub potential_energy: f64,
}

/// Evaluates `robot` at every state.
///
/// ```
/// use dynamics_cli::{eval::evaluate, states::State};
/// dynamics_macros::robot! {
///     pub robot Pendulum; gravity = [0.0, -9.81, 0.0];
///     link base; link rod { mass = 1.0; com = [0.2, 0.0, 0.0]; inertia = [1e-3, 1e-2, 1e-2]; }
///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
/// }
/// let s = State { q: vec![0.0], v: vec![0.0], a: vec![0.0] };
/// let out = evaluate(&Pendulum::default(), &[s]).unwrap();
/// assert!((out[0].g[0] - 1.0 * 9.81 * 0.2).abs() < 1e-12); // m g l cos q
/// ```
pub fn evaluate<R: Robot<N>, const N: usize>(
    robot: &R,
    states: &[State],
) -> Result<Vec<Evaluated>, DynamicsError> {
    states
        .iter()
        .map(|s| {
            let q = SVector::<f64, N>::from_column_slice(&s.q);
            let v = SVector::<f64, N>::from_column_slice(&s.v);
            let a = SVector::<f64, N>::from_column_slice(&s.a);
            let tau = robot.inverse_dynamics(&q, &v, &a);
            let m = robot.mass_matrix(&q);
            let c = robot.coriolis_matrix(&q, &v);
            let rows = |x: &nalgebra::SMatrix<f64, N, N>| -> Vec<Vec<f64>> {
                (0..N)
                    .map(|i| (0..N).map(|j| x[(i, j)]).collect())
                    .collect()
            };
            let pj = robot.perturbation_jacobians(&q, &v, &a);
            let fd = linearize::forward_dynamics_derivatives(robot, &q, &v, &tau)?;
            Ok(Evaluated {
                q: s.q.clone(),
                v: s.v.clone(),
                a: s.a.clone(),
                tau: tau.iter().copied().collect(),
                m: rows(&m),
                g: robot.gravity(&q).iter().copied().collect(),
                c: rows(&c),
                nle: robot.nonlinear_effects(&q, &v).iter().copied().collect(),
                ddq: fd.qdd.iter().copied().collect(),
                dtau_dq: rows(&pj.k),
                dtau_dv: rows(&pj.d),
                ddq_dq: rows(&fd.ddq_dq),
                ddq_dv: rows(&fd.ddq_dv),
                kinetic_energy: robot.kinetic_energy(&q, &v),
                potential_energy: robot.potential_energy(&q),
            })
        })
        .collect()
}
