//! One unmodelled effect with its parameters ([`Effect`]): its kind and
//! place. Its force laws are in `laws.rs`, the check of its parameters in
//! `validate.rs`.

mod laws;
mod validate;

pub(crate) use laws::STRIBECK_GRID;
pub use laws::{smooth_sign, SIGN_SMOOTHING};

use super::EffectKind;

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
    /// A point mass at the tip, relative to the model: negative where the
    /// robot lacks mass the model carries there (down to the tip body's
    /// modelled mass, [`Effect::within_tip_body`]).
    PayloadMass {
        /// Mass, kg.
        mass: f64,
        /// Its position in the tip's frame (centre of mass), m; zero at
        /// the tip's origin (a point tip has no frame: zero there).
        com: [f64; 3],
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
    /// A spring at `joint`: the joint feels `-(stiffness q + preload)`.
    JointSpring {
        /// Joint index.
        joint: usize,
        /// Stiffness (N m/rad or N/m), >= 0.
        stiffness: f64,
        /// The spring's effort at `q = 0` (N m or N): at rest at
        /// `q = -preload / stiffness`.
        preload: f64,
    },
}

impl Effect {
    /// Multiplies the efforts a joint effect exerts by `k` (its force
    /// levels, rotor inertia, stiffness; not its velocities or widths):
    /// the same effect seen through an effort sensor of gain `k`. Effects
    /// at a point or on the sensors are left as they are.
    ///
    /// ```
    /// use dynamics_sim2real::effects::Effect;
    /// let mut e = Effect::ViscousFriction { joint: 0, fv: 0.6 };
    /// e.scale_forces(0.5);
    /// assert_eq!(e, Effect::ViscousFriction { joint: 0, fv: 0.3 });
    /// ```
    pub fn scale_forces(&mut self, k: f64) {
        match self {
            Effect::CoulombFriction { fc, .. } => *fc *= k,
            Effect::ViscousFriction { fv, .. } => *fv *= k,
            Effect::StribeckFriction { fc, fs, .. } => {
                *fc *= k;
                *fs *= k;
            }
            Effect::Armature { inertia, .. } => *inertia *= k,
            Effect::JointSpring {
                stiffness, preload, ..
            } => {
                *stiffness *= k;
                *preload *= k;
            }
            _ => {}
        }
    }
}

impl Effect {
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
            Effect::JointSpring { .. } => EffectKind::JointSpring,
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
            | Effect::EffortOffset { joint, .. }
            | Effect::JointSpring { joint, .. } => Some(joint),
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
}
