//! Many states per call: the model's outputs over slices of states, in
//! vector lanes ([`crate::lanes`]) at the widest [`Level`] the CPU has.
//!
//! Each function takes the states as slices of nalgebra vectors (one entry
//! per state, all slices of one length) and writes one output per state.
//! Inside, the states are taken `WIDTH` at a time into lanes
//! (structure of arrays), the robot's `*_lanes` method runs on them, and
//! the lanes are written back; a last group that does not fill the lanes
//! is padded with its last state (the padding is computed and dropped).
//! The results are those of the scalar methods of [`Robot`], bit for bit
//! where the build has FMA (`-C target-cpu=native` on any x86-64 since
//! 2013); without it the lanes' multiply-adds are fused and the scalar
//! code's are not, and results agree to a few ulp.
//!
//! The [`Batch`] methods `inverse_dynamics_many` etc. (every robot has
//! them) call these at [`Level::detect`]; the functions here take the
//! level, for comparisons.
//! With the feature `rayon`, `parallel` spreads large batches over all
//! cores.

mod dispatch;
mod ldlt;
#[cfg(feature = "rayon")]
pub mod parallel;

use nalgebra::{SMatrix, SVector};
use thiserror::Error;

use dispatch::Kernel;
pub use dispatch::Level;

use crate::lanes::Lanes;
use crate::linearize::ForwardDerivatives;
use crate::{DynamicsError, MotionTerms, PerturbationJacobians, Robot};

/// Why a batch call failed.
///
/// ```
/// use dynamics_runtime::batch::BatchError;
/// let e = BatchError::Length { quantity: "qd", expected: 3, found: 2 };
/// assert_eq!(e.to_string(), "qd has 2 states, 3 expected (one per state of q)");
/// ```
#[derive(Debug, Clone, PartialEq, Error)]
pub enum BatchError {
    /// A slice's length differs from `q`'s.
    #[error("{quantity} has {found} states, {expected} expected (one per state of q)")]
    Length {
        /// Which argument.
        quantity: &'static str,
        /// `q.len()`.
        expected: usize,
        /// Its length.
        found: usize,
    },
    /// The scalar function fails at this state (the outputs of the states
    /// before it are written; the others' are unspecified).
    #[error("state {state}: {error}")]
    State {
        /// Index of the state in the slices.
        state: usize,
        /// The scalar function's error there.
        #[source]
        error: DynamicsError,
    },
}

/// Fails unless `x` has `expected` entries.
fn length<T>(quantity: &'static str, x: &[T], expected: usize) -> Result<(), BatchError> {
    if x.len() == expected {
        Ok(())
    } else {
        Err(BatchError::Length {
            quantity,
            expected,
            found: x.len(),
        })
    }
}

/// States `start..start + WIDTH` of `x` in lanes (past the end: the last).
#[inline(always)]
fn gather<L: Lanes, const N: usize>(x: &[SVector<f64, N>], start: usize) -> [L; N] {
    let end = (start + L::WIDTH).min(x.len());
    L::load_states(&x[start..end], |v| &v.data.0[0])
}

/// Writes the lanes of `values` into the states of `out` (at most
/// `WIDTH`), each state's part `field` of it: a matrix's columns
/// (`values[column][row]`, column-major as nalgebra's storage), a vector
/// as one column.
#[inline(always)]
fn store<L: Lanes, T, const R: usize, const C: usize>(
    values: &[[L; R]; C],
    out: &mut [T],
    field: impl Fn(&mut T) -> &mut [[f64; R]; C],
) {
    L::store_states(values, out, field);
}

/// `Q(0) + (Qqt1 + Qqt2) + tau` (the scalar code's order).
#[inline(always)]
fn rhs<L: Lanes, const N: usize>(q0: &[L; N], qqt: &[L; N], tau: &[L; N]) -> [L; N] {
    let mut b = *q0;
    for j in 0..N {
        b[j] = b[j] + qqt[j] + tau[j];
    }
    b
}

/// `sum(x * 0)` over `values`: 0 in the lanes where every value is finite,
/// NaN where one is not (`inf * 0` and `NaN * 0` are NaN); one multiply-add
/// a value for all lanes instead of a test per value and state.
#[inline(always)]
fn finite_probe<L: Lanes>(values: &[L]) -> L {
    let zero = L::splat(0.0);
    let mut acc = zero;
    for &v in values {
        acc = v.mul_add(zero, acc);
    }
    acc
}

/// The batch functions as methods of every robot, at [`Level::detect`]:
/// `use dynamics_runtime::batch::Batch;` and call `robot.inverse_dynamics_many(..)`.
///
/// ```
/// use dynamics_runtime::batch::Batch;
/// use nalgebra::Vector1;
/// dynamics_macros::robot! {
///     pub robot Pendulum;
///     gravity = [0.0, -9.81, 0.0];
///     link base;
///     link rod { mass = 1.0; com = [1.0, 0.0, 0.0]; }
///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
/// }
/// let z = [Vector1::zeros(); 9];
/// let mut tau = [Vector1::zeros(); 9];
/// Pendulum::default().inverse_dynamics_many(&z, &z, &z, &mut tau)?;
/// assert!((tau[8][0] - 9.81).abs() < 1e-14);
/// # Ok::<(), dynamics_runtime::batch::BatchError>(())
/// ```
pub trait Batch<const N: usize>: Robot<N> + Sized {
    /// Inverse dynamics of many states in vector lanes at the widest
    /// [`Level`] this CPU has ([`inverse_dynamics`]).
    ///
    /// ```
    /// use dynamics_runtime::batch::Batch;
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
    /// let q: Vec<_> = (0..100).map(|k| Vector1::new(0.01 * k as f64)).collect();
    /// let z = vec![Vector1::zeros(); 100];
    /// let mut tau = vec![Vector1::zeros(); 100];
    /// p.inverse_dynamics_many(&q, &z, &z, &mut tau)?;
    /// assert_eq!(tau[99], p.inverse_dynamics(&q[99], &z[99], &z[99]));
    /// # Ok::<(), dynamics_runtime::batch::BatchError>(())
    /// ```
    fn inverse_dynamics_many(
        &self,
        q: &[SVector<f64, N>],
        qd: &[SVector<f64, N>],
        qdd: &[SVector<f64, N>],
        out: &mut [SVector<f64, N>],
    ) -> Result<(), BatchError> {
        inverse_dynamics(self, Level::detect(), q, qd, qdd, out)
    }
    /// The inertia matrix of many states ([`mass_matrix`]).
    ///
    /// ```
    /// use dynamics_runtime::batch::Batch;
    /// use dynamics_runtime::Robot;
    /// use nalgebra::{Matrix1, Vector1};
    /// dynamics_macros::robot! {
    ///     pub robot Pendulum;
    ///     gravity = [0.0, -9.81, 0.0];
    ///     link base;
    ///     link rod { mass = 2.0; com = [0.5, 0.0, 0.0]; }
    ///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
    /// }
    /// let mut a = vec![Matrix1::zeros(); 3];
    /// Pendulum::default().mass_matrix_many(&[Vector1::new(0.1); 3], &mut a)?;
    /// assert_eq!(a[2][(0, 0)], 0.5);
    /// # Ok::<(), dynamics_runtime::batch::BatchError>(())
    /// ```
    fn mass_matrix_many(
        &self,
        q: &[SVector<f64, N>],
        out: &mut [SMatrix<f64, N, N>],
    ) -> Result<(), BatchError> {
        mass_matrix(self, Level::detect(), q, out)
    }
    /// A, the bias terms and Q(0) of many states ([`motion_terms`]).
    ///
    /// ```
    /// use dynamics_runtime::batch::Batch;
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
    /// let z = [Vector1::zeros(); 2];
    /// let mut terms = [p.motion_terms(&z[0], &z[0]); 2];
    /// p.motion_terms_many(&z, &z, &mut terms)?;
    /// assert!((terms[1].bias()[0] + 9.81).abs() < 1e-15);
    /// # Ok::<(), dynamics_runtime::batch::BatchError>(())
    /// ```
    fn motion_terms_many(
        &self,
        q: &[SVector<f64, N>],
        qd: &[SVector<f64, N>],
        out: &mut [MotionTerms<N>],
    ) -> Result<(), BatchError> {
        motion_terms(self, Level::detect(), q, qd, out)
    }
    /// K and D of many states ([`perturbation_jacobians`]).
    ///
    /// ```
    /// use dynamics_runtime::batch::Batch;
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
    /// let z = [Vector1::zeros(); 2];
    /// let mut kd = [p.perturbation_jacobians(&z[0], &z[0], &z[0]); 2];
    /// p.perturbation_jacobians_many(&z, &z, &z, &mut kd)?;
    /// assert_eq!(kd[1].d[(0, 0)], 0.5);
    /// # Ok::<(), dynamics_runtime::batch::BatchError>(())
    /// ```
    fn perturbation_jacobians_many(
        &self,
        q: &[SVector<f64, N>],
        qd: &[SVector<f64, N>],
        qdd: &[SVector<f64, N>],
        out: &mut [PerturbationJacobians<N>],
    ) -> Result<(), BatchError> {
        perturbation_jacobians(self, Level::detect(), q, qd, qdd, out)
    }
    /// Forward dynamics of many states ([`forward_dynamics`]).
    ///
    /// ```
    /// use dynamics_runtime::batch::Batch;
    /// use dynamics_runtime::Robot;
    /// use nalgebra::Vector1;
    /// dynamics_macros::robot! {
    ///     pub robot Pendulum;
    ///     gravity = [0.0, -9.81, 0.0];
    ///     link base;
    ///     link rod { mass = 1.0; com = [1.0, 0.0, 0.0]; }
    ///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
    /// }
    /// let z = [Vector1::zeros(); 3];
    /// let mut qdd = [Vector1::zeros(); 3];
    /// Pendulum::default().forward_dynamics_many(&z, &z, &z, &mut qdd)?;
    /// assert!((qdd[2][0] + 9.81).abs() < 1e-14);
    /// # Ok::<(), dynamics_runtime::batch::BatchError>(())
    /// ```
    fn forward_dynamics_many(
        &self,
        q: &[SVector<f64, N>],
        qd: &[SVector<f64, N>],
        tau: &[SVector<f64, N>],
        out: &mut [SVector<f64, N>],
    ) -> Result<(), BatchError> {
        forward_dynamics(self, Level::detect(), q, qd, tau, out)
    }
    /// Forward dynamics and their derivatives of many states
    /// ([`forward_dynamics_derivatives`]).
    ///
    /// ```
    /// use dynamics_runtime::batch::Batch;
    /// use dynamics_runtime::{linearize, Robot};
    /// use nalgebra::Vector1;
    /// dynamics_macros::robot! {
    ///     pub robot Pendulum;
    ///     gravity = [0.0, -9.81, 0.0];
    ///     link base;
    ///     link rod { mass = 1.0; com = [1.0, 0.0, 0.0]; }
    ///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; damping = 0.5; }
    /// }
    /// let p = Pendulum::default();
    /// let z = [Vector1::zeros(); 3];
    /// let mut d = [linearize::forward_dynamics_derivatives(&p, &z[0], &z[0], &z[0])?; 3];
    /// p.forward_dynamics_derivatives_many(&z, &z, &z, &mut d)?;
    /// assert!((d[2].ddq_dv[(0, 0)] + 0.5).abs() < 1e-15);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    fn forward_dynamics_derivatives_many(
        &self,
        q: &[SVector<f64, N>],
        qd: &[SVector<f64, N>],
        tau: &[SVector<f64, N>],
        out: &mut [ForwardDerivatives<N>],
    ) -> Result<(), BatchError> {
        forward_dynamics_derivatives(self, Level::detect(), q, qd, tau, out)
    }
}

impl<R: Robot<N>, const N: usize> Batch<N> for R {}

/// Inverse dynamics of every state (see [`Robot::inverse_dynamics`]).
///
/// ```
/// use dynamics_runtime::batch::{self, Level};
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
/// let q: Vec<_> = (0..10).map(|k| Vector1::new(0.1 * k as f64)).collect();
/// let zero = vec![Vector1::zeros(); 10];
/// let mut tau = vec![Vector1::zeros(); 10];
/// batch::inverse_dynamics(&p, Level::detect(), &q, &zero, &zero, &mut tau)?;
/// assert_eq!(tau[7], p.inverse_dynamics(&q[7], &zero[7], &zero[7]));
/// # Ok::<(), dynamics_runtime::batch::BatchError>(())
/// ```
pub fn inverse_dynamics<R: Robot<N>, const N: usize>(
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
    struct K<'a, R, const N: usize> {
        robot: &'a R,
        x: [&'a [SVector<f64, N>]; 3],
        out: &'a mut [SVector<f64, N>],
    }
    impl<R: Robot<N>, const N: usize> Kernel for K<'_, R, N> {
        type Output = ();
        #[inline(always)]
        fn run<L: Lanes>(self) {
            let [q, qd, qdd] = self.x;
            for s in (0..q.len()).step_by(L::WIDTH) {
                let m = L::WIDTH.min(q.len() - s);
                let tau = self.robot.inverse_dynamics_lanes(
                    &gather::<L, N>(q, s),
                    &gather(qd, s),
                    &gather(qdd, s),
                );
                store(core::array::from_ref(&tau), &mut self.out[s..s + m], |o| {
                    &mut o.data.0
                });
            }
        }
    }
    dispatch::run(
        level,
        K {
            robot,
            x: [q, qd, qdd],
            out,
        },
    );
    Ok(())
}

/// The inertia matrix of every state (see [`Robot::mass_matrix`]).
///
/// ```
/// use dynamics_runtime::batch::{self, Level};
/// use dynamics_runtime::Robot;
/// use nalgebra::{Matrix1, Vector1};
/// dynamics_macros::robot! {
///     pub robot Pendulum;
///     gravity = [0.0, -9.81, 0.0];
///     link base;
///     link rod { mass = 2.0; com = [0.5, 0.0, 0.0]; }
///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
/// }
/// let q = vec![Vector1::new(0.3); 5];
/// let mut a = vec![Matrix1::zeros(); 5];
/// batch::mass_matrix(&Pendulum::default(), Level::detect(), &q, &mut a)?;
/// assert_eq!(a[4], Pendulum::default().mass_matrix(&q[4]));
/// # Ok::<(), dynamics_runtime::batch::BatchError>(())
/// ```
pub fn mass_matrix<R: Robot<N>, const N: usize>(
    robot: &R,
    level: Level,
    q: &[SVector<f64, N>],
    out: &mut [SMatrix<f64, N, N>],
) -> Result<(), BatchError> {
    length("out", out, q.len())?;
    struct K<'a, R, const N: usize> {
        robot: &'a R,
        q: &'a [SVector<f64, N>],
        out: &'a mut [SMatrix<f64, N, N>],
    }
    impl<R: Robot<N>, const N: usize> Kernel for K<'_, R, N> {
        type Output = ();
        #[inline(always)]
        fn run<L: Lanes>(self) {
            for s in (0..self.q.len()).step_by(L::WIDTH) {
                let m = L::WIDTH.min(self.q.len() - s);
                let a = self.robot.mass_matrix_lanes(&gather::<L, N>(self.q, s));
                store(&a, &mut self.out[s..s + m], |o| &mut o.data.0);
            }
        }
    }
    dispatch::run(level, K { robot, q, out });
    Ok(())
}

/// A, Qqt1 + Qqt2 and Q(0) of every state (see [`Robot::motion_terms`]).
///
/// ```
/// use dynamics_runtime::batch::{self, Level};
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
/// let (q, qd) = (vec![Vector1::new(0.2); 3], vec![Vector1::new(-1.0); 3]);
/// let mut terms = vec![p.motion_terms(&q[0], &qd[0]); 3];
/// batch::motion_terms(&p, Level::detect(), &q, &qd, &mut terms)?;
/// assert_eq!(terms[2], p.motion_terms(&q[2], &qd[2]));
/// # Ok::<(), dynamics_runtime::batch::BatchError>(())
/// ```
pub fn motion_terms<R: Robot<N>, const N: usize>(
    robot: &R,
    level: Level,
    q: &[SVector<f64, N>],
    qd: &[SVector<f64, N>],
    out: &mut [MotionTerms<N>],
) -> Result<(), BatchError> {
    length("qd", qd, q.len())?;
    length("out", out, q.len())?;
    struct K<'a, R, const N: usize> {
        robot: &'a R,
        x: [&'a [SVector<f64, N>]; 2],
        out: &'a mut [MotionTerms<N>],
    }
    impl<R: Robot<N>, const N: usize> Kernel for K<'_, R, N> {
        type Output = ();
        #[inline(always)]
        fn run<L: Lanes>(self) {
            let [q, qd] = self.x;
            for s in (0..q.len()).step_by(L::WIDTH) {
                let m = L::WIDTH.min(q.len() - s);
                let (a, qqt, q0) = self
                    .robot
                    .motion_terms_lanes(&gather::<L, N>(q, s), &gather(qd, s));
                let out = &mut self.out[s..s + m];
                store(&a, out, |o| &mut o.a.data.0);
                store(core::array::from_ref(&qqt), out, |o| &mut o.qqt.data.0);
                store(core::array::from_ref(&q0), out, |o| &mut o.q0.data.0);
            }
        }
    }
    dispatch::run(
        level,
        K {
            robot,
            x: [q, qd],
            out,
        },
    );
    Ok(())
}

/// K and D of every state (see [`Robot::perturbation_jacobians`]).
///
/// ```
/// use dynamics_runtime::batch::{self, Level};
/// use dynamics_runtime::Robot;
/// use nalgebra::Vector2;
/// dynamics_macros::robot! {
///     pub robot TwoLink;
///     gravity = [0.0, -9.81, 0.0];
///     link base;
///     link l1 { mass = 1.0; com = [0.5, 0.0, 0.0]; inertia = [1e-3, 0.08, 0.08]; }
///     link l2 { mass = 1.0; com = [0.5, 0.0, 0.0]; inertia = [1e-3, 0.08, 0.08]; }
///     joint j1 = revolute(base -> l1) { transfer = [rot_z(q)]; }
///     joint j2 = revolute(l1 -> l2) { transfer = [trans_x(1.0), rot_z(q)]; }
/// }
/// let r = TwoLink::default();
/// let x: Vec<_> = (0..9).map(|k| Vector2::new(0.1 * k as f64, -0.3)).collect();
/// let mut kd = vec![r.perturbation_jacobians(&x[0], &x[0], &x[0]); 9];
/// batch::perturbation_jacobians(&r, Level::detect(), &x, &x, &x, &mut kd)?;
/// assert_eq!(kd[8], r.perturbation_jacobians(&x[8], &x[8], &x[8]));
/// # Ok::<(), dynamics_runtime::batch::BatchError>(())
/// ```
pub fn perturbation_jacobians<R: Robot<N>, const N: usize>(
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
    struct K<'a, R, const N: usize> {
        robot: &'a R,
        x: [&'a [SVector<f64, N>]; 3],
        out: &'a mut [PerturbationJacobians<N>],
    }
    impl<R: Robot<N>, const N: usize> Kernel for K<'_, R, N> {
        type Output = ();
        #[inline(always)]
        fn run<L: Lanes>(self) {
            let [q, qd, qdd] = self.x;
            for s in (0..q.len()).step_by(L::WIDTH) {
                let m = L::WIDTH.min(q.len() - s);
                let (k, d) = self.robot.perturbation_jacobians_lanes(
                    &gather::<L, N>(q, s),
                    &gather(qd, s),
                    &gather(qdd, s),
                );
                let out = &mut self.out[s..s + m];
                store(&k, out, |o| &mut o.k.data.0);
                store(&d, out, |o| &mut o.d.data.0);
            }
        }
    }
    dispatch::run(
        level,
        K {
            robot,
            x: [q, qd, qdd],
            out,
        },
    );
    Ok(())
}

/// The forward dynamics of every state and their derivatives (see
/// [`crate::linearize::forward_dynamics_derivatives`]: one pass for A, the
/// bias, qdd, K and D; `A = L D L^T`, then `-A^-1 K`, `-A^-1 D`).
///
/// Errors at the first state where the scalar function fails (an input
/// that is not finite, an inertia matrix that is not positive definite, a
/// result that is not finite), naming it; the outputs of the states before
/// it are written.
///
/// ```
/// use dynamics_runtime::batch::{self, Level};
/// use dynamics_runtime::linearize::forward_dynamics_derivatives;
/// use nalgebra::Vector2;
/// dynamics_macros::robot! {
///     pub robot TwoLink;
///     gravity = [0.0, -9.81, 0.0];
///     link base;
///     link l1 { mass = 1.0; com = [0.5, 0.0, 0.0]; inertia = [1e-3, 0.08, 0.08]; }
///     link l2 { mass = 1.0; com = [0.5, 0.0, 0.0]; inertia = [1e-3, 0.08, 0.08]; }
///     joint j1 = revolute(base -> l1) { transfer = [rot_z(q)]; }
///     joint j2 = revolute(l1 -> l2) { transfer = [trans_x(1.0), rot_z(q)]; }
/// }
/// let r = TwoLink::default();
/// let x: Vec<_> = (0..6).map(|k| Vector2::new(0.1 * k as f64, -0.3)).collect();
/// let mut out = vec![forward_dynamics_derivatives(&r, &x[0], &x[0], &x[0])?; 6];
/// batch::forward_dynamics_derivatives(&r, Level::detect(), &x, &x, &x, &mut out)?;
/// assert_eq!(out[5], forward_dynamics_derivatives(&r, &x[5], &x[5], &x[5])?);
///
/// let mut bad = x.clone();
/// bad[3][1] = f64::NAN;
/// let e = batch::forward_dynamics_derivatives(&r, Level::detect(), &bad, &x, &x, &mut out);
/// assert_eq!(e.unwrap_err().to_string(), "state 3: q[1] is not finite (NaN or infinite)");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn forward_dynamics_derivatives<R: Robot<N>, const N: usize>(
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
    struct K<'a, R, const N: usize> {
        robot: &'a R,
        x: [&'a [SVector<f64, N>]; 3],
        out: &'a mut [ForwardDerivatives<N>],
    }
    impl<R: Robot<N>, const N: usize> Kernel for K<'_, R, N> {
        type Output = Result<(), BatchError>;
        #[inline(always)]
        fn run<L: Lanes>(self) -> Result<(), BatchError> {
            let [q, qd, tau] = self.x;
            for s in (0..q.len()).step_by(L::WIDTH) {
                let m = L::WIDTH.min(q.len() - s);
                let t = gather::<L, N>(tau, s);
                let mut factors = None;
                let (qdd, k, d) = self.robot.motion_and_jacobians_lanes(
                    &gather::<L, N>(q, s),
                    &gather(qd, s),
                    // Inlined: as a function of its own it would be compiled
                    // without the lanes' CPU features.
                    #[inline(always)]
                    |a, qqt, q0| {
                        let (f, ok) = ldlt::Ldlt::new(a);
                        let qdd = f.solve(&rhs(q0, qqt, &t));
                        factors = Some((f, ok));
                        qdd
                    },
                );
                let Some((f, ok)) = factors else {
                    continue;
                };
                // -A^-1 K and -A^-1 D column by column, in place.
                let (mut ddq_dq, mut ddq_dv) = (k, d);
                for c in 0..N {
                    f.solve_in_place(&mut ddq_dq[c], -1.0);
                    f.solve_in_place(&mut ddq_dv[c], -1.0);
                }
                let out = &mut self.out[s..s + m];
                store(core::array::from_ref(&qdd), out, |o| &mut o.qdd.data.0);
                store(&ddq_dq, out, |o| &mut o.ddq_dq.data.0);
                store(&ddq_dv, out, |o| &mut o.ddq_dv.data.0);
                let probe = finite_probe(&qdd)
                    + finite_probe(ddq_dq.as_flattened())
                    + finite_probe(ddq_dv.as_flattened());
                for (i, d) in out.iter_mut().enumerate() {
                    *d = if ok & (1 << i) != 0 && probe.lane(i) == 0.0 {
                        *d
                    } else {
                        // The scalar function says why (or, at an edge
                        // the lanes judged otherwise, gives the value).
                        let k = s + i;
                        match crate::linearize::forward_dynamics_derivatives(
                            self.robot, &q[k], &qd[k], &tau[k],
                        ) {
                            Ok(d) => d,
                            Err(error) => return Err(BatchError::State { state: k, error }),
                        }
                    };
                }
            }
            Ok(())
        }
    }
    dispatch::run(
        level,
        K {
            robot,
            x: [q, qd, tau],
            out,
        },
    )
}

/// The forward dynamics of every state, `A^-1 (Q(0) + Qqt1 + Qqt2 + tau)`
/// by `A = L D L^T` (the factorisation of
/// [`crate::linearize::forward_dynamics_derivatives`]; agrees with
/// [`Robot::forward_dynamics`], which uses a Cholesky factorisation, to
/// rounding).
///
/// Errors as [`forward_dynamics_derivatives`].
///
/// ```
/// use dynamics_runtime::batch::{self, Level};
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
/// let q: Vec<_> = (0..5).map(|k| Vector1::new(0.2 * k as f64)).collect();
/// let zero = vec![Vector1::zeros(); 5];
/// let mut qdd = vec![Vector1::zeros(); 5];
/// batch::forward_dynamics(&p, Level::detect(), &q, &zero, &zero, &mut qdd)?;
/// let scalar = p.forward_dynamics(&q[4], &zero[4], &zero[4])?;
/// assert!((qdd[4] - scalar).norm() <= 1e-15);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn forward_dynamics<R: Robot<N>, const N: usize>(
    robot: &R,
    level: Level,
    q: &[SVector<f64, N>],
    qd: &[SVector<f64, N>],
    tau: &[SVector<f64, N>],
    out: &mut [SVector<f64, N>],
) -> Result<(), BatchError> {
    let n = q.len();
    length("qd", qd, n)?;
    length("tau", tau, n)?;
    length("out", out, n)?;
    struct K<'a, R, const N: usize> {
        robot: &'a R,
        x: [&'a [SVector<f64, N>]; 3],
        out: &'a mut [SVector<f64, N>],
    }
    impl<R: Robot<N>, const N: usize> Kernel for K<'_, R, N> {
        type Output = Result<(), BatchError>;
        #[inline(always)]
        fn run<L: Lanes>(self) -> Result<(), BatchError> {
            let [q, qd, tau] = self.x;
            for s in (0..q.len()).step_by(L::WIDTH) {
                let m = L::WIDTH.min(q.len() - s);
                let (a, qqt, q0) = self
                    .robot
                    .motion_terms_lanes(&gather::<L, N>(q, s), &gather(qd, s));
                let t = gather::<L, N>(tau, s);
                let (f, ok) = ldlt::Ldlt::new(&a);
                let qdd = f.solve(&rhs(&q0, &qqt, &t));
                let out = &mut self.out[s..s + m];
                store(core::array::from_ref(&qdd), out, |o| &mut o.data.0);
                let probe = finite_probe(&qdd);
                for (i, v) in out.iter_mut().enumerate() {
                    *v = if ok & (1 << i) != 0 && probe.lane(i) == 0.0 {
                        *v
                    } else {
                        let k = s + i;
                        match robot_forward(self.robot, &q[k], &qd[k], &tau[k]) {
                            Ok(v) => v,
                            Err(error) => return Err(BatchError::State { state: k, error }),
                        }
                    };
                }
            }
            Ok(())
        }
    }
    dispatch::run(
        level,
        K {
            robot,
            x: [q, qd, tau],
            out,
        },
    )
}

/// The scalar forward dynamics, for a state the lanes could not solve.
#[cold]
fn robot_forward<R: Robot<N>, const N: usize>(
    robot: &R,
    q: &SVector<f64, N>,
    qd: &SVector<f64, N>,
    tau: &SVector<f64, N>,
) -> Result<SVector<f64, N>, DynamicsError> {
    robot.forward_dynamics(q, qd, tau)
}
