//! Named run-time parameters of a generated robot.

use crate::{DynamicsError, ParameterName};

/// The run-time parameters of a robot (`param` items of `robot!`), read and
/// written by name or index. `robot!` implements it for the `<Robot>Params`
/// struct it generates.
///
/// ```
/// use dynamics_runtime::Parameters;
/// dynamics_macros::robot! {
///     pub robot Pendulum;
///     gravity = [0.0, -9.81, 0.0];
///     param m = 1.5;
///     link base;
///     link rod { mass = m; com = [0.5, 0.0, 0.0]; inertia = [1e-3, 1e-3, 1e-3]; }
///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
/// }
/// let mut p = PendulumParams::default();
/// assert_eq!(PendulumParams::NAMES, &["m"]);
/// assert_eq!(p.get("m"), Some(1.5));
/// p.set("m", 2.0).unwrap();
/// assert_eq!(p.m, 2.0);
/// let e = p.set("mass", 1.0).unwrap_err();
/// assert_eq!(e.to_string(), "unknown parameter `mass`; this robot has: m");
/// ```
pub trait Parameters: Clone + Default + core::fmt::Debug {
    /// Parameter names, in declaration order.
    const NAMES: &'static [&'static str];
    /// Value of the parameter at `index` (declaration order).
    fn value(&self, index: usize) -> Option<f64>;
    /// Sets the parameter at `index`; returns false when there is none.
    fn set_value(&mut self, index: usize, value: f64) -> bool;

    /// Value of the parameter called `name`.
    fn get(&self, name: &str) -> Option<f64> {
        let i = Self::NAMES.iter().position(|n| *n == name)?;
        self.value(i)
    }

    /// Sets the parameter called `name`.
    fn set(&mut self, name: &str, value: f64) -> Result<(), DynamicsError> {
        match Self::NAMES.iter().position(|n| *n == name) {
            Some(i) if self.set_value(i, value) => Ok(()),
            _ => Err(DynamicsError::UnknownParameter {
                name: ParameterName::new(name),
                known: Self::NAMES,
            }),
        }
    }
}
