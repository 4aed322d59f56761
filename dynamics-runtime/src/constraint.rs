//! Program constraints on the motion, emitted by `robot!` from its
//! `constraint` items.

use nalgebra::{SMatrix, SVector};

use crate::Robot;

/// A robot with `M` program constraints `f(t, q) = 0` (dissertation, eq. 2.39)
/// whose Jacobian and second derivatives `robot!` derived symbolically.
///
/// ```
/// use dynamics_runtime::{Constrained, Robot};
/// use nalgebra::{Vector1, Vector2};
/// dynamics_macros::robot! {
///     pub robot Slider;
///     gravity = [0.0, -9.81, 0.0];
///     link base;
///     link a { mass = 1.0; }
///     link b { mass = 1.0; }
///     joint x = prismatic(base -> a) { transfer = [trans_x(q)]; }
///     joint y = prismatic(a -> b) { transfer = [trans_y(q)]; }
///     /// Stay on the line y = 2 x.
///     constraint line = y - 2.0 * x;
/// }
/// let s = Slider::default();
/// let q = Vector2::new(1.0, 2.0);
/// assert_eq!(s.constraint_residual(0.0, &q), Vector1::new(0.0));
/// assert_eq!(s.constraint_jacobian(0.0, &q)[(0, 0)], -2.0);
/// assert_eq!(Slider::CONSTRAINT_NAMES, ["line"]);
/// ```
pub trait Constrained<const N: usize, const M: usize>: Robot<N> {
    /// Constraint names, in declaration order.
    const CONSTRAINT_NAMES: [&'static str; M];
    /// f(t, q).
    fn constraint_residual(&self, t: f64, q: &SVector<f64, N>) -> SVector<f64, M>;
    /// J = df/dq.
    fn constraint_jacobian(&self, t: f64, q: &SVector<f64, N>) -> SMatrix<f64, M, N>;
    /// The part of d2f/dt2 that does not multiply qdd:
    /// `d2f/dt2 = J qdd + bias(t, q, qd)`.
    fn constraint_bias(&self, t: f64, q: &SVector<f64, N>, qd: &SVector<f64, N>)
        -> SVector<f64, M>;
}
