//! Per-sample model quantities that several candidates share: the
//! perturbation Jacobian K = dF/dq (encoder offsets), the tip's Jacobian,
//! velocity and bias acceleration (payload, environment), the joints' own
//! inertia.

use nalgebra::{Matrix3, SMatrix, SVector, Vector3};

use super::row_series::RowSeries;
use crate::diagnose::along;
use crate::diagnose::signals::Signals;
use crate::effects::nominal_friction;
use crate::effects::Tip;
use dynamics_runtime::Robot;

/// Per joint, the nominal model's Coulomb levels and viscous coefficients
/// ([`crate::effects::nominal_friction`]).
pub type Friction<const N: usize> = (SVector<f64, N>, SVector<f64, N>);

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
    /// The tip frame's orientation per sample (world from tip; empty for a
    /// point tip, which has no frame).
    pub tip_rot: Vec<Matrix3<f64>>,
    /// The tip frame's angular-velocity Jacobian per sample (empty for a
    /// point tip).
    pub jac_w: Vec<SMatrix<f64, 3, N>>,
    /// The tip frame's angular acceleration `J_w qdd + Jd_w qd` per sample
    /// (empty for a point tip).
    pub tip_alpha: Vec<Vector3<f64>>,
    /// Mean A[j][j] over the data.
    pub inertia: SVector<f64, N>,
    /// Per joint, its acceleration per unit of its own effort: what the
    /// link of a motor-side simulation answers to (`motor_sim/`). One over
    /// its mean own inertia (see `Basis::new` for the per-sample inverse
    /// mass matrix tried instead).
    pub compliance: SVector<f64, N>,
    /// Gravity vector of the model.
    pub gravity: Vector3<f64>,
    /// The tip used.
    pub tip: Tip,
    /// The modelled mass of the body that carries the tip
    /// ([`Tip::body_mass`]): the most a payload relative to the model can
    /// take away.
    pub tip_mass: f64,
    /// The friction laws' columns (every Coulomb width and Stribeck
    /// velocity searched, filtered as the residual shows a force of them)
    /// and the accelerations smoothed once more (the rotor-inertia
    /// column): kept at the fit's rows, recomputed elsewhere
    /// (`row_series.rs`).
    pub series: RowSeries<N>,
    /// Per joint, the nominal model's own Coulomb level and viscous
    /// coefficient (`nominal_friction.rs`): how far a friction correction
    /// may go below zero.
    pub friction: Friction<N>,
}

/// Smooths every entry of `v` over `range` (zero where the window does not
/// fit).
fn smooth_in_place<const R: usize, const C: usize>(
    sg: &crate::smoothing::SavitzkyGolay,
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
    /// Evaluates the shared quantities along `sig`, the series of
    /// [`RowSeries`] kept at `rows` (increasing sample indices). The model
    /// is evaluated `chunk` samples at a time (`along.rs`; 0: the default).
    pub fn new<R: Robot<N>>(robot: &R, sig: &Signals<N>, rows: &[usize], chunk: usize) -> Self {
        let n = sig.t.len();
        let tip = Tip::of::<R, N>();
        let mut b = Basis {
            k: vec![SMatrix::zeros(); n],
            jac: vec![SMatrix::zeros(); n],
            tip_acc: vec![Vector3::zeros(); n],
            tip_rot: Vec::new(),
            jac_w: Vec::new(),
            tip_alpha: Vec::new(),
            inertia: SVector::zeros(),
            compliance: SVector::zeros(),
            gravity: Vector3::from(R::GRAVITY),
            tip,
            tip_mass: Tip::body_mass::<R, N>(robot),
            series: RowSeries::new(sig, rows, chunk),
            friction: (SVector::zeros(), SVector::zeros()),
        };
        let (a, z) = sig.range;
        if let Some(q) = sig.q.get(a) {
            b.friction = nominal_friction(robot, q);
        }
        let motion = [&sig.q[..], &sig.qd[..], &sig.qdd[..]];
        along::perturbation_k(robot, motion, a..z, chunk, &mut b.k);
        along::tip_motion(robot, &tip, motion, a..z, chunk, &mut b.jac, &mut b.tip_acc);
        if let Tip::Frame(_) = tip {
            b.tip_rot = vec![Matrix3::identity(); n];
            b.jac_w = vec![SMatrix::zeros(); n];
            b.tip_alpha = vec![Vector3::zeros(); n];
            let (rot, jac, alpha) = (&mut b.tip_rot, &mut b.jac_w, &mut b.tip_alpha);
            along::tip_rotation(robot, &tip, motion, a..z, rot, jac, alpha);
        }
        b.inertia = along::mass_diagonal_sum(robot, &sig.q, a..z, chunk);
        b.inertia /= (z - a).max(1) as f64;
        // The link's response to its own effort, as one over its mean own
        // inertia. The inverse mass matrix's diagonal at each sample (the
        // joint's response with the other joints' efforts held; the
        // simulation would take it per sample) was tried: right on the MAR's
        // backlash cases, but on the real Panda log it chose elastic joints
        // at joints 1-3 that predicted the held-out half worse (plain
        // shrink 0.429 to 0.409; `scripts/real-logs.sh`): there the other
        // joints' controllers hold them, which neither figure models.
        b.compliance = b.inertia.map(|x| if x > 0.0 { 1.0 / x } else { 0.0 });
        // Columns built from the acceleration estimate are smoothed once
        // more, like the acceleration itself.
        smooth_in_place(&sig.sg, &mut b.tip_acc, (a, z));
        if !b.tip_alpha.is_empty() {
            smooth_in_place(&sig.sg, &mut b.tip_alpha, (a, z));
        }
        smooth_in_place(&sig.sg, &mut b.k, (a, z));
        b
    }
}
