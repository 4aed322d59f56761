//! The friction the nominal model already carries: a URDF's
//! `<dynamics damping friction>`, which CAD exports often fill with
//! made-up values, and which a joint torque sensor on the link side does
//! not see at all. A friction correction is the change from it, so it may
//! take the nominal friction away but not make the total negative (the
//! diagnosis's fit, `diagnose/pool/build.rs`; [`Effect::within_nominal_friction`],
//! which [`Plant`](super::Plant) and [`Calibrated`](super::Calibrated)
//! accept).
//!
//! The levels are read from the model itself, whatever made them: with
//! one joint moving at speed `v`, its friction force
//! ([`Robot::joint_friction`], the velocity-dependent part of the
//! generalised forces without a resistance of the environment) is
//! `-(fv v + fc)` once `v` is far above any smoothing of the Coulomb law;
//! two speeds give both.

use nalgebra::SVector;

use dynamics_runtime::Robot;

/// The speeds (rad/s or m/s) the levels are read at: far above the
/// smoothing of any Coulomb law, far below overflow.
const SPEED: f64 = 1e3;

/// Per joint, the nominal model's Coulomb level and viscous coefficient
/// at configuration `q` (0 where it has none; never negative or NaN).
///
/// ```
/// use dynamics_sim2real::effects::nominal_friction;
/// dynamics_macros::robot! {
///     pub robot Hinge; gravity = [0.0, 0.0, -9.81];
///     link base; link door { mass = 2.0; com = [0.4, 0.0, 0.0]; inertia = [0.1, 0.1, 0.1]; }
///     joint j = revolute(base -> door) { transfer = [rot_z(q)]; damping = 0.3; coulomb = 0.2; }
/// }
/// let (coulomb, viscous) = nominal_friction(&Hinge::default(), &[0.0].into());
/// assert!((coulomb[0] - 0.2).abs() < 1e-9 && (viscous[0] - 0.3).abs() < 1e-9);
/// ```
pub fn nominal_friction<R: Robot<N>, const N: usize>(
    robot: &R,
    q: &SVector<f64, N>,
) -> (SVector<f64, N>, SVector<f64, N>) {
    let mut coulomb = SVector::<f64, N>::zeros();
    let mut viscous = SVector::<f64, N>::zeros();
    for j in 0..N {
        let at = |v: f64| {
            let mut qd = SVector::<f64, N>::zeros();
            qd[j] = v;
            -robot.joint_friction(q, &qd)[j]
        };
        let (e1, e2) = (at(SPEED), at(2.0 * SPEED));
        let fv = (e2 - e1) / SPEED;
        let fc = e1 - fv * SPEED;
        let clean = |x: f64| if x.is_finite() && x > 0.0 { x } else { 0.0 };
        viscous[j] = clean(fv);
        // (Rounding of `fv SPEED` leaves some 1e-13 of a level that is not
        // there.)
        coulomb[j] = clean(fc - 1e-12 * e1.abs().max(1.0));
    }
    (coulomb, viscous)
}

#[cfg(test)]
mod tests {
    use super::*;

    dynamics_macros::robot! {
        robot TwoLinks;
        gravity = [0.0, -9.81, 0.0];
        param fv = 0.0;
        param fc = 0.0;
        link base;
        link a { mass = 1.0; com = [0.3, 0.0, 0.0]; inertia = [1e-3, 0.01, 0.01]; }
        link b { mass = 0.5; com = [0.2, 0.0, 0.0]; inertia = [1e-3, 0.005, 0.005]; }
        joint j1 = revolute(base -> a) { transfer = [rot_z(q)]; damping = fv; coulomb = fc; spring = 2.0; }
        joint j2 = revolute(a -> b) { transfer = [trans_x(0.4), rot_z(q)]; }
    }

    /// A model without friction reads none (its spring and gravity are
    /// not friction); with a damping and a Coulomb level set at the first
    /// joint, those are read back there and none at the second.
    #[test]
    fn the_levels_set_are_read_back() {
        let q = SVector::<f64, 2>::new(0.3, -0.7);
        let mut robot = TwoLinks::default();
        let (c, v) = nominal_friction(&robot, &q);
        assert_eq!((c, v), (SVector::zeros(), SVector::zeros()));
        robot.params_mut().fv = 1.2;
        robot.params_mut().fc = 0.5;
        let (c, v) = nominal_friction(&robot, &q);
        assert!(
            (v[0] - 1.2).abs() < 1e-9 && (c[0] - 0.5).abs() < 1e-6,
            "{c} {v}"
        );
        assert_eq!((c[1], v[1]), (0.0, 0.0));
    }
}
