//! What an effect does: the force laws of friction, of a motor side's
//! transmission and of environment resistance, and the effort sensors'
//! law undone ([`Effect::applied_effort`]).

use super::Effect;

/// Velocity scale of the smooth sign `tanh(v / eps)` used by every friction
/// law (rad/s or m/s): below it friction fades linearly, so that the motion
/// equations stay smooth enough for an adaptive integrator.
pub const SIGN_SMOOTHING: f64 = 1e-2;

/// The Stribeck velocities the diagnosis searches (and the designer of
/// separating motions measures the breakaway at), rad/s.
pub(crate) const STRIBECK_GRID: [f64; 4] = [0.01, 0.03, 0.1, 0.3];

/// The smooth sign of friction laws, `tanh(v / SIGN_SMOOTHING)`.
///
/// ```
/// use dynamics_sim2real::effects::smooth_sign;
/// assert!((smooth_sign(1.0) - 1.0).abs() < 1e-12);
/// assert_eq!(smooth_sign(0.0), 0.0);
/// ```
pub fn smooth_sign(v: f64) -> f64 {
    (v / SIGN_SMOOTHING).tanh()
}

impl Effect {
    /// The effort applied at the joints when the effort sensors of
    /// `effects` report `measured` (effort scale and offset undone).
    ///
    /// ```
    /// use dynamics_sim2real::effects::Effect;
    /// let e = [Effect::EffortScale { joint: 0, scale: 2.0 }, Effect::EffortOffset { joint: 1, offset: 0.5 }];
    /// let applied = Effect::applied_effort(&e, &nalgebra::Vector2::new(4.0, 1.0));
    /// assert_eq!(applied, nalgebra::Vector2::new(2.0, 0.5));
    /// ```
    pub fn applied_effort<const N: usize>(
        effects: &[Effect],
        measured: &nalgebra::SVector<f64, N>,
    ) -> nalgebra::SVector<f64, N> {
        let mut out = *measured;
        for e in effects {
            if let Effect::EffortOffset { joint, offset } = *e {
                if joint < N {
                    out[joint] -= offset;
                }
            }
        }
        for e in effects {
            if let Effect::EffortScale { joint, scale } = *e {
                if joint < N && scale != 0.0 {
                    out[joint] /= scale;
                }
            }
        }
        out
    }

    /// The friction force at the joint for joint velocity `v` (zero for
    /// effects that are not joint friction).
    pub fn joint_force(&self, v: f64) -> f64 {
        match *self {
            Effect::CoulombFriction { fc, vw, .. } => -fc * (v / vw).tanh(),
            Effect::ViscousFriction { fv, .. } => -fv * v,
            Effect::StribeckFriction { fc, fs, vs, .. } => {
                -(fc + (fs - fc) * (-(v / vs).powi(2)).exp()) * smooth_sign(v)
            }
            _ => 0.0,
        }
    }

    /// The effort the motor side passes to the link, for motor-link
    /// deflection `e = theta - q` and its rate `ed`; `contact` is the
    /// backlash contact side (-1, 0, +1) the integrator is in.
    pub fn transmitted(&self, e: f64, ed: f64, contact: i8) -> f64 {
        match *self {
            Effect::JointElasticity {
                stiffness, damping, ..
            } => stiffness * e + damping * ed,
            Effect::Backlash {
                half_width,
                contact_stiffness,
                contact_damping,
                ..
            } => match contact {
                1 => contact_stiffness * (e - half_width) + contact_damping * ed,
                -1 => contact_stiffness * (e + half_width) + contact_damping * ed,
                _ => 0.0,
            },
            _ => 0.0,
        }
    }

    /// The resistance force at the tip for tip velocity `v`.
    pub fn resistance(&self, v: &nalgebra::Vector3<f64>) -> nalgebra::Vector3<f64> {
        match *self {
            Effect::EnvironmentResistance { mu, alpha } => {
                let s = v.norm();
                if s == 0.0 {
                    nalgebra::Vector3::zeros()
                } else {
                    -v * (mu * s.powf(alpha - 1.0))
                }
            }
            _ => nalgebra::Vector3::zeros(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn friction_laws_oppose_motion_and_have_their_levels() {
        let c = Effect::coulomb(0, 2.0);
        assert!((c.joint_force(1.0) + 2.0).abs() < 1e-12);
        assert!((c.joint_force(-1.0) - 2.0).abs() < 1e-12);
        let s = Effect::StribeckFriction {
            joint: 0,
            fc: 1.0,
            fs: 1.5,
            vs: 0.1,
        };
        // Near (but above) the smoothing scale the static level shows;
        // far above vs only Coulomb is left.
        let level = 1.0 + 0.5 * (-0.25f64).exp();
        assert!((s.joint_force(0.05) + level).abs() < 1e-3);
        assert!((s.joint_force(2.0) + 1.0).abs() < 1e-9);
        for v in [-3.0, -0.2, -1e-3, 1e-3, 0.2, 3.0] {
            for e in [c, s, Effect::ViscousFriction { joint: 0, fv: 0.3 }] {
                assert!(e.joint_force(v) * v < 0.0, "{e:?} at {v}");
            }
        }
    }

    #[test]
    fn backlash_passes_nothing_inside_the_gap_and_pushes_outside() {
        let b = Effect::Backlash {
            joint: 0,
            half_width: 0.01,
            motor_inertia: 0.01,
            contact_stiffness: 1e4,
            contact_damping: 0.0,
        };
        assert_eq!(b.transmitted(0.005, 1.0, 0), 0.0);
        assert!((b.transmitted(0.011, 0.0, 1) - 10.0).abs() < 1e-9);
        assert!((b.transmitted(-0.012, 0.0, -1) + 20.0).abs() < 1e-9);
    }

    #[test]
    fn resistance_opposes_velocity_with_power_alpha() {
        let r = Effect::EnvironmentResistance {
            mu: 0.05,
            alpha: 2.0,
        };
        let v = nalgebra::Vector3::new(3.0, 4.0, 0.0);
        let f = r.resistance(&v);
        assert!((f.norm() - 0.05 * 25.0).abs() < 1e-12);
        assert!(f.dot(&v) < 0.0);
    }
}
