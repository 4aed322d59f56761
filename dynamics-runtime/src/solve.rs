//! Solving the equations of motion for the accelerations.

use nalgebra::{SMatrix, SVector};

use crate::DynamicsError;

/// qdd = A^-1 (bias + u) by Cholesky (fixed size, no heap), with the bias
/// `Q + Qqt1 + Qqt2` of `MotionTerms::bias`; `q` names the state in errors.
pub(crate) fn accelerations<const N: usize>(
    a: &SMatrix<f64, N, N>,
    bias: &SVector<f64, N>,
    u: &SVector<f64, N>,
    q: &SVector<f64, N>,
) -> Result<SVector<f64, N>, DynamicsError> {
    let chol = a
        .cholesky()
        .ok_or_else(|| DynamicsError::SingularMassMatrix {
            q: crate::Coordinates::new(q.as_slice()),
        })?;
    let qdd = chol.solve(&(bias + u));
    match qdd.iter().position(|x| !x.is_finite()) {
        Some(index) => Err(DynamicsError::Diverged {
            quantity: "qdd",
            index,
        }),
        None => Ok(qdd),
    }
}
