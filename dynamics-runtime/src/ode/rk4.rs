//! The classical fixed-step Runge-Kutta method of order 4.

use super::OdeState;

/// One RK4 step of size `h` from (t, y) for `y' = f(t, y)`.
///
/// ```
/// use dynamics_runtime::ode::rk4_step;
/// use nalgebra::Vector1;
/// // y' = y, y(0) = 1: one step of 0.1 is e^0.1 to 1e-7.
/// let y = rk4_step(&mut |_t, y: &Vector1<f64>| Ok::<_, ()>(*y), 0.0, &Vector1::new(1.0), 0.1).unwrap();
/// assert!((y[0] - 0.1f64.exp()).abs() < 1e-7);
/// ```
pub fn rk4_step<S: OdeState, E>(
    f: &mut impl FnMut(f64, &S) -> Result<S, E>,
    t: f64,
    y: &S,
    h: f64,
) -> Result<S, E> {
    let k1 = f(t, y)?;
    let k2 = f(t + 0.5 * h, &y.axpy(0.5 * h, &k1))?;
    let k3 = f(t + 0.5 * h, &y.axpy(0.5 * h, &k2))?;
    let k4 = f(t + h, &y.axpy(h, &k3))?;
    Ok(y.axpy(h / 6.0, &k1)
        .axpy(h / 3.0, &k2)
        .axpy(h / 3.0, &k3)
        .axpy(h / 6.0, &k4))
}
