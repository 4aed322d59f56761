//! The batch functions over all cores (feature `rayon`): the states cut
//! into blocks of [`BLOCK`], each block a call of the single-core batch
//! function on one worker. Below [`PARALLEL_FROM`] states one call on the
//! calling thread (handing work to other threads costs some microseconds,
//! the time of a few hundred states).

use core::ops::Range;

use nalgebra::{SMatrix, SVector};
use rayon::prelude::*;

use super::{length, BatchError, Level};
use crate::linearize::ForwardDerivatives;
use crate::{PerturbationJacobians, Robot};

/// States per block given to one worker.
pub const BLOCK: usize = 256;

/// Fewest states worth spreading over threads.
pub const PARALLEL_FROM: usize = 2048;

/// `f(states, out block)` for the blocks of [`BLOCK`] states of `out` on
/// rayon's workers; the first error, its state counted from the start.
fn in_blocks<T: Send>(
    out: &mut [T],
    f: impl Fn(Range<usize>, &mut [T]) -> Result<(), BatchError> + Sync,
) -> Result<(), BatchError> {
    let results: Vec<(usize, Result<(), BatchError>)> = out
        .par_chunks_mut(BLOCK)
        .enumerate()
        .map(|(b, o)| {
            let s = b * BLOCK;
            (s, f(s..s + o.len(), o))
        })
        .collect();
    for (start, r) in results {
        match r {
            Ok(()) => {}
            Err(BatchError::State { state, error }) => {
                return Err(BatchError::State {
                    state: start + state,
                    error,
                })
            }
            Err(e) => return Err(e),
        }
    }
    Ok(())
}

/// [`super::inverse_dynamics`] over all cores.
///
/// ```
/// use dynamics_runtime::batch::{parallel, Level};
/// use dynamics_runtime::Robot;
/// use nalgebra::Vector1;
/// dynamics_macros::robot! {
///     pub robot Pendulum;
///     gravity = [0.0, -9.81, 0.0];
///     link base;
///     link rod { mass = 1.0; com = [1.0, 0.0, 0.0]; }
///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
/// }
/// let p = Pendulum::default();
/// let q: Vec<_> = (0..5000).map(|k| Vector1::new(1e-3 * k as f64)).collect();
/// let z = vec![Vector1::zeros(); 5000];
/// let mut tau = vec![Vector1::zeros(); 5000];
/// parallel::inverse_dynamics(&p, Level::detect(), &q, &z, &z, &mut tau)?;
/// assert_eq!(tau[4321], p.inverse_dynamics(&q[4321], &z[4321], &z[4321]));
/// # Ok::<(), dynamics_runtime::batch::BatchError>(())
/// ```
pub fn inverse_dynamics<R: Robot<N> + Sync, const N: usize>(
    robot: &R,
    level: Level,
    q: &[SVector<f64, N>],
    qd: &[SVector<f64, N>],
    qdd: &[SVector<f64, N>],
    out: &mut [SVector<f64, N>],
) -> Result<(), BatchError> {
    let n = q.len();
    length("qd", qd, n)?;
    length("qdd", qdd, n)?;
    length("out", out, n)?;
    if n < PARALLEL_FROM {
        return super::inverse_dynamics(robot, level, q, qd, qdd, out);
    }
    in_blocks(out, |r, o| {
        super::inverse_dynamics(
            robot,
            level,
            &q[r.clone()],
            &qd[r.clone()],
            &qdd[r.clone()],
            o,
        )
    })
}

/// [`super::mass_matrix`] over all cores.
///
/// ```
/// use dynamics_runtime::batch::{parallel, Level};
/// use dynamics_runtime::Robot;
/// use nalgebra::{Matrix1, Vector1};
/// dynamics_macros::robot! {
///     pub robot Pendulum;
///     gravity = [0.0, -9.81, 0.0];
///     link base;
///     link rod { mass = 2.0; com = [0.5, 0.0, 0.0]; }
///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
/// }
/// let q = vec![Vector1::new(0.1); 3000];
/// let mut a = vec![Matrix1::zeros(); 3000];
/// parallel::mass_matrix(&Pendulum::default(), Level::detect(), &q, &mut a)?;
/// assert_eq!(a[2999][(0, 0)], 0.5);
/// # Ok::<(), dynamics_runtime::batch::BatchError>(())
/// ```
pub fn mass_matrix<R: Robot<N> + Sync, const N: usize>(
    robot: &R,
    level: Level,
    q: &[SVector<f64, N>],
    out: &mut [SMatrix<f64, N, N>],
) -> Result<(), BatchError> {
    length("out", out, q.len())?;
    if q.len() < PARALLEL_FROM {
        return super::mass_matrix(robot, level, q, out);
    }
    in_blocks(out, |r, o| {
        super::mass_matrix(robot, level, &q[r.clone()], o)
    })
}

/// [`super::perturbation_jacobians`] over all cores.
///
/// ```
/// use dynamics_runtime::batch::{parallel, Level};
/// use dynamics_runtime::Robot;
/// use nalgebra::Vector1;
/// dynamics_macros::robot! {
///     pub robot Pendulum;
///     gravity = [0.0, -9.81, 0.0];
///     link base;
///     link rod { mass = 1.0; com = [1.0, 0.0, 0.0]; }
///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; damping = 0.5; }
/// }
/// let p = Pendulum::default();
/// let z = vec![Vector1::zeros(); 3000];
/// let mut kd = vec![p.perturbation_jacobians(&z[0], &z[0], &z[0]); 3000];
/// parallel::perturbation_jacobians(&p, Level::detect(), &z, &z, &z, &mut kd)?;
/// assert_eq!(kd[2500].d[(0, 0)], 0.5);
/// # Ok::<(), dynamics_runtime::batch::BatchError>(())
/// ```
pub fn perturbation_jacobians<R: Robot<N> + Sync, const N: usize>(
    robot: &R,
    level: Level,
    q: &[SVector<f64, N>],
    qd: &[SVector<f64, N>],
    qdd: &[SVector<f64, N>],
    out: &mut [PerturbationJacobians<N>],
) -> Result<(), BatchError> {
    let n = q.len();
    length("qd", qd, n)?;
    length("qdd", qdd, n)?;
    length("out", out, n)?;
    if n < PARALLEL_FROM {
        return super::perturbation_jacobians(robot, level, q, qd, qdd, out);
    }
    in_blocks(out, |r, o| {
        super::perturbation_jacobians(
            robot,
            level,
            &q[r.clone()],
            &qd[r.clone()],
            &qdd[r.clone()],
            o,
        )
    })
}

/// [`super::forward_dynamics_derivatives`] over all cores; an error names
/// the first failing state of the whole batch (blocks after it may be
/// written).
///
/// ```
/// use dynamics_runtime::batch::{parallel, Level};
/// use dynamics_runtime::linearize::forward_dynamics_derivatives;
/// use nalgebra::Vector1;
/// dynamics_macros::robot! {
///     pub robot Pendulum;
///     gravity = [0.0, -9.81, 0.0];
///     link base;
///     link rod { mass = 1.0; com = [1.0, 0.0, 0.0]; }
///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
/// }
/// let p = Pendulum::default();
/// let mut q = vec![Vector1::new(0.2); 3000];
/// let z = vec![Vector1::zeros(); 3000];
/// let mut d = vec![forward_dynamics_derivatives(&p, &q[0], &z[0], &z[0])?; 3000];
/// q[2100][0] = f64::NAN;
/// let e = parallel::forward_dynamics_derivatives(&p, Level::detect(), &q, &z, &z, &mut d);
/// assert_eq!(e.unwrap_err().to_string(), "state 2100: q[0] is not finite (NaN or infinite)");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn forward_dynamics_derivatives<R: Robot<N> + Sync, const N: usize>(
    robot: &R,
    level: Level,
    q: &[SVector<f64, N>],
    qd: &[SVector<f64, N>],
    tau: &[SVector<f64, N>],
    out: &mut [ForwardDerivatives<N>],
) -> Result<(), BatchError> {
    let n = q.len();
    length("qd", qd, n)?;
    length("tau", tau, n)?;
    length("out", out, n)?;
    if n < PARALLEL_FROM {
        return super::forward_dynamics_derivatives(robot, level, q, qd, tau, out);
    }
    in_blocks(out, |r, o| {
        super::forward_dynamics_derivatives(robot, level, &q[r.clone()], &qd[r.clone()], &tau[r], o)
    })
}
