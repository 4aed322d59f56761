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
//! The [`Robot`] methods `inverse_dynamics_many` etc. call these at
//! [`Level::detect`]; the functions here take the level, for comparisons.
//! With the feature `rayon`, `parallel` spreads large batches over all
//! cores.

mod dispatch;
mod ldlt;
#[cfg(feature = "rayon")]
pub mod parallel;

use nalgebra::{SMatrix, SVector};
use thiserror::Error;

pub use dispatch::Level;
use dispatch::Kernel;

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
    /// before it are written, the others are not).
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
    let last = x.len() - 1;
    core::array::from_fn(|j| L::from_fn(|i| x[(start + i).min(last)][j]))
}

/// State `i` of lanes.
#[inline(always)]
fn vector<L: Lanes, const N: usize>(x: &[L; N], i: usize) -> SVector<f64, N> {
    SVector::from_fn(|j, _| x[j].lane(i))
}

/// State `i` of row-major lane matrices.
#[inline(always)]
fn matrix<L: Lanes, const N: usize>(x: &[[L; N]; N], i: usize) -> SMatrix<f64, N, N> {
    SMatrix::from_fn(|r, c| x[r][c].lane(i))
}

/// Calls `f(start, lanes)` for each group of `WIDTH` states of `len`, with
/// the number of real states in the group.
#[inline(always)]
fn groups<L: Lanes>(len: usize, mut f: impl FnMut(usize, usize)) {
    let mut start = 0;
    while start < len {
        f(start, L::WIDTH.min(len - start));
        start += L::WIDTH;
    }
}

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
            groups::<L>(q.len(), |s, m| {
                let tau = self.robot.inverse_dynamics_lanes(
                    &gather::<L, N>(q, s),
                    &gather(qd, s),
                    &gather(qdd, s),
                );
                for i in 0..m {
                    self.out[s + i] = vector(&tau, i);
                }
            });
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
            groups::<L>(self.q.len(), |s, m| {
                let a = self.robot.mass_matrix_lanes(&gather::<L, N>(self.q, s));
                for i in 0..m {
                    self.out[s + i] = matrix(&a, i);
                }
            });
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
            groups::<L>(q.len(), |s, m| {
                let (a, qqt, q0) = self
                    .robot
                    .motion_terms_lanes(&gather::<L, N>(q, s), &gather(qd, s));
                for i in 0..m {
                    self.out[s + i] = MotionTerms {
                        a: matrix(&a, i),
                        qqt: vector(&qqt, i),
                        q0: vector(&q0, i),
                    };
                }
            });
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
            groups::<L>(q.len(), |s, m| {
                let (k, d) = self.robot.perturbation_jacobians_lanes(
                    &gather::<L, N>(q, s),
                    &gather(qd, s),
                    &gather(qdd, s),
                );
                for i in 0..m {
                    self.out[s + i] = PerturbationJacobians {
                        k: matrix(&k, i),
                        d: matrix(&d, i),
                    };
                }
            });
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
/// result that is not finite), naming it; the states before it are
/// written.
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
            let mut result = Ok(());
            groups::<L>(q.len(), |s, m| {
                if result.is_err() {
                    return;
                }
                let t = gather::<L, N>(tau, s);
                let mut factors = None;
                let (qdd, k, d) = self.robot.motion_and_jacobians_lanes(
                    &gather::<L, N>(q, s),
                    &gather(qd, s),
                    |a, qqt, q0| {
                        let (f, ok) = ldlt::Ldlt::new(a);
                        let b: [L; N] = core::array::from_fn(|j| q0[j] + qqt[j] + t[j]);
                        let qdd = f.solve(&b);
                        factors = Some((f, ok));
                        qdd
                    },
                );
                let Some((f, ok)) = factors else {
                    return;
                };
                let mut kd = [k, d];
                for rows in &mut kd {
                    f.solve_rows(rows, -1.0);
                }
                let [ddq_dq, ddq_dv] = kd;
                for i in 0..m {
                    let d = ForwardDerivatives {
                        qdd: vector(&qdd, i),
                        ddq_dq: matrix(&ddq_dq, i),
                        ddq_dv: matrix(&ddq_dv, i),
                    };
                    let finite = d.qdd.iter().all(|x| x.is_finite())
                        && d.ddq_dq.iter().all(|x| x.is_finite())
                        && d.ddq_dv.iter().all(|x| x.is_finite());
                    self.out[s + i] = if ok & (1 << i) != 0 && finite {
                        d
                    } else {
                        // The scalar function says why (or, at an edge
                        // the lanes judged otherwise, gives the value).
                        let k = s + i;
                        match crate::linearize::forward_dynamics_derivatives(
                            self.robot, &q[k], &qd[k], &tau[k],
                        ) {
                            Ok(d) => d,
                            Err(error) => {
                                result = Err(BatchError::State { state: k, error });
                                return;
                            }
                        }
                    };
                }
            });
            result
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
            let mut result = Ok(());
            groups::<L>(q.len(), |s, m| {
                if result.is_err() {
                    return;
                }
                let (a, qqt, q0) = self
                    .robot
                    .motion_terms_lanes(&gather::<L, N>(q, s), &gather(qd, s));
                let t = gather::<L, N>(tau, s);
                let (f, ok) = ldlt::Ldlt::new(&a);
                let b: [L; N] = core::array::from_fn(|j| q0[j] + qqt[j] + t[j]);
                let qdd = f.solve(&b);
                for i in 0..m {
                    let v = vector(&qdd, i);
                    self.out[s + i] = if ok & (1 << i) != 0 && v.iter().all(|x| x.is_finite()) {
                        v
                    } else {
                        let k = s + i;
                        match robot_forward(self.robot, &q[k], &qd[k], &tau[k]) {
                            Ok(v) => v,
                            Err(error) => {
                                result = Err(BatchError::State { state: k, error });
                                return;
                            }
                        }
                    };
                }
            });
            result
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
