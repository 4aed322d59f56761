//! What an integrator needs of a state: linear combinations, a weighted
//! error norm, a finiteness test. Implemented for `SVector<f64, M>` and for
//! a robot's `(q, qd)` pair, so states live on the stack at any size.

use nalgebra::SVector;

/// A state of an ODE, as a vector space element.
pub trait OdeState: Copy {
    /// `self + a x`
    fn axpy(&self, a: f64, x: &Self) -> Self;
    /// Root-mean-square of `e_i / (atol + rtol max(|y0_i|, |y1_i|))`.
    fn error_norm(e: &Self, y0: &Self, y1: &Self, rtol: f64, atol: f64) -> f64;
    /// Index of the first non-finite entry, if any.
    fn first_non_finite(&self) -> Option<usize>;
    /// Zero.
    fn zero() -> Self;
}

impl<const M: usize> OdeState for SVector<f64, M> {
    fn axpy(&self, a: f64, x: &Self) -> Self {
        self + x * a
    }
    fn error_norm(e: &Self, y0: &Self, y1: &Self, rtol: f64, atol: f64) -> f64 {
        let mut s = 0.0;
        for i in 0..M {
            let sc = atol + rtol * y0[i].abs().max(y1[i].abs());
            s += (e[i] / sc).powi(2);
        }
        (s / M.max(1) as f64).sqrt()
    }
    fn first_non_finite(&self) -> Option<usize> {
        self.iter().position(|x| !x.is_finite())
    }
    fn zero() -> Self {
        Self::zeros()
    }
}

/// Positions and velocities of a robot with N coordinates.
///
/// ```
/// use dynamics_runtime::ode::{JointState, OdeState};
/// let a = JointState::<2> { q: [1.0, 2.0].into(), qd: [0.0, 1.0].into() };
/// let b = a.axpy(2.0, &a);
/// assert_eq!(b.q[1], 6.0);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointState<const N: usize> {
    /// Positions.
    pub q: SVector<f64, N>,
    /// Velocities.
    pub qd: SVector<f64, N>,
}

impl<const N: usize> OdeState for JointState<N> {
    fn axpy(&self, a: f64, x: &Self) -> Self {
        JointState {
            q: self.q + x.q * a,
            qd: self.qd + x.qd * a,
        }
    }
    fn error_norm(e: &Self, y0: &Self, y1: &Self, rtol: f64, atol: f64) -> f64 {
        let mut s = 0.0;
        for i in 0..N {
            let sq = atol + rtol * y0.q[i].abs().max(y1.q[i].abs());
            let sv = atol + rtol * y0.qd[i].abs().max(y1.qd[i].abs());
            s += (e.q[i] / sq).powi(2) + (e.qd[i] / sv).powi(2);
        }
        (s / (2 * N).max(1) as f64).sqrt()
    }
    fn first_non_finite(&self) -> Option<usize> {
        self.q
            .iter()
            .position(|x| !x.is_finite())
            .or_else(|| self.qd.iter().position(|x| !x.is_finite()).map(|i| i + N))
    }
    fn zero() -> Self {
        JointState {
            q: SVector::zeros(),
            qd: SVector::zeros(),
        }
    }
}

/// Two states integrated together (e.g. a nominal motion and its perturbation).
impl<A: OdeState, B: OdeState> OdeState for (A, B) {
    fn axpy(&self, a: f64, x: &Self) -> Self {
        (self.0.axpy(a, &x.0), self.1.axpy(a, &x.1))
    }
    fn error_norm(e: &Self, y0: &Self, y1: &Self, rtol: f64, atol: f64) -> f64 {
        let a = A::error_norm(&e.0, &y0.0, &y1.0, rtol, atol);
        let b = B::error_norm(&e.1, &y0.1, &y1.1, rtol, atol);
        a.max(b)
    }
    fn first_non_finite(&self) -> Option<usize> {
        self.0
            .first_non_finite()
            .or_else(|| self.1.first_non_finite())
    }
    fn zero() -> Self {
        (A::zero(), B::zero())
    }
}
