//! The nominal model evaluated along a record: the one place each
//! per-sample model quantity of the diagnosis is computed (inverse
//! dynamics, the perturbation Jacobian K, the tip's Jacobian and bias
//! acceleration, the mass matrix's diagonal, the inertial regressor), over
//! a range of samples taken `chunk` samples at a time. Inverse dynamics,
//! K and the mass matrix go through the runtime's batch functions (vector
//! lanes, several samples per instruction); the chunk also bounds what a
//! stage that streams the record (the link columns, `candidates/links.rs`)
//! holds at once.

use std::ops::Range;

use nalgebra::{Matrix3, SMatrix, SVector, Vector3};

use crate::effects::Tip;
use dynamics_runtime::batch::Batch;
use dynamics_runtime::{DynamicsError, PerturbationJacobians, Robot};

/// Samples a chunk takes unless told otherwise ([`crate::diagnose::Options::chunk`]
/// 0): some 16 MB of a 7-joint arm's link regressors.
pub const CHUNK: usize = 4096;

/// The chunks of `range`, `chunk` samples each (the last one shorter; 0
/// reads as [`CHUNK`]).
pub fn chunks(range: Range<usize>, chunk: usize) -> impl Iterator<Item = Range<usize>> {
    let step = if chunk == 0 { CHUNK } else { chunk };
    range
        .clone()
        .step_by(step)
        .map(move |a| a..(a.saturating_add(step)).min(range.end))
}

/// The nominal model's efforts `ID(q, qd, qdd)` at the samples of `range`
/// into `out` (the other samples left as they are).
pub fn inverse_dynamics<R: Robot<N>, const N: usize>(
    robot: &R,
    [q, qd, qdd]: [&[SVector<f64, N>]; 3],
    range: Range<usize>,
    chunk: usize,
    out: &mut [SVector<f64, N>],
) {
    for c in chunks(range, chunk) {
        let (q, qd, qdd) = (&q[c.clone()], &qd[c.clone()], &qdd[c.clone()]);
        // Slices of one length: the batch cannot fail.
        if robot
            .inverse_dynamics_many(q, qd, qdd, &mut out[c])
            .is_err()
        {
            unreachable!("slices of one chunk have one length");
        }
    }
}

/// The perturbation Jacobian K = dF/dq at the samples of `range` into
/// `out`.
pub fn perturbation_k<R: Robot<N>, const N: usize>(
    robot: &R,
    [q, qd, qdd]: [&[SVector<f64, N>]; 3],
    range: Range<usize>,
    chunk: usize,
    out: &mut [SMatrix<f64, N, N>],
) {
    let mut kd = Vec::new();
    for c in chunks(range, chunk) {
        let (q, qd, qdd) = (&q[c.clone()], &qd[c.clone()], &qdd[c.clone()]);
        let zero = SMatrix::<f64, N, N>::zeros();
        kd.resize(c.len(), PerturbationJacobians { k: zero, d: zero });
        if robot
            .perturbation_jacobians_many(q, qd, qdd, &mut kd)
            .is_err()
        {
            unreachable!("slices of one chunk have one length");
        }
        for (o, pj) in out[c].iter_mut().zip(&kd) {
            *o = pj.k;
        }
    }
}

/// The tip's position Jacobian J and acceleration `J qdd + Jd qd` at the
/// samples of `range` into `jac` and `acc`.
pub fn tip_motion<R: Robot<N>, const N: usize>(
    robot: &R,
    tip: &Tip,
    [q, qd, qdd]: [&[SVector<f64, N>]; 3],
    range: Range<usize>,
    chunk: usize,
    jac: &mut [SMatrix<f64, 3, N>],
    acc: &mut [Vector3<f64>],
) {
    for c in chunks(range, chunk) {
        for k in c {
            let (_, j) = tip.position_jacobian(robot, &q[k]);
            jac[k] = j;
            acc[k] = j * qdd[k] + tip.bias_acceleration(robot, &q[k], &qd[k]);
        }
    }
}

/// The tip frame's orientation, angular-velocity Jacobian J_w and angular
/// acceleration `J_w qdd + Jd_w qd` at the samples of `range` into `rot`,
/// `jac` and `alpha` (left as they are for a point tip, which has no
/// frame); `frame_tip` gives the same values with `tip_motion`'s.
#[cfg(test)]
#[allow(clippy::too_many_arguments)]
pub fn tip_rotation<R: Robot<N>, const N: usize>(
    robot: &R,
    tip: &Tip,
    [q, qd, qdd]: [&[SVector<f64, N>]; 3],
    range: Range<usize>,
    rot: &mut [Matrix3<f64>],
    jac: &mut [SMatrix<f64, 3, N>],
    alpha: &mut [Vector3<f64>],
) {
    for k in range {
        if let Some((r, j)) = tip.angular_jacobian(robot, &q[k]) {
            rot[k] = r;
            jac[k] = j;
            alpha[k] = j * qdd[k] + tip.angular_bias(robot, &q[k], &qd[k]);
        }
    }
}

/// Where a frame tip's orientation, angular-velocity Jacobian and angular
/// acceleration are written, a sample each.
pub type FrameOut<'a, const N: usize> = (
    &'a mut [Matrix3<f64>],
    &'a mut [SMatrix<f64, 3, N>],
    &'a mut [Vector3<f64>],
);

/// A frame tip's motion at the samples of `range`: what [`tip_motion`]
/// and `tip_rotation` write, to the bit, each of the frame's poses
/// their central differences share evaluated once
/// (`Tip::frame_motion`). `false`, nothing written, for a point tip.
#[allow(clippy::too_many_arguments)]
pub fn frame_tip<R: Robot<N>, const N: usize>(
    robot: &R,
    tip: &Tip,
    [q, qd, qdd]: [&[SVector<f64, N>]; 3],
    range: Range<usize>,
    jac: &mut [SMatrix<f64, 3, N>],
    acc: &mut [Vector3<f64>],
    (rot, jac_w, alpha): FrameOut<'_, N>,
) -> bool {
    if !matches!(tip, Tip::Frame(_)) {
        return false;
    }
    for k in range {
        let Some(m) = tip.frame_motion(robot, &q[k], &qd[k], &qdd[k]) else {
            return false;
        };
        jac[k] = m.jac;
        acc[k] = m.acc;
        if let Some((r, j)) = m.rotation {
            rot[k] = r;
            jac_w[k] = j;
            alpha[k] = m.alpha;
        }
    }
    true
}

/// The mass matrix's diagonal at each state of `q` (a chunk or less)
/// added to `sum`, in the samples' order.
pub fn add_mass_diagonal<R: Robot<N>, const N: usize>(
    robot: &R,
    q: &[SVector<f64, N>],
    sum: &mut SVector<f64, N>,
) {
    let mut a = vec![SMatrix::<f64, N, N>::zeros(); q.len()];
    if robot.mass_matrix_many(q, &mut a).is_err() {
        unreachable!("slices of one length");
    }
    for m in &a {
        for j in 0..N {
            sum[j] += m[(j, j)];
        }
    }
}

/// Every link's inertial regressor at each sample of `range` (a chunk or
/// less), appended to `out` one entry a sample, `links` matrices each.
pub fn inertial_regressor<R: Robot<N>, const N: usize>(
    robot: &R,
    [q, qd, qdd]: [&[SVector<f64, N>]; 3],
    range: Range<usize>,
    links: usize,
    out: &mut impl Extend<Vec<SMatrix<f64, N, 10>>>,
) -> Result<(), DynamicsError> {
    for k in range {
        let mut y = vec![SMatrix::<f64, N, 10>::zeros(); links];
        robot.inertial_regressor(&q[k], &qd[k], &qdd[k], &mut y)?;
        out.extend(std::iter::once(y));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::chunks;

    /// The chunks cover the range once, in order, each at most `chunk`
    /// long; 0 takes the default; a chunk longer than the range is the
    /// whole range.
    #[test]
    fn chunks_cover_the_range_once() {
        assert_eq!(chunks(3..10, 4).collect::<Vec<_>>(), vec![3..7, 7..10]);
        assert_eq!(chunks(3..10, 1).count(), 7);
        assert_eq!(chunks(3..10, usize::MAX).collect::<Vec<_>>(), vec![3..10]);
        assert_eq!(
            chunks(0..10_000, 0).collect::<Vec<_>>(),
            vec![0..4096, 4096..8192, 8192..10_000]
        );
        assert_eq!(chunks(5..5, 3).count(), 0);
    }
}
