//! Solving the equations of motion for the accelerations.

use nalgebra::SVector;

use crate::{DynamicsError, MotionTerms};

/// qdd = A^-1 (Q + Qqt1 + Qqt2 + u) by Cholesky (fixed size, no heap).
pub(crate) fn accelerations<const N: usize>(
    terms: &MotionTerms<N>,
    u: &SVector<f64, N>,
    q: &SVector<f64, N>,
) -> Result<SVector<f64, N>, DynamicsError> {
    let chol = terms
        .a
        .cholesky()
        .ok_or_else(|| DynamicsError::SingularMassMatrix {
            q: crate::Coordinates::new(q.as_slice()),
        })?;
    let qdd = chol.solve(&(terms.bias() + u));
    match qdd.iter().position(|x| !x.is_finite()) {
        Some(index) => Err(DynamicsError::Diverged {
            quantity: "qdd",
            index,
        }),
        None => Ok(qdd),
    }
}
