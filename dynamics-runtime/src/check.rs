//! Input checks shared by the runtime's entry points.

use nalgebra::SVector;

use crate::DynamicsError;

/// Fails with [`DynamicsError::NonFinite`] naming the first NaN or infinite entry.
pub(crate) fn finite<const N: usize>(
    quantity: &'static str,
    v: &SVector<f64, N>,
) -> Result<(), DynamicsError> {
    match first_non_finite(v.as_slice()) {
        Some(index) => Err(DynamicsError::NonFinite { quantity, index }),
        None => Ok(()),
    }
}

/// The index of the first NaN or infinite entry of `x`. The common case,
/// all finite, is one pass without early exit (vector lanes, no branch per
/// entry); only a failure looks for the index.
#[inline]
pub(crate) fn first_non_finite(x: &[f64]) -> Option<usize> {
    if x.iter().fold(true, |ok, v| ok & v.is_finite()) {
        None
    } else {
        x.iter().position(|v| !v.is_finite())
    }
}
