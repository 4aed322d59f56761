//! Per-sample model quantities that several candidates share: the
//! perturbation Jacobian K = dF/dq (encoder offsets), the tip's Jacobian,
//! velocity and bias acceleration (payload, environment), the joints' own
//! inertia.

use nalgebra::{SMatrix, SVector, Vector3};

use super::candidate::STRIBECK_GRID;
use super::nominal_friction::nominal_friction;
use super::signals::Signals;
use crate::effects::{smooth_sign, Tip};
use dynamics_runtime::Robot;

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
    /// Accelerations smoothed once more (the rotor-inertia column): the
    /// acceleration estimate's own noise, which the nominal model's
    /// residual already carries, is not added a second time by a column.
    pub qdd: Vec<SVector<f64, N>>,
    /// Per joint, the smoothed sign of the (lightly smoothed) velocity:
    /// the Coulomb column, smoothed like the efforts it is compared with.
    pub sign: Vec<SVector<f64, N>>,
    /// The same for the Stribeck term `exp(-(v/vs)^2) sign(v)`, one per
    /// velocity of [`STRIBECK_GRID`].
    pub stribeck: Vec<Vec<SVector<f64, N>>>,
    /// Per joint, the nominal model's own Coulomb level and viscous
    /// coefficient (`nominal_friction.rs`): how far a friction correction
    /// may go below zero.
    pub friction: (SVector<f64, N>, SVector<f64, N>),
}

/// `f` of the lightly smoothed velocity, then smoothed like the efforts.
fn smoothed_column<const N: usize>(
    sig: &Signals<N>,
    f: impl Fn(f64) -> f64,
) -> Vec<SVector<f64, N>> {
    let n = sig.t.len();
    let mut out = vec![SVector::<f64, N>::zeros(); n];
    for j in 0..N {
        let raw: Vec<f64> = sig
            .qd_light
            .iter()
            .map(|v| if v[j].is_finite() { f(v[j]) } else { 0.0 })
            .collect();
        for (o, x) in out.iter_mut().zip(sig.sg.apply(&raw, 0)) {
            o[j] = x;
        }
    }
    out
}

/// Smooths every entry of `v` over `range` (zero where the window does not
/// fit).
fn smooth_in_place<const R: usize, const C: usize>(
    sg: &super::filter::SavitzkyGolay,
    v: &mut [SMatrix<f64, R, C>],
    (a, z): (usize, usize),
) {
    for i in 0..R * C {
        let x: Vec<f64> = (a..z).map(|k| v[k].as_slice()[i]).collect();
        let y = sg.apply(&x, 0);
        for (k, y) in (a..z).zip(y) {
            v[k].as_mut_slice()[i] = if y.is_finite() { y } else { 0.0 };
        }
    }
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
            qdd: sig.qdd.clone(),
            sign: smoothed_column(sig, smooth_sign),
            stribeck: STRIBECK_GRID
                .iter()
                .map(|&vs| smoothed_column(sig, |v| (-(v / vs).powi(2)).exp() * smooth_sign(v)))
                .collect(),
            friction: (SVector::zeros(), SVector::zeros()),
        };
        let (a, z) = sig.range;
        if let Some(q) = sig.q.get(a) {
            b.friction = nominal_friction(robot, q);
        }
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
        // Columns built from the acceleration estimate are smoothed once
        // more, like the acceleration itself.
        smooth_in_place(&sig.sg, &mut b.qdd, (a, z));
        smooth_in_place(&sig.sg, &mut b.tip_acc, (a, z));
        smooth_in_place(&sig.sg, &mut b.k, (a, z));
        b
    }
}
