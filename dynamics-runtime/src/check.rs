//! Input checks shared by the runtime's entry points.

use nalgebra::SVector;

use crate::DynamicsError;

/// Fails with [`DynamicsError::NonFinite`] naming the first NaN or infinite entry.
pub(crate) fn finite<const N: usize>(
    quantity: &'static str,
    v: &SVector<f64, N>,
) -> Result<(), DynamicsError> {
    match v.iter().position(|x| !x.is_finite()) {
        Some(index) => Err(DynamicsError::NonFinite { quantity, index }),
        None => Ok(()),
    }
}
