//! Robots declared with `robot!` in a `#![no_std]` crate, every run-time
//! output called: inverse dynamics, the mass matrix, the perturbation
//! Jacobians, forward dynamics (Cholesky through nalgebra without std),
//! the inertial regressor, parameters by name (and their error), program
//! constraints, a controller.
//!
//! The proof is the `#[panic_handler]` below: the standard library
//! defines one too, so if anything in this crate's graph linked std (the
//! runtime with its `std` feature, nalgebra's or thiserror's `std`, a
//! `std::` path in the emitted code), the build would fail with
//! "found duplicate lang item `panic_impl`" (E0152), and on a target
//! without std (thumbv7em-none-eabihf) with "can't find crate for `std`".
//! The public functions below are what `nm --size-sort` measures for the
//! README (each one the emitted function, inlined into it).

#![no_std]

use dynamics_runtime::batch::Batch;
use dynamics_runtime::control::{ComputedTorque, Controller, Reference};
use dynamics_runtime::nalgebra::{SMatrix, SVector};
use dynamics_runtime::{
    linearize, Constrained, DynamicsError, Parameters, PerturbationJacobians, Robot,
};

/// Halts: a controller's firmware would log and stop the drives here.
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    loop {}
}

dynamics_macros::robot! {
    /// A planar arm on a linear axis with what the emitted code can call
    /// beside `+ - * /`: Coulomb friction (tanh), a square root and a
    /// fourth power of a parameter, a spring, a point mass, a program
    /// constraint.
    pub robot Slide;
    gravity = [0.0, -9.81, 0.0];
    const L1 = 0.4;
    param payload = 0.5;
    param stiffness = 20.0;
    link base;
    link carriage { mass = 2.0; }
    link upper {
        mass = 1.0 + 0.2 * sqrt(payload);
        com = [L1 / 2.0, 0.0, 0.0];
        inertia = [1e-4, 0.02 + payload * payload * payload * payload * 1e-3, 0.02];
    }
    link fore {
        mass = 0.8; com = [0.2, 0.0, 0.0]; inertia = [1e-4, 0.01, 0.01];
        point_mass load = payload at [0.4, 0.0, 0.0];
    }
    joint x = prismatic(base -> carriage) {
        transfer = [trans_x(q)]; spring = stiffness; rest = 0.1; damping = 0.5;
    }
    joint shoulder = revolute(carriage -> upper) {
        transfer = [rot_z(q)]; coulomb = 0.3; coulomb_smoothing = 0.01;
    }
    joint elbow = revolute(upper -> fore) { transfer = [trans_x(L1), rot_z(q)]; damping = 0.1; }
    /// The carriage follows a sine.
    constraint track = x - 0.1 * sin(t);
}

dynamics_macros::robot! {
    /// The planar 3R loading arm of the dissertation (the URDF twin of `robots::Arm3r`).
    pub robot Arm3r;
    gravity = [0.0, -9.8, 0.0];
    urdf = "../robots/data/urdf/arm3r.urdf";
}

dynamics_macros::robot! {
    /// Universal Robots UR5.
    pub robot Ur5;
    gravity = [0.0, 0.0, -9.81];
    urdf = "../robots/data/urdf/ur5.urdf";
}

dynamics_macros::robot! {
    /// Franka Emika Panda.
    pub robot Panda;
    gravity = [0.0, 0.0, -9.81];
    urdf = "../robots/data/urdf/panda.urdf";
}

/// The outputs of one robot as plain functions (what a controller calls).
macro_rules! outputs {
    ($module:ident, $robot:ty, $n:literal) => {
        /// The outputs of this robot.
        pub mod $module {
            use super::*;

            /// U = A qdd - Q(0) - Qqt1 - Qqt2.
            pub fn inverse_dynamics(
                r: &$robot,
                q: &SVector<f64, $n>,
                qd: &SVector<f64, $n>,
                qdd: &SVector<f64, $n>,
            ) -> SVector<f64, $n> {
                r.inverse_dynamics(q, qd, qdd)
            }

            /// A(q).
            pub fn mass_matrix(r: &$robot, q: &SVector<f64, $n>) -> SMatrix<f64, $n, $n> {
                r.mass_matrix(q)
            }

            /// K = dF/dq, D = dF/dqd.
            pub fn perturbation_jacobians(
                r: &$robot,
                q: &SVector<f64, $n>,
                qd: &SVector<f64, $n>,
                qdd: &SVector<f64, $n>,
            ) -> PerturbationJacobians<$n> {
                r.perturbation_jacobians(q, qd, qdd)
            }

            /// qdd = A^-1 (Q(0) + Qqt1 + Qqt2 + u).
            pub fn forward_dynamics(
                r: &$robot,
                q: &SVector<f64, $n>,
                qd: &SVector<f64, $n>,
                u: &SVector<f64, $n>,
            ) -> Result<SVector<f64, $n>, DynamicsError> {
                r.forward_dynamics(q, qd, u)
            }

            /// The zero-order-hold model of a step `h` about (q, qd, u):
            /// forward-dynamics derivatives, state space, matrix exponential.
            pub fn discrete_model(
                r: &$robot,
                q: &SVector<f64, $n>,
                qd: &SVector<f64, $n>,
                u: &SVector<f64, $n>,
                h: f64,
            ) -> Option<linearize::DiscreteStateSpace<$n>> {
                let ss = linearize::state_space(r, q, qd, u).ok()?;
                ss.discretize(h).ok()
            }

            /// The inertial regressor, one N x 10 block per link of
            /// `LINK_NAMES` (the caller's array: no heap).
            pub fn inertial_regressor(
                r: &$robot,
                q: &SVector<f64, $n>,
                qd: &SVector<f64, $n>,
                qdd: &SVector<f64, $n>,
                out: &mut [SMatrix<f64, $n, 10>],
            ) -> Result<(), DynamicsError> {
                r.inertial_regressor(q, qd, qdd, out)
            }

            /// Computed torque on the model: the effort for a reference.
            pub fn computed_torque(
                r: &$robot,
                q: &SVector<f64, $n>,
                qd: &SVector<f64, $n>,
                reference: &Reference<$n>,
            ) -> SVector<f64, $n> {
                let mut c = ComputedTorque {
                    model: r,
                    kp: SVector::repeat(100.0),
                    kd: SVector::repeat(20.0),
                };
                c.effort(q, qd, reference)
            }
        }
    };
}

outputs!(slide, Slide, 3);
outputs!(arm3r, Arm3r, 3);
outputs!(ur5, Ur5, 6);
outputs!(panda, Panda, 7);

/// Inverse dynamics and forward-dynamics derivatives of many states in
/// vector lanes (the lane width the build targets: no run-time CPU check
/// without std; scalar on the Cortex-M4F).
pub fn arm3r_batch(
    r: &Arm3r,
    q: &[SVector<f64, 3>],
    qd: &[SVector<f64, 3>],
    qdd: &[SVector<f64, 3>],
    tau: &mut [SVector<f64, 3>],
    derivatives: &mut [linearize::ForwardDerivatives<3>],
) -> Result<(), dynamics_runtime::batch::BatchError> {
    r.inverse_dynamics_many(q, qd, qdd, tau)?;
    r.forward_dynamics_derivatives_many(q, qd, tau, derivatives)
}

/// Sets a parameter of [`Slide`] by name: the error names the parameter
/// and the known ones without a heap.
pub fn set_payload(r: &mut Slide, name: &str, value: f64) -> Result<(), DynamicsError> {
    r.params_mut().set(name, value)
}

/// The program constraint of [`Slide`]: residual, Jacobian and bias.
pub fn track(
    r: &Slide,
    t: f64,
    q: &SVector<f64, 3>,
    qd: &SVector<f64, 3>,
) -> (SVector<f64, 1>, SMatrix<f64, 1, 3>, SVector<f64, 1>) {
    (
        r.constraint_residual(t, q),
        r.constraint_jacobian(t, q),
        r.constraint_bias(t, q, qd),
    )
}
