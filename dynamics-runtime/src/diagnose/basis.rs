//! Per-sample model quantities that several candidates share: the
//! perturbation Jacobian K = dF/dq (encoder offsets), the tip's Jacobian,
//! velocity and bias acceleration (payload, environment), the joints' own
//! inertia.

use nalgebra::{SMatrix, SVector, Vector3};

use super::signals::Signals;
use crate::effects::Tip;
use crate::Robot;

/// Shared model quantities along one data set (valid inside the signals'
/// range).
#[derive(Debug, Clone)]
pub struct Basis<const N: usize> {
    /// K = dF/dq per sample.
    pub k: Vec<SMatrix<f64, N, N>>,
    /// Tip Jacobian per sample.
    pub jac: Vec<SMatrix<f64, 3, N>>,
    /// Tip acceleration J qdd + Jd qd per sample.
    pub tip_acc: Vec<Vector3<f64>>,
    /// Mean A[j][j] over the data.
    pub inertia: SVector<f64, N>,
    /// Gravity vector of the model.
    pub gravity: Vector3<f64>,
    /// The tip used.
    pub tip: Tip,
}

impl<const N: usize> Basis<N> {
    /// Evaluates the shared quantities along `sig`.
    pub fn new<R: Robot<N>>(robot: &R, sig: &Signals<N>) -> Self {
        let n = sig.t.len();
        let tip = Tip::of::<R, N>();
        let mut b = Basis {
            k: vec![SMatrix::zeros(); n],
            jac: vec![SMatrix::zeros(); n],
            tip_acc: vec![Vector3::zeros(); n],
            inertia: SVector::zeros(),
            gravity: Vector3::from(R::GRAVITY),
            tip,
        };
        let (a, z) = sig.range;
        for k in a..z {
            let (q, qd, qdd) = (&sig.q[k], &sig.qd[k], &sig.qdd[k]);
            b.k[k] = robot.perturbation_jacobians(q, qd, qdd).k;
            let (_, jac) = tip.position_jacobian(robot, q);
            b.jac[k] = jac;
            b.tip_acc[k] = jac * qdd + tip.bias_acceleration(robot, q, qd);
            let m = robot.mass_matrix(q);
            for j in 0..N {
                b.inertia[j] += m[(j, j)];
            }
        }
        b.inertia /= (z - a).max(1) as f64;
        b
    }
}
