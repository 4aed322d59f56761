//! Plain least squares, and the smoothing the diagnosis shares with the
//! generator (`crate::smoothing`).

use nalgebra::{DMatrix, DVector};

pub use crate::smoothing::SavitzkyGolay;

/// Plain least squares helper: the solution and residual sum of squares
/// of `x theta = y`, with columns in `free` (the rest fixed at zero).
pub(crate) fn least_squares(x: &DMatrix<f64>, y: &DVector<f64>) -> Option<DVector<f64>> {
    let xtx = x.transpose() * x;
    let xty = x.transpose() * y;
    xtx.cholesky().map(|c| c.solve(&xty))
}
