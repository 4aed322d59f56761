//! Joint-space tracking controllers (dissertation, chapter 4): PD with gravity
//! compensation, computed torque, and sliding-mode control with a boundary
//! layer. Each uses a model of the robot (any `Robot<N>`; it may differ
//! from the plant).

use nalgebra::SVector;

use crate::Robot;

/// A reference motion sample.
///
/// ```
/// use dynamics_runtime::control::Reference;
/// use nalgebra::Vector2;
/// // Rest at q = (0.1, -0.2).
/// let r = Reference { q: Vector2::new(0.1, -0.2), qd: Vector2::zeros(), qdd: Vector2::zeros() };
/// assert_eq!(r.qd.norm(), 0.0);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reference<const N: usize> {
    /// Desired positions.
    pub q: SVector<f64, N>,
    /// Desired velocities.
    pub qd: SVector<f64, N>,
    /// Desired accelerations.
    pub qdd: SVector<f64, N>,
}

/// A controller: efforts from the measured state and the reference.
///
/// Implement it for a control law of your own; [`crate::synth`] and the
/// scenarios drive a plant with any `Controller`.
///
/// ```
/// use dynamics_runtime::control::{Controller, Reference};
/// use nalgebra::SVector;
/// /// A pure spring towards the reference.
/// struct Spring(f64);
/// impl<const N: usize> Controller<N> for Spring {
///     fn effort(&mut self, q: &SVector<f64, N>, _qd: &SVector<f64, N>, r: &Reference<N>) -> SVector<f64, N> {
///         (r.q - q) * self.0
///     }
/// }
/// let z = nalgebra::Vector1::new(0.0);
/// let r = Reference { q: nalgebra::Vector1::new(0.5), qd: z, qdd: z };
/// assert_eq!(Spring(10.0).effort(&z, &z, &r)[0], 5.0);
/// ```
pub trait Controller<const N: usize> {
    /// The joint efforts to apply.
    fn effort(
        &mut self,
        q: &SVector<f64, N>,
        qd: &SVector<f64, N>,
        r: &Reference<N>,
    ) -> SVector<f64, N>;
}

/// `tau = g(q) + Kp (q_r - q) + Kd (qd_r - qd)` (gravity from the model).
///
/// ```
/// use dynamics_runtime::control::{Controller, PdGravity, Reference};
/// use dynamics_runtime::Robot;
/// dynamics_macros::robot! {
///     pub robot Pendulum;
///     gravity = [0.0, -9.81, 0.0];
///     link base;
///     link rod { mass = 1.0; com = [1.0, 0.0, 0.0]; }
///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
/// }
/// let model = Pendulum::default();
/// let mut c = PdGravity { model: &model, kp: [100.0].into(), kd: [20.0].into() };
/// let z = nalgebra::Vector1::new(0.0);
/// let tau = c.effort(&z, &z, &Reference { q: z, qd: z, qdd: z });
/// assert!((tau[0] - 9.81).abs() < 1e-12); // holds the rod up
/// ```
pub struct PdGravity<'a, R, const N: usize> {
    /// The model whose gravity is compensated.
    pub model: &'a R,
    /// Position gains.
    pub kp: SVector<f64, N>,
    /// Velocity gains.
    pub kd: SVector<f64, N>,
}

impl<R: Robot<N>, const N: usize> Controller<N> for PdGravity<'_, R, N> {
    fn effort(
        &mut self,
        q: &SVector<f64, N>,
        qd: &SVector<f64, N>,
        r: &Reference<N>,
    ) -> SVector<f64, N> {
        self.model.gravity(q)
            + self.kp.component_mul(&(r.q - q))
            + self.kd.component_mul(&(r.qd - qd))
    }
}

/// Computed torque: `tau = A(q) (qdd_r + Kd e_d + Kp e) - (Q(0) + Qqt)`.
///
/// On the reference, with an exact model, it is the inverse dynamics of the
/// reference motion:
///
/// ```
/// use dynamics_runtime::control::{ComputedTorque, Controller, Reference};
/// use dynamics_runtime::Robot;
/// dynamics_macros::robot! {
///     pub robot Pendulum;
///     gravity = [0.0, -9.81, 0.0];
///     link base;
///     link rod { mass = 1.0; com = [1.0, 0.0, 0.0]; }
///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
/// }
/// let model = Pendulum::default();
/// let mut c = ComputedTorque { model: &model, kp: [100.0].into(), kd: [20.0].into() };
/// let (q, qd, qdd) = ([0.3].into(), [-1.0].into(), [2.0].into());
/// let tau = c.effort(&q, &qd, &Reference { q, qd, qdd });
/// assert!((tau - model.inverse_dynamics(&q, &qd, &qdd)).norm() < 1e-12);
/// ```
pub struct ComputedTorque<'a, R, const N: usize> {
    /// The model.
    pub model: &'a R,
    /// Position gains.
    pub kp: SVector<f64, N>,
    /// Velocity gains.
    pub kd: SVector<f64, N>,
}

impl<R: Robot<N>, const N: usize> Controller<N> for ComputedTorque<'_, R, N> {
    fn effort(
        &mut self,
        q: &SVector<f64, N>,
        qd: &SVector<f64, N>,
        r: &Reference<N>,
    ) -> SVector<f64, N> {
        let m = self.model.motion_terms(q, qd);
        let v = r.qdd + self.kd.component_mul(&(r.qd - qd)) + self.kp.component_mul(&(r.q - q));
        m.a * v - m.bias()
    }
}

/// Sliding mode with a boundary layer: with `e = q_r - q` and the sliding
/// variable `s = e_d + Lambda e`,
/// `tau = A(q) (qdd_r + Lambda e_d) - (Q(0) + Qqt) + K sat(s / phi)`.
///
/// Outside the boundary layer the switching term saturates at `K`:
///
/// ```
/// use dynamics_runtime::control::{Controller, Reference, SlidingMode};
/// use dynamics_runtime::Robot;
/// dynamics_macros::robot! {
///     pub robot Pendulum;
///     gravity = [0.0, -9.81, 0.0];
///     link base;
///     link rod { mass = 1.0; com = [1.0, 0.0, 0.0]; }
///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
/// }
/// let model = Pendulum::default();
/// let mut c = SlidingMode { model: &model, lambda: [5.0].into(), k: [3.0].into(), phi: 0.01 };
/// let z = nalgebra::Vector1::new(0.0);
/// let r = Reference { q: [0.2].into(), qd: z, qdd: z };
/// // e = 0.2, s = Lambda e = 1 >> phi: gravity plus the full gain K.
/// let tau = c.effort(&z, &z, &r);
/// assert!((tau[0] - (model.gravity(&z)[0] + 3.0)).abs() < 1e-12);
/// ```
pub struct SlidingMode<'a, R, const N: usize> {
    /// The model.
    pub model: &'a R,
    /// Slope of the sliding surface, 1/s.
    pub lambda: SVector<f64, N>,
    /// Switching gain.
    pub k: SVector<f64, N>,
    /// Boundary layer width (no chattering inside it).
    pub phi: f64,
}

impl<R: Robot<N>, const N: usize> Controller<N> for SlidingMode<'_, R, N> {
    fn effort(
        &mut self,
        q: &SVector<f64, N>,
        qd: &SVector<f64, N>,
        r: &Reference<N>,
    ) -> SVector<f64, N> {
        let m = self.model.motion_terms(q, qd);
        let (e, ed) = (r.q - q, r.qd - qd);
        let s = ed + self.lambda.component_mul(&e);
        let sat = s.map(|x| (x / self.phi).clamp(-1.0, 1.0));
        m.a * (r.qdd + self.lambda.component_mul(&ed)) - m.bias() + self.k.component_mul(&sat)
    }
}
