//! The check that an effect's parameters are physical
//! ([`Effect::validate`]), naming the offending one; and the friction
//! corrections that are physical only beside a model's own friction
//! ([`Effect::within_nominal_friction`]).

use super::Effect;

impl Effect {
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
            Effect::PayloadMass { mass, com } => {
                check("mass", mass, false)?;
                match com.iter().all(|c| c.is_finite()) {
                    true => Ok(()),
                    false => Err("payload_mass: com must be finite".into()),
                }
            }
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
            Effect::JointSpring {
                stiffness, preload, ..
            } => {
                check("stiffness", stiffness, false)?;
                if preload.is_finite() {
                    Ok(())
                } else {
                    Err("joint_spring: preload must be finite".into())
                }
            }
        }
    }
}

impl Effect {
    /// [`Effect::validate`] beside a model with per-joint Coulomb levels
    /// `coulomb` and viscous coefficients `viscous`: a friction correction
    /// that takes away no more than the model's own friction
    /// ([`Effect::within_nominal_friction`]) passes too.
    ///
    /// ```
    /// use dynamics_sim2real::effects::Effect;
    /// let less = Effect::ViscousFriction { joint: 0, fv: -0.5 };
    /// assert!(less.validate_beside_friction(&[0.0], &[0.8]).is_ok());
    /// assert!(less.validate_beside_friction(&[0.0], &[0.3]).unwrap_err().contains("fv"));
    /// ```
    pub fn validate_beside_friction(&self, coulomb: &[f64], viscous: &[f64]) -> Result<(), String> {
        self.validate().or_else(|reason| {
            self.within_nominal_friction(coulomb, viscous)
                .then_some(())
                .ok_or(reason)
        })
    }

    /// Whether this is a payload relative to the model that takes away
    /// mass the model carries at the tip: a `payload_mass` whose mass is
    /// negative down to minus `body_mass`, the modelled mass of the body
    /// that carries the tip ([`crate::effects::Tip::body_mass`]). A robot
    /// logged without the hand its model has is such a payload.
    ///
    /// ```
    /// use dynamics_sim2real::effects::Effect;
    /// let hand_absent = Effect::PayloadMass { mass: -0.7, com: [0.0, 0.0, -0.07] };
    /// assert!(hand_absent.validate().is_err());
    /// assert!(hand_absent.within_tip_body(1.5));
    /// assert!(!hand_absent.within_tip_body(0.5));
    /// ```
    pub fn within_tip_body(&self, body_mass: f64) -> bool {
        matches!(*self, Effect::PayloadMass { mass, com }
            if mass.is_finite() && mass >= -body_mass * (1.0 + 1e-9)
                && com.iter().all(|c| c.is_finite()))
    }

    /// Whether this is a friction correction that takes away no more
    /// friction than a model with per-joint Coulomb levels `coulomb` and
    /// viscous coefficients `viscous` has (`coulomb_friction`,
    /// `stribeck_friction` or `viscous_friction` whose levels may be
    /// negative down to minus the model's own; their other parameters
    /// valid). With the model's friction the total stays dissipative: a
    /// CAD export's made-up damping taken away by the diagnosis.
    ///
    /// ```
    /// use dynamics_sim2real::effects::Effect;
    /// let less = Effect::ViscousFriction { joint: 0, fv: -0.5 };
    /// assert!(less.validate().is_err());
    /// assert!(less.within_nominal_friction(&[0.0], &[0.8]));
    /// assert!(!less.within_nominal_friction(&[0.0], &[0.3]));
    /// ```
    pub fn within_nominal_friction(&self, coulomb: &[f64], viscous: &[f64]) -> bool {
        let ok = |x: f64, nominal: Option<&f64>| {
            nominal.is_some_and(|n| x.is_finite() && x >= -n * (1.0 + 1e-9))
        };
        match *self {
            Effect::CoulombFriction { joint, fc, vw } => {
                ok(fc, coulomb.get(joint)) && vw.is_finite() && vw > 0.0
            }
            Effect::ViscousFriction { joint, fv } => ok(fv, viscous.get(joint)),
            Effect::StribeckFriction { joint, fc, fs, vs } => {
                ok(fc, coulomb.get(joint))
                    && ok(fs, coulomb.get(joint))
                    && vs.is_finite()
                    && vs > 0.0
            }
            _ => false,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
