//! Per-sample model quantities that several candidates share: the
//! perturbation Jacobian K = dF/dq (encoder offsets), the tip's Jacobian,
//! velocity and bias acceleration (payload, environment), the joints' own
//! inertia.

use nalgebra::{Matrix3, SMatrix, SVector, Vector3};

use super::grids::{COULOMB_WIDTHS, STRIBECK_GRID};
use crate::diagnose::along;
use crate::diagnose::candidates::force_filter::through_motion;
use crate::diagnose::signals::Signals;
use crate::effects::nominal_friction;
use crate::effects::{smooth_sign, Tip, SIGN_SMOOTHING};
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
    /// Per sample, a joint's acceleration per unit of its own effort: what
    /// the link of a motor-side simulation answers to (`motor_sim/`). One
    /// over its mean own inertia at every sample (see `Basis::new` for the
    /// per-sample inverse mass matrix tried instead).
    pub compliance: Vec<SVector<f64, N>>,
    /// Gravity vector of the model.
    pub gravity: Vector3<f64>,
    /// The tip used.
    pub tip: Tip,
    /// The modelled mass of the body that carries the tip
    /// ([`Tip::body_mass`]): the most a payload relative to the model can
    /// take away.
    pub tip_mass: f64,
    /// Accelerations smoothed once more (the rotor-inertia column): the
    /// acceleration estimate's own noise, which the nominal model's
    /// residual already carries, is not added a second time by a column.
    pub qdd: Vec<SVector<f64, N>>,
    /// Per joint, the filtered sign of the (lightly smoothed) velocity:
    /// the sharp Coulomb column and Stribeck's, filtered as the residual
    /// they are compared with shows a force (`force_filter.rs`).
    pub sign: Vec<SVector<f64, N>>,
    /// The same for `tanh(v / vw)`, one per width of [`COULOMB_WIDTHS`]
    /// after the first (the first, the sharp one, is `sign`, not kept
    /// twice).
    pub coulomb: Vec<Vec<SVector<f64, N>>>,
    /// The same for the Stribeck term `exp(-(v/vs)^2) sign(v)`, one per
    /// velocity of [`STRIBECK_GRID`].
    pub stribeck: Vec<Vec<SVector<f64, N>>>,
    /// Per joint, the nominal model's own Coulomb level and viscous
    /// coefficient (`nominal_friction.rs`): how far a friction correction
    /// may go below zero.
    pub friction: Friction<N>,
}

/// Velocity step of the quadrature in [`interval_mean`], rad/s or m/s: an
/// eighth of the narrowest velocity scale a friction column has (the
/// smooth sign's, and the smallest Stribeck velocity searched).
const VELOCITY_STEP: f64 = SIGN_SMOOTHING / 8.0;

/// The mean of `f` over sample `k`'s own interval, from half-way to the
/// previous sample to half-way to the next, the velocity going linearly
/// through `prev`, `v` and `next` (midpoint rule, steps of at most
/// [`VELOCITY_STEP`]). A friction law is sharp in the velocity: where the
/// velocity crosses a Stribeck velocity within one sample interval (0.03
/// rad/s crossed at 5 rad/s^2 in 6 ms, under one interval at 100 Hz),
/// `f` at the sample alone catches the breakaway or misses it, and the
/// impulse it gives the motion, which the accelerations carry, is lost.
/// The mean keeps it.
fn interval_mean(f: &impl Fn(f64) -> f64, prev: f64, v: f64, next: f64) -> f64 {
    let half = |a: f64, b: f64| {
        let m = ((b - a).abs() / VELOCITY_STEP).ceil().clamp(1.0, 256.0) as usize;
        (0..m)
            .map(|i| f(a + (b - a) * (i as f64 + 0.5) / m as f64))
            .sum::<f64>()
            / m as f64
    };
    0.5 * (half(0.5 * (prev + v), v) + half(v, 0.5 * (v + next)))
}

/// `f` of the lightly smoothed velocity, averaged over each sample's
/// interval ([`interval_mean`]), then filtered as the residual sees a
/// force of that law ([`through_motion`]).
fn smoothed_column<const N: usize>(
    sig: &Signals<N>,
    f: impl Fn(f64) -> f64,
) -> Vec<SVector<f64, N>> {
    let n = sig.t.len();
    let mut out = vec![SVector::<f64, N>::zeros(); n];
    let v = &sig.qd_light;
    for j in 0..N {
        let raw: Vec<f64> = (0..n)
            .map(|k| {
                let x = v[k][j];
                if !x.is_finite() {
                    return 0.0;
                }
                let near = |i: Option<usize>| {
                    i.and_then(|i| v.get(i))
                        .map(|y| y[j])
                        .filter(|y| y.is_finite())
                        .unwrap_or(x)
                };
                interval_mean(&f, near(k.checked_sub(1)), x, near(Some(k + 1)))
            })
            .collect();
        for (o, x) in out
            .iter_mut()
            .zip(through_motion(&sig.sg, &raw, sig.dt, sig.qd_measured))
        {
            o[j] = x;
        }
    }
    out
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
    /// Evaluates the shared quantities along `sig`.
    /// The model is evaluated `chunk` samples at a time (`along.rs`; 0:
    /// the default).
    pub fn new<R: Robot<N>>(robot: &R, sig: &Signals<N>, chunk: usize) -> Self {
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
            compliance: vec![SVector::zeros(); n],
            gravity: Vector3::from(R::GRAVITY),
            tip,
            tip_mass: Tip::body_mass::<R, N>(robot),
            qdd: sig.qdd.to_vec(),
            sign: smoothed_column(sig, smooth_sign),
            coulomb: COULOMB_WIDTHS[1..]
                .iter()
                .map(|&w| smoothed_column(sig, |v| (v / w).tanh()))
                .collect(),
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
        // machinery takes it per sample) was tried: right on the MAR's
        // backlash cases, but on the real Panda log it chose elastic joints
        // at joints 1-3 that predicted the held-out half worse (plain
        // shrink 0.429 to 0.409; `scripts/real-logs.sh`): there the other
        // joints' controllers hold them, which neither figure models.
        let own = b.inertia.map(|x| if x > 0.0 { 1.0 / x } else { 0.0 });
        for v in b.compliance.iter_mut() {
            *v = own;
        }
        // Columns built from the acceleration estimate are smoothed once
        // more, like the acceleration itself.
        smooth_in_place(&sig.sg, &mut b.qdd, (a, z));
        smooth_in_place(&sig.sg, &mut b.tip_acc, (a, z));
        if !b.tip_alpha.is_empty() {
            smooth_in_place(&sig.sg, &mut b.tip_alpha, (a, z));
        }
        smooth_in_place(&sig.sg, &mut b.k, (a, z));
        b
    }
}

#[cfg(test)]
mod tests {
    use super::interval_mean;

    /// A velocity crossing a narrow bump `exp(-(v/vs)^2)` at a steady
    /// acceleration, sampled every 10 ms: the interval means add up to the
    /// bump's impulse, `vs sqrt(pi) / a` (a Gaussian integral), wherever
    /// the samples fall; the values at the samples alone miss it or
    /// overshoot it by far.
    #[test]
    fn interval_means_keep_a_narrow_bumps_impulse() {
        let (vs, a, dt) = (0.01, 5.0, 0.01);
        let f = |v: f64| (-(v / vs).powi(2)).exp();
        let exact = vs * std::f64::consts::PI.sqrt() / a;
        let mut point_errors: Vec<f64> = Vec::new();
        for shift in [0.0, 0.25, 0.5] {
            let v = |k: i64| a * (k as f64 + shift) * dt;
            let mean: f64 = (-50..50)
                .map(|k| interval_mean(&f, v(k - 1), v(k), v(k + 1)) * dt)
                .sum();
            assert!(
                (mean / exact - 1.0).abs() < 0.01,
                "shift {shift}: {mean} against {exact}"
            );
            let point: f64 = (-50..50).map(|k| f(v(k)) * dt).sum();
            point_errors.push((point / exact - 1.0).abs());
        }
        assert!(point_errors.iter().any(|e| *e > 0.5), "{point_errors:?}");
    }
}
