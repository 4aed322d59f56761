//! The zero-order-hold discretisation of the state-space model.

use thiserror::Error;

use super::expm::expm;
use super::{BlockMatrix, StateSpace};

/// The discrete-time model `dx[k+1] = a dx[k] + b du[k]` of a
/// [`StateSpace`] whose input is held constant over each step `h`:
/// `exp([[A_c, B_c], [0, 0]] h) = [[a, b], [0, I]]`.
///
/// ```
/// use dynamics_runtime::linearize::{BlockMatrix, StateSpace};
/// use nalgebra::{Matrix1, Vector1};
/// // The double integrator q'' = u: a = [[1, h], [0, 1]], b = [[h^2/2], [h]].
/// let mut a = BlockMatrix::zeros();
/// a.blocks[0][1] = Matrix1::identity();
/// let mut b = BlockMatrix::zeros();
/// b.blocks[1][0] = Matrix1::identity();
/// let ss = StateSpace { a, b, qdd: Vector1::zeros() };
/// let d = ss.discretize(0.1).unwrap();
/// assert!((d.a[(0, 1)] - 0.1).abs() < 1e-16 && (d.a[(1, 1)] - 1.0).abs() < 1e-16);
/// assert!((d.b[(0, 0)] - 0.005).abs() < 1e-17 && (d.b[(1, 0)] - 0.1).abs() < 1e-16);
/// assert!(ss.discretize(0.0).is_err());
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DiscreteStateSpace<const N: usize> {
    /// `A_d = exp(A_c h)`.
    pub a: BlockMatrix<N, 2, 2>,
    /// `B_d = (integral_0^h exp(A_c s) ds) B_c`.
    pub b: BlockMatrix<N, 2, 1>,
    /// The step, s.
    pub h: f64,
}

/// Why a state-space model could not be discretised.
///
/// ```
/// use dynamics_runtime::linearize::DiscretizeError;
/// let e = DiscretizeError::Step { h: -0.1 };
/// assert_eq!(e.to_string(), "the step h = -0.1 s is not a finite positive number");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Error)]
pub enum DiscretizeError {
    /// The step is zero, negative, NaN or infinite.
    #[error("the step h = {h} s is not a finite positive number")]
    Step {
        /// The step asked for.
        h: f64,
    },
    /// A matrix of the continuous model holds NaN or an infinity.
    #[error("{matrix}[({row}, {col})] of the continuous model is not finite")]
    NonFinite {
        /// `A_c` or `B_c`.
        matrix: &'static str,
        /// Row of the first offending entry.
        row: usize,
        /// Column of the first offending entry.
        col: usize,
    },
    /// `exp([[A_c, B_c], [0, 0]] h)` overflows: the step is far too long
    /// for how fast the model grows.
    #[error(
        "the matrix exponential overflows: ||[[A_c, B_c], [0, 0]]|| h = {norm:e} (step too long)"
    )]
    Overflow {
        /// The max-row-sum norm of the augmented matrix times `h`.
        norm: f64,
    },
}

impl<const N: usize> StateSpace<N> {
    /// The zero-order-hold model for a step `h` (s), by the exponential of
    /// the augmented matrix `[[A_c, B_c], [0, 0]] h` (scaling and squaring
    /// with a (6, 6) Pade approximant; no heap).
    pub fn discretize(&self, h: f64) -> Result<DiscreteStateSpace<N>, DiscretizeError> {
        if !(h.is_finite() && h > 0.0) {
            return Err(DiscretizeError::Step { h });
        }
        if let Some((row, col)) = self.a.first_non_finite() {
            return Err(DiscretizeError::NonFinite {
                matrix: "A_c",
                row,
                col,
            });
        }
        if let Some((row, col)) = self.b.first_non_finite() {
            return Err(DiscretizeError::NonFinite {
                matrix: "B_c",
                row,
                col,
            });
        }
        let mut m = BlockMatrix::<N, 3, 3>::zeros();
        for r in 0..2 {
            for c in 0..2 {
                m.blocks[r][c] = self.a.blocks[r][c] * h;
            }
            m.blocks[r][2] = self.b.blocks[r][0] * h;
        }
        let e = expm(&m).ok_or(DiscretizeError::Overflow { norm: m.norm_inf() })?;
        let mut out = DiscreteStateSpace {
            a: BlockMatrix::zeros(),
            b: BlockMatrix::zeros(),
            h,
        };
        for r in 0..2 {
            for c in 0..2 {
                out.a.blocks[r][c] = e.blocks[r][c];
            }
            out.b.blocks[r][0] = e.blocks[r][2];
        }
        Ok(out)
    }
}
