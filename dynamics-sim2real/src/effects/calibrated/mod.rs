//! A robot with known effects folded into its nominal model: what a
//! previous diagnosis found (a calibrated baseline), so that the next one
//! compares data against the calibrated robot and names only what changed.
//!
//! [`Calibrated`] implements [`Robot`] by adding the effects that act as
//! forces or inertia (friction laws, rotor inertia, a payload at the tip,
//! environment resistance) to every quantity of the wrapped model, the way
//! the plant adds them ([`crate::effects::Plant::mass_and_forces`]).
//! Effects that are not a rigid model's are kept apart, for the data to be
//! corrected by (`dynamics_sim2real::baseline::undo`): those on the
//! sensors (encoder offset, delay, effort scale and offset), those with a
//! motor-side state of their own (elasticity, backlash: the effort that
//! reaches the link is simulated along the record), and effects limited to
//! a window of the record's time.
//!
//! Here: the folding (which effects, what they add at a state) and the
//! effects kept apart; the [`Robot`] implementation in `robot.rs`.

mod robot;
#[cfg(test)]
mod tests;

use nalgebra::{SMatrix, SVector, Vector3};

use super::{Effect, EffectKind, Tip, Window};
use dynamics_runtime::Robot;

/// Why effects cannot be taken into a calibrated model.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CalibratedError {
    /// No effect (the vocabulary's `none`).
    #[error("effect `{kind}` is no effect to take back")]
    NotNominal {
        /// Its kind's name.
        kind: &'static str,
    },
    /// An effect that cannot be limited to a window (a delay, a motor
    /// side: their state carries over the window's edges).
    #[error("effect `{kind}` cannot be limited to a window (kinds that can: every force or inertia of the model, encoder_offset, effort_scale, effort_offset)")]
    NotWindowed {
        /// Its kind's name.
        kind: &'static str,
    },
    /// A window that is not a span of time.
    #[error("effect `{kind}`: {reason}")]
    Window {
        /// Its kind's name.
        kind: &'static str,
        /// What is wrong with the window.
        reason: String,
    },
    /// A link correction of a link the robot does not have.
    #[error("effect `{kind}` at link index {link}: the robot has {n} links")]
    Link {
        /// Its kind's name.
        kind: &'static str,
        /// The link index.
        link: usize,
        /// The robot's link count.
        n: usize,
    },
    /// An effect on a joint the robot does not have.
    #[error("effect `{kind}` at joint index {joint}: the robot has {n} joints")]
    Joint {
        /// Its kind's name.
        kind: &'static str,
        /// The joint index.
        joint: usize,
        /// The robot's joint count.
        n: usize,
    },
    /// An unphysical parameter.
    #[error("effect `{kind}`: {reason}")]
    Invalid {
        /// Its kind's name.
        kind: &'static str,
        /// What is wrong.
        reason: String,
    },
}

/// `robot` with `effects` added to its nominal model.
///
/// ```
/// use dynamics_runtime::Robot;
/// use dynamics_sim2real::effects::{Calibrated, Effect};
/// dynamics_macros::robot! {
///     pub robot Pendulum; gravity = [0.0, -9.81, 0.0];
///     link base; link rod { mass = 1.0; com = [1.0, 0.0, 0.0]; }
///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
/// }
/// let friction = Effect::ViscousFriction { joint: 0, fv: 0.5 };
/// let r = Calibrated::new(Pendulum::default(), vec![friction]).unwrap();
/// let (q, qd, qdd) = (nalgebra::Vector1::new(0.0), nalgebra::Vector1::new(2.0), nalgebra::Vector1::new(0.0));
/// // m g l cos q to hold it, plus fv qd to overcome the friction:
/// assert!((r.inverse_dynamics(&q, &qd, &qdd)[0] - (9.81 + 1.0)).abs() < 1e-12);
/// ```
#[derive(Debug, Clone)]
pub struct Calibrated<R, const N: usize> {
    robot: R,
    effects: Vec<Effect>,
    sensors: Vec<Effect>,
    motor: Vec<Effect>,
    windowed: Vec<(Effect, Window)>,
    tip: Tip,
}

/// Where an effect of a baseline goes.
enum Place {
    /// Folded into the model.
    Model,
    /// Undone on the sensors' data.
    Sensor,
    /// A motor side, simulated along the data.
    Motor,
}

/// What the effects add at one state: to A, to Q(0), to Qqt1 + Qqt2.
struct Extra<const N: usize> {
    a: SMatrix<f64, N, N>,
    q0: SVector<f64, N>,
    qqt: SVector<f64, N>,
}

impl<R: Robot<N>, const N: usize> Calibrated<R, N> {
    /// Folds `effects` into `robot`'s nominal model. A friction correction
    /// may take away friction the nominal model has (a URDF's `<dynamics
    /// damping friction>`), no more ([`Effect::within_nominal_friction`]);
    /// a payload may take away mass the model carries at the tip, no more
    /// than the tip body's ([`Effect::within_tip_body`]).
    ///
    /// Effects on the sensors (encoder offsets, a delay, effort scales and
    /// offsets) are not part of the model: they are kept apart
    /// ([`Calibrated::sensor_effects`]) for the data to be corrected by
    /// ([`crate::effects::undo_sensors`]). A late effort stream is a
    /// negative `time_delay` here. Elasticity and backlash are kept apart
    /// too ([`Calibrated::motor_effects`]): their motor side has a state of
    /// its own, which the data's correction simulates.
    pub fn new(robot: R, effects: Vec<Effect>) -> Result<Self, CalibratedError> {
        Self::timed(robot, effects.into_iter().map(|e| (e, None)).collect())
    }

    /// [`Calibrated::new`] with effects limited to a window of the
    /// record's time (`Some(window)`): those are kept apart
    /// ([`Calibrated::windowed_effects`]), to be undone on the data inside
    /// their window; a delay and a motor side cannot be limited in time.
    ///
    /// ```
    /// use dynamics_sim2real::effects::{Calibrated, Effect, Window};
    /// dynamics_macros::robot! {
    ///     pub robot Pendulum; gravity = [0.0, -9.81, 0.0];
    ///     link base; link rod { mass = 1.0; com = [1.0, 0.0, 0.0]; }
    ///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
    /// }
    /// let held: Window = "2:4".parse().unwrap();
    /// let payload = Effect::PayloadMass { mass: 0.5, com: [0.0; 3] };
    /// let r = Calibrated::timed(Pendulum::default(), vec![(payload, Some(held))]).unwrap();
    /// assert!(r.effects().is_empty());
    /// assert_eq!(r.windowed_effects(), &[(payload, held)]);
    /// let late = Effect::TimeDelay { delay: 0.01 };
    /// assert!(Calibrated::timed(Pendulum::default(), vec![(late, Some(held))]).is_err());
    /// ```
    pub fn timed(
        robot: R,
        effects: Vec<(Effect, Option<Window>)>,
    ) -> Result<Self, CalibratedError> {
        let (coulomb, viscous) = super::nominal_friction(&robot, &SVector::zeros());
        let tip_mass = Tip::body_mass::<R, N>(&robot);
        let (mut model, mut sensors, mut motor) = (Vec::new(), Vec::new(), Vec::new());
        let mut windowed = Vec::new();
        for (e, window) in effects {
            let kind = e.kind().name();
            let place = match e.kind() {
                EffectKind::CoulombFriction
                | EffectKind::ViscousFriction
                | EffectKind::StribeckFriction
                | EffectKind::Armature
                | EffectKind::PayloadMass
                | EffectKind::EnvironmentResistance
                | EffectKind::JointSpring
                | EffectKind::InertialParameters => Place::Model,
                EffectKind::EncoderOffset
                | EffectKind::TimeDelay
                | EffectKind::EffortScale
                | EffectKind::EffortOffset => Place::Sensor,
                EffectKind::JointElasticity | EffectKind::Backlash => Place::Motor,
                EffectKind::None => return Err(CalibratedError::NotNominal { kind }),
            };
            if let Some(joint) = e.joint().filter(|&j| j >= N) {
                return Err(CalibratedError::Joint { kind, joint, n: N });
            }
            if let Effect::InertialParameters { link, .. } = e {
                if link >= R::LINK_NAMES.len() {
                    let n = R::LINK_NAMES.len();
                    return Err(CalibratedError::Link { kind, link, n });
                }
            }
            match e {
                // Either way late.
                Effect::TimeDelay { delay } if delay.is_finite() => {}
                _ => e
                    .validate_beside_friction(coulomb.as_slice(), viscous.as_slice())
                    .or_else(|reason| e.within_tip_body(tip_mass).then_some(()).ok_or(reason))
                    .map_err(|reason| CalibratedError::Invalid { kind, reason })?,
            }
            match (window, place) {
                (Some(_), Place::Motor) => return Err(CalibratedError::NotWindowed { kind }),
                (Some(_), _) if matches!(e, Effect::TimeDelay { .. }) => {
                    return Err(CalibratedError::NotWindowed { kind })
                }
                (Some(w), _) => {
                    w.validate().map_err(|err| CalibratedError::Window {
                        kind,
                        reason: err.to_string(),
                    })?;
                    windowed.push((e, w));
                }
                (None, Place::Model) => model.push(e),
                (None, Place::Sensor) => sensors.push(e),
                (None, Place::Motor) => motor.push(e),
            }
        }
        // A diagnosis fits the other effects in the measured effort's units:
        // at a joint whose effort reads `scale` times the applied one, its
        // joint's own forces are `scale` times too large for the model. So
        // is an effort offset limited to a window: the record's effort is
        // divided by the scale (always on) before the windowed offset is
        // taken out of it.
        for s in &sensors {
            if let Effect::EffortScale { joint, scale } = *s {
                let own = model
                    .iter_mut()
                    .chain(windowed.iter_mut().map(|(e, _)| e))
                    .filter(|e| e.joint() == Some(joint) && e.kind() != EffectKind::EffortScale);
                for e in own {
                    e.scale_forces(1.0 / scale);
                    if let Effect::EffortOffset { offset, .. } = e {
                        *offset /= scale;
                    }
                }
            }
        }
        // Undone in the reverse of how they act: the offset, then the scale.
        sensors.sort_by_key(|e| !matches!(e, Effect::EffortOffset { .. }));
        Ok(Calibrated {
            robot,
            effects: model,
            sensors,
            motor,
            windowed,
            tip: Tip::of::<R, N>(),
        })
    }

    /// The effects on the sensors, to be undone on measured data.
    pub fn sensor_effects(&self) -> &[Effect] {
        &self.sensors
    }

    /// The motor sides (elasticity, backlash), to be simulated along
    /// measured data.
    pub fn motor_effects(&self) -> &[Effect] {
        &self.motor
    }

    /// The effects limited to a window of the record's time, to be undone
    /// on measured data inside it.
    pub fn windowed_effects(&self) -> &[(Effect, Window)] {
        &self.windowed
    }

    /// Whether every effect of the baseline is folded into the model
    /// (none kept apart for the data: a robot that stands for the whole
    /// baseline wherever a model alone is used).
    pub fn model_only(&self) -> bool {
        self.sensors.is_empty() && self.motor.is_empty() && self.windowed.is_empty()
    }

    /// The wrapped nominal model.
    pub fn nominal(&self) -> &R {
        &self.robot
    }

    /// The effects folded in (not those on the sensors).
    pub fn effects(&self) -> &[Effect] {
        &self.effects
    }

    fn extra(&self, q: &SVector<f64, N>, qd: &SVector<f64, N>) -> Extra<N> {
        let mut x = Extra {
            a: SMatrix::zeros(),
            q0: SVector::zeros(),
            qqt: SVector::zeros(),
        };
        for e in &self.effects {
            match *e {
                Effect::CoulombFriction { joint, .. }
                | Effect::ViscousFriction { joint, .. }
                | Effect::StribeckFriction { joint, .. } => x.q0[joint] += e.joint_force(qd[joint]),
                Effect::Armature { joint, inertia } => x.a[(joint, joint)] += inertia,
                Effect::JointSpring {
                    joint,
                    stiffness,
                    preload,
                } => x.q0[joint] -= stiffness * q[joint] + preload,
                Effect::PayloadMass { mass, com } => {
                    let c = Vector3::from(com);
                    let (_, jac) = self.tip.position_jacobian_at(&self.robot, q, &c);
                    let bias = self.tip.bias_acceleration_at(&self.robot, q, qd, &c);
                    x.a += jac.transpose() * jac * mass;
                    x.q0 += jac.transpose() * (Vector3::from(R::GRAVITY) * mass);
                    x.qqt -= jac.transpose() * (bias * mass);
                }
                Effect::InertialParameters { link, ref delta } => {
                    let (da, df) = crate::effects::inertial::terms(&self.robot, link, delta, q, qd);
                    let (_, f0) = crate::effects::inertial::terms(
                        &self.robot,
                        link,
                        delta,
                        q,
                        &SVector::zeros(),
                    );
                    x.a += da;
                    x.q0 += f0;
                    x.qqt += df - f0;
                }
                Effect::EnvironmentResistance { .. } => {
                    let (_, jac) = self.tip.position_jacobian(&self.robot, q);
                    x.q0 += jac.transpose() * e.resistance(&(jac * qd));
                }
                _ => {}
            }
        }
        x
    }

    /// What the effects add to the residual `F = A qdd - Q - Qqt - U`.
    fn extra_residual(
        &self,
        q: &SVector<f64, N>,
        qd: &SVector<f64, N>,
        qdd: &SVector<f64, N>,
    ) -> SVector<f64, N> {
        let x = self.extra(q, qd);
        x.a * qdd - x.q0 - x.qqt
    }

    /// What the link corrections add to the forces at rest (gravity
    /// only): `-Y(q, 0, 0) delta` summed over them.
    fn links_at_rest(&self, q: &SVector<f64, N>) -> SVector<f64, N> {
        let zero = SVector::zeros();
        self.effects
            .iter()
            .filter_map(|e| match e {
                Effect::InertialParameters { link, delta } => {
                    Some(crate::effects::inertial::terms(&self.robot, *link, delta, q, &zero).1)
                }
                _ => None,
            })
            .sum()
    }

    /// A Coriolis matrix of the link corrections' velocity efforts `c(qd)`
    /// (quadratic in `qd`): half their Jacobian in `qd`, by central
    /// differences (exact for a quadratic, to rounding), so that
    /// `C qd = c`.
    fn links_coriolis(&self, q: &SVector<f64, N>, qd: &SVector<f64, N>) -> SMatrix<f64, N, N> {
        let mut c = SMatrix::<f64, N, N>::zeros();
        if !self
            .effects
            .iter()
            .any(|e| matches!(e, Effect::InertialParameters { .. }))
        {
            return c;
        }
        let velocity = |v: &SVector<f64, N>| -> SVector<f64, N> {
            let x = self.extra(q, v);
            // Only the links' share: a payload's is added by the caller.
            -(x.qqt - self.payload_qqt(q, v))
        };
        for k in 0..N {
            let h = 1e-3 * (1.0 + qd[k].abs());
            let (mut p, mut m) = (*qd, *qd);
            p[k] += h;
            m[k] -= h;
            c.set_column(k, &((velocity(&p) - velocity(&m)) / (4.0 * h)));
        }
        c
    }

    /// The payloads' share of the velocity terms (`-m J^T Jd qd` each, at
    /// its centre of mass).
    fn payload_qqt(&self, q: &SVector<f64, N>, qd: &SVector<f64, N>) -> SVector<f64, N> {
        self.effects
            .iter()
            .filter_map(|e| match *e {
                Effect::PayloadMass { mass, com } if mass != 0.0 => {
                    let c = Vector3::from(com);
                    let (_, jac) = self.tip.position_jacobian_at(&self.robot, q, &c);
                    let bias = self.tip.bias_acceleration_at(&self.robot, q, qd, &c);
                    Some(-(jac.transpose() * (bias * mass)))
                }
                _ => None,
            })
            .sum()
    }

    /// The link corrections' potential energy, `-g . (dm p + R dmc)` of
    /// each link at its frame (a link with no frame of its name adds
    /// none).
    fn links_potential(&self, q: &SVector<f64, N>) -> f64 {
        let g = Vector3::from(R::GRAVITY);
        self.effects
            .iter()
            .filter_map(|e| match e {
                Effect::InertialParameters { link, delta } => {
                    let name = R::LINK_NAMES.get(*link)?;
                    let frame = R::FRAME_NAMES.iter().position(|f| f == name)?;
                    let pose = self.robot.frame_pose(frame, q)?;
                    let p = Vector3::new(pose[(0, 3)], pose[(1, 3)], pose[(2, 3)]);
                    let rot = pose.fixed_view::<3, 3>(0, 0);
                    let mc = Vector3::new(delta[1], delta[2], delta[3]);
                    Some(-g.dot(&(p * delta[0] + rot * mc)))
                }
                _ => None,
            })
            .sum()
    }

    /// Each payload's mass and centre of mass in the tip's frame.
    fn payloads(&self) -> Vec<(f64, Vector3<f64>)> {
        self.effects
            .iter()
            .filter_map(|e| match *e {
                Effect::PayloadMass { mass, com } if mass != 0.0 => {
                    Some((mass, Vector3::from(com)))
                }
                _ => None,
            })
            .collect()
    }
}
