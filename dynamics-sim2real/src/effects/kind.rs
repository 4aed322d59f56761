//! The vocabulary of unmodelled effects (docs/diagnosis.md): each kind's name as it appears in CSV truth files, JSON
//! reports and on the command line.

use std::fmt;
use std::str::FromStr;

/// What kind of unmodelled effect.
///
/// ```
/// use dynamics_sim2real::effects::EffectKind;
/// let k: EffectKind = "backlash".parse().unwrap();
/// assert_eq!(k, EffectKind::Backlash);
/// assert_eq!(k.to_string(), "backlash");
/// assert_eq!(format!("{k:<10}|"), "backlash  |"); // widths as a string's
/// assert!("glue".parse::<EffectKind>().is_err());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum EffectKind {
    /// The model explains the data within noise.
    None,
    /// Coulomb friction `-Fc sign(qd)`.
    CoulombFriction,
    /// Viscous friction `-Fv qd`.
    ViscousFriction,
    /// Stribeck friction `-(Fc + (Fs - Fc) exp(-(qd/vs)^2)) sign(qd)`.
    StribeckFriction,
    /// Rotor inertia reflected to the joint.
    Armature,
    /// A link's mass, first moments and inertia differ from the model's.
    /// (Not in [`EffectKind::ALL`] yet: the draws from it stay as they
    /// are until the diagnosis has a candidate for it.)
    InertialParameters,
    /// An extra point mass at the tip.
    PayloadMass,
    /// A two-mass joint: motor and link joined by a spring and a damper.
    JointElasticity,
    /// A dead zone of half-width delta between motor and link.
    Backlash,
    /// `F = -mu |v|^(alpha-1) v` at the tip (dissertation, sec. 3.4).
    EnvironmentResistance,
    /// The encoder reads `q + offset`.
    EncoderOffset,
    /// Positions and velocities are recorded `delay` seconds late.
    TimeDelay,
    /// The measured effort is `scale` times the applied one (a torque
    /// constant or gear ratio that is off: efforts computed from motor
    /// currents).
    EffortScale,
    /// The measured effort carries a constant `offset` (a sensor bias; with
    /// Coulomb friction at the same joint, a friction level that depends on
    /// the direction of motion).
    EffortOffset,
    /// A spring at the joint: effort `-(stiffness q + preload)` (a cable
    /// harness or hose bent by the joint, a compensator's spring; at rest
    /// at `q = -preload / stiffness`).
    JointSpring,
}

impl EffectKind {
    /// Every kind, `None` first.
    pub const ALL: [EffectKind; 14] = [
        EffectKind::None,
        EffectKind::CoulombFriction,
        EffectKind::ViscousFriction,
        EffectKind::StribeckFriction,
        EffectKind::Armature,
        EffectKind::PayloadMass,
        EffectKind::JointElasticity,
        EffectKind::Backlash,
        EffectKind::EnvironmentResistance,
        EffectKind::EncoderOffset,
        EffectKind::TimeDelay,
        EffectKind::EffortScale,
        EffectKind::EffortOffset,
        EffectKind::JointSpring,
    ];

    /// The name of the vocabulary (`coulomb_friction`, ...).
    pub fn name(self) -> &'static str {
        match self {
            EffectKind::None => "none",
            EffectKind::CoulombFriction => "coulomb_friction",
            EffectKind::ViscousFriction => "viscous_friction",
            EffectKind::StribeckFriction => "stribeck_friction",
            EffectKind::Armature => "armature",
            EffectKind::InertialParameters => "inertial_parameters",
            EffectKind::PayloadMass => "payload_mass",
            EffectKind::JointElasticity => "joint_elasticity",
            EffectKind::Backlash => "backlash",
            EffectKind::EnvironmentResistance => "environment_resistance",
            EffectKind::EncoderOffset => "encoder_offset",
            EffectKind::TimeDelay => "time_delay",
            EffectKind::EffortScale => "effort_scale",
            EffectKind::EffortOffset => "effort_offset",
            EffectKind::JointSpring => "joint_spring",
        }
    }

    /// Where the effect sits.
    pub fn place(self) -> PlaceKind {
        match self {
            EffectKind::None => PlaceKind::Nowhere,
            EffectKind::PayloadMass | EffectKind::EnvironmentResistance => PlaceKind::Point,
            EffectKind::InertialParameters => PlaceKind::Link,
            EffectKind::TimeDelay => PlaceKind::All,
            _ => PlaceKind::Joint,
        }
    }
}

/// Where an effect of some kind acts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PlaceKind {
    /// Nowhere (`none`).
    Nowhere,
    /// At one joint.
    Joint,
    /// At a point (the tip).
    Point,
    /// On one link's mass properties.
    Link,
    /// On every measured signal.
    All,
}

impl serde::Serialize for EffectKind {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.name())
    }
}

impl fmt::Display for EffectKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.pad(self.name())
    }
}

/// An effect name outside the vocabulary.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown effect `{0}`; known: none, coulomb_friction, viscous_friction, stribeck_friction, armature, inertial_parameters, payload_mass, joint_elasticity, backlash, environment_resistance, encoder_offset, time_delay, effort_scale, effort_offset, joint_spring")]
pub struct UnknownEffect(pub String);

impl FromStr for EffectKind {
    type Err = UnknownEffect;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        EffectKind::ALL
            .into_iter()
            .chain([EffectKind::InertialParameters])
            .find(|k| k.name() == s)
            .ok_or_else(|| UnknownEffect(s.to_string()))
    }
}
