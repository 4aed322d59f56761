//! One unmodelled effect with its parameters, and its force law.

use super::EffectKind;

/// Velocity scale of the smooth sign `tanh(v / eps)` used by every friction
/// law (rad/s or m/s): below it friction fades linearly, so that the motion
/// equations stay smooth enough for an adaptive integrator.
pub const SIGN_SMOOTHING: f64 = 1e-2;

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

/// An unmodelled effect with its place and parameters (SI units). Joints
/// are indices into the robot's `JOINT_NAMES`; payload and environment act
/// at the robot's tip (see [`crate::effects::Tip`]).
///
/// ```
/// use dynamics_sim2real::effects::{Effect, EffectKind};
/// let e = Effect::ViscousFriction { joint: 1, fv: 0.5 };
/// assert_eq!(e.kind(), EffectKind::ViscousFriction);
/// assert_eq!(e.joint(), Some(1));
/// // The force opposes the motion:
/// assert_eq!(e.joint_force(2.0), -1.0);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Effect {
    /// `Q_j = -fc tanh(qd_j / vw)` (N m or N): Coulomb friction whose
    /// sign turns over the velocity width `vw` ([`SIGN_SMOOTHING`] for a
    /// sharp one; real joints' friction often turns over tenths of a rad/s,
    /// e.g. the Panda's published sigmoid model).
    CoulombFriction {
        /// Joint index.
        joint: usize,
        /// Coulomb level Fc.
        fc: f64,
        /// Velocity width vw > 0 (rad/s or m/s).
        vw: f64,
    },
    /// `Q_j = -fv qd_j`.
    ViscousFriction {
        /// Joint index.
        joint: usize,
        /// Viscous coefficient Fv.
        fv: f64,
    },
    /// `Q_j = -(fc + (fs - fc) exp(-(qd/vs)^2)) sign(qd_j)`.
    StribeckFriction {
        /// Joint index.
        joint: usize,
        /// Coulomb level Fc.
        fc: f64,
        /// Static (breakaway) level Fs >= Fc.
        fs: f64,
        /// Stribeck velocity vs > 0.
        vs: f64,
    },
    /// Rotor inertia `ia` added to `A[j][j]`.
    Armature {
        /// Joint index.
        joint: usize,
        /// Reflected rotor inertia (kg m^2, or kg for a slide).
        inertia: f64,
    },
    /// Link `link` (an index into `Robot::LINK_NAMES`) differs from the
    /// nominal model by `delta` in its ten inertial parameters
    /// (Pinocchio's order, link frame, inertia about the frame's origin:
    /// see [`crate::inertial`]); the robot needs `Y_l(q, qd, qdd) delta`
    /// more effort.
    InertialParameters {
        /// Link index.
        link: usize,
        /// Change of `[m, m c_x, m c_y, m c_z, I_xx, I_xy, I_yy, I_xz, I_yz, I_zz]`.
        delta: [f64; 10],
    },
    /// A point mass at the tip.
    PayloadMass {
        /// Mass, kg.
        mass: f64,
    },
    /// Two-mass joint: the drive effort acts on a motor of inertia
    /// `motor_inertia`, joined to the link by `stiffness` and `damping`.
    JointElasticity {
        /// Joint index.
        joint: usize,
        /// Stiffness k.
        stiffness: f64,
        /// Damping c.
        damping: f64,
        /// Motor-side inertia.
        motor_inertia: f64,
    },
    /// Dead zone of half-width `half_width` between motor and link; in
    /// contact, a stiff spring-damper (`contact_stiffness`, `contact_damping`).
    Backlash {
        /// Joint index.
        joint: usize,
        /// Clearance half-width delta (rad or m).
        half_width: f64,
        /// Motor-side inertia.
        motor_inertia: f64,
        /// Contact stiffness.
        contact_stiffness: f64,
        /// Contact damping.
        contact_damping: f64,
    },
    /// `F = -mu |v|^(alpha-1) v` at the tip, through the tip Jacobian.
    EnvironmentResistance {
        /// Resistance coefficient mu.
        mu: f64,
        /// Velocity exponent alpha >= 1.
        alpha: f64,
    },
    /// The encoder of `joint` reads `q + offset`.
    EncoderOffset {
        /// Joint index.
        joint: usize,
        /// Offset (rad or m).
        offset: f64,
    },
    /// Positions and velocities are recorded `delay` seconds late.
    TimeDelay {
        /// Delay, s.
        delay: f64,
    },
    /// The effort sensor of `joint` reports `scale` times the applied
    /// effort.
    EffortScale {
        /// Joint index.
        joint: usize,
        /// Measured over applied effort.
        scale: f64,
    },
    /// The effort sensor of `joint` reports the applied effort plus
    /// `offset`.
    EffortOffset {
        /// Joint index.
        joint: usize,
        /// Offset (N m or N).
        offset: f64,
    },
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

    /// Whether the effect sits in the sensors (encoder offset, delay,
    /// effort scale and offset) rather than in the plant.
    pub fn is_sensor(&self) -> bool {
        matches!(
            self,
            Effect::EncoderOffset { .. }
                | Effect::TimeDelay { .. }
                | Effect::EffortScale { .. }
                | Effect::EffortOffset { .. }
        )
    }

    /// The kind of this effect.
    pub fn kind(&self) -> EffectKind {
        match self {
            Effect::CoulombFriction { .. } => EffectKind::CoulombFriction,
            Effect::ViscousFriction { .. } => EffectKind::ViscousFriction,
            Effect::StribeckFriction { .. } => EffectKind::StribeckFriction,
            Effect::Armature { .. } => EffectKind::Armature,
            Effect::InertialParameters { .. } => EffectKind::InertialParameters,
            Effect::PayloadMass { .. } => EffectKind::PayloadMass,
            Effect::JointElasticity { .. } => EffectKind::JointElasticity,
            Effect::Backlash { .. } => EffectKind::Backlash,
            Effect::EnvironmentResistance { .. } => EffectKind::EnvironmentResistance,
            Effect::EncoderOffset { .. } => EffectKind::EncoderOffset,
            Effect::TimeDelay { .. } => EffectKind::TimeDelay,
            Effect::EffortScale { .. } => EffectKind::EffortScale,
            Effect::EffortOffset { .. } => EffectKind::EffortOffset,
        }
    }

    /// Sharp Coulomb friction `fc` at `joint` (velocity width
    /// [`SIGN_SMOOTHING`]).
    ///
    /// ```
    /// use dynamics_sim2real::effects::{Effect, SIGN_SMOOTHING};
    /// let e = Effect::coulomb(1, 0.3);
    /// assert_eq!(e, Effect::CoulombFriction { joint: 1, fc: 0.3, vw: SIGN_SMOOTHING });
    /// assert!((e.joint_force(1.0) + 0.3).abs() < 1e-12);
    /// ```
    pub fn coulomb(joint: usize, fc: f64) -> Effect {
        Effect::CoulombFriction {
            joint,
            fc,
            vw: SIGN_SMOOTHING,
        }
    }

    /// The joint it sits at, for joint effects.
    pub fn joint(&self) -> Option<usize> {
        match *self {
            Effect::CoulombFriction { joint, .. }
            | Effect::ViscousFriction { joint, .. }
            | Effect::StribeckFriction { joint, .. }
            | Effect::Armature { joint, .. }
            | Effect::JointElasticity { joint, .. }
            | Effect::Backlash { joint, .. }
            | Effect::EncoderOffset { joint, .. }
            | Effect::EffortScale { joint, .. }
            | Effect::EffortOffset { joint, .. } => Some(joint),
            _ => None,
        }
    }

    /// Whether the effect has a motor side with states of its own.
    pub fn has_motor(&self) -> bool {
        matches!(
            self,
            Effect::JointElasticity { .. } | Effect::Backlash { .. }
        )
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

    /// Checks that the parameters are physical (finite, non-negative where
    /// they must be), naming the offending one.
    pub fn validate(&self) -> Result<(), String> {
        let check = |name: &str, v: f64, positive: bool| -> Result<(), String> {
            if !v.is_finite() || v < 0.0 || (positive && v == 0.0) {
                Err(format!(
                    "{}: {name} must be {} and finite, got {v}",
                    self.kind(),
                    if positive { "> 0" } else { ">= 0" }
                ))
            } else {
                Ok(())
            }
        };
        match *self {
            Effect::CoulombFriction { fc, vw, .. } => {
                check("fc", fc, false)?;
                check("vw", vw, true)
            }
            Effect::ViscousFriction { fv, .. } => check("fv", fv, false),
            Effect::StribeckFriction { fc, fs, vs, .. } => {
                check("fc", fc, false)?;
                check("fs", fs, false)?;
                check("vs", vs, true)
            }
            Effect::Armature { inertia, .. } => check("inertia", inertia, false),
            Effect::InertialParameters { ref delta, .. } => {
                match delta.iter().position(|v| !v.is_finite()) {
                    Some(k) => Err(format!(
                        "inertial_parameters: {} must be finite",
                        crate::inertial::PARAMETER_NAMES[k]
                    )),
                    None => Ok(()),
                }
            }
            Effect::PayloadMass { mass } => check("mass", mass, false),
            Effect::JointElasticity {
                stiffness,
                damping,
                motor_inertia,
                ..
            } => {
                check("stiffness", stiffness, true)?;
                check("damping", damping, false)?;
                check("motor_inertia", motor_inertia, true)
            }
            Effect::Backlash {
                half_width,
                motor_inertia,
                contact_stiffness,
                contact_damping,
                ..
            } => {
                check("half_width", half_width, false)?;
                check("motor_inertia", motor_inertia, true)?;
                check("contact_stiffness", contact_stiffness, true)?;
                check("contact_damping", contact_damping, false)
            }
            Effect::EnvironmentResistance { mu, alpha } => {
                check("mu", mu, false)?;
                if alpha.is_finite() && alpha >= 1.0 {
                    Ok(())
                } else {
                    Err(format!(
                        "environment_resistance: alpha must be >= 1, got {alpha}"
                    ))
                }
            }
            Effect::EncoderOffset { offset, .. } => {
                if offset.is_finite() {
                    Ok(())
                } else {
                    Err("encoder_offset: offset must be finite".into())
                }
            }
            Effect::TimeDelay { delay } => check("delay", delay, false),
            Effect::EffortScale { scale, .. } => check("scale", scale, true),
            Effect::EffortOffset { offset, .. } => {
                if offset.is_finite() {
                    Ok(())
                } else {
                    Err("effort_offset: offset must be finite".into())
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn friction_laws_oppose_motion_and_have_their_levels() {
        let c = Effect::CoulombFriction {
            joint: 0,
            fc: 2.0,
            vw: SIGN_SMOOTHING,
        };
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

    #[test]
    fn validation_names_the_parameter() {
        let e = Effect::JointElasticity {
            joint: 0,
            stiffness: -1.0,
            damping: 0.0,
            motor_inertia: 1.0,
        };
        assert!(e.validate().unwrap_err().contains("stiffness"));
        assert!(Effect::TimeDelay { delay: f64::NAN }.validate().is_err());
    }
}
