//! Forward-dynamics derivatives and the linearised state-space model, what
//! model-predictive controllers consume.
//!
//! The forward dynamics `qdd = f(q, qd, tau)` solve `F(q, qd, qdd) = A qdd -
//! Q(0) - Qqt1 - Qqt2 - tau = 0`. Differentiating that identity at fixed
//! `tau` gives, with the perturbation Jacobians `K = dF/dq` and `D = dF/dqd`
//! taken at the forward dynamics' own `qdd` (Pinocchio's
//! `computeABADerivatives`):
//!
//! ```text
//! d(qdd)/dq  = -A^-1 K(q, qd, qdd)
//! d(qdd)/dqd = -A^-1 D(q, qd, qdd)
//! d(qdd)/dtau = A^-1
//! ```
//!
//! computed from one `L D L^T` factorisation of `A` and `2N` (`3N` for the
//! state-space model) pairs of triangular solves; `A^-1` is never formed to be
//! multiplied. With the state `x = [q; qd]` and input `u = tau`, the
//! continuous-time linearisation `dx' = A_c dx + B_c du` has
//! `A_c = [[0, I], [d(qdd)/dq, d(qdd)/dqd]]` and `B_c = [[0], [A^-1]]`;
//! [`StateSpace::discretize`] turns it into the zero-order-hold model of a
//! step `h` (`dx[k+1] = A_d dx[k] + B_d du[k]`).
//!
//! Matrices of `2N` rows are [`BlockMatrix`]es of `N x N` blocks (stable Rust
//! cannot write `SMatrix<f64, {2 * N}, {2 * N}>`). Nothing here allocates, and
//! all of it but [`BlockMatrix::to_dmatrix`] (feature `std`) builds without std.
//!
//! ```
//! use dynamics_runtime::linearize;
//! dynamics_macros::robot! {
//!     pub robot Pendulum;
//!     gravity = [0.0, -9.81, 0.0];
//!     link base;
//!     link rod { mass = 1.0; com = [1.0, 0.0, 0.0]; }
//!     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
//! }
//! // Hanging straight down at rest: qdd = -g/l dq, a harmonic oscillator.
//! let down = nalgebra::Vector1::new(-std::f64::consts::FRAC_PI_2);
//! let zero = nalgebra::Vector1::zeros();
//! let ss = linearize::state_space(&Pendulum::default(), &down, &zero, &zero).unwrap();
//! assert!((ss.a[(1, 0)] + 9.81).abs() < 1e-12 && ss.a[(0, 1)] == 1.0);
//! assert!((ss.b[(1, 0)] - 1.0).abs() < 1e-12); // 1 / (m l^2)
//! let zoh = ss.discretize(0.01).unwrap();
//! let w = 9.81f64.sqrt();
//! assert!((zoh.a[(0, 0)] - (w * 0.01).cos()).abs() < 1e-14);
//! ```

mod blocks;
#[cfg(feature = "std")]
mod dense;
mod derivatives;
mod expm;
mod ldlt;
mod zoh;

pub use blocks::BlockMatrix;
pub use derivatives::{forward_dynamics_derivatives, state_space, ForwardDerivatives, StateSpace};
pub use zoh::{DiscreteStateSpace, DiscretizeError};
