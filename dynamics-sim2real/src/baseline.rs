//! The effects of a diagnosis report, back as [`Effect`]s attached to a
//! robot: one report entry (kind, joint or point, named parameters, as in
//! `which.ranked[]` and `which.effects[]`) to one effect, through the
//! diagnosis' own candidate ([`Candidate::effect`]) so that a report reads
//! back as the model the diagnosis corrected with.

use crate::diagnose::{Candidate, Parameter};
use crate::effects::SIGN_SMOOTHING;
use crate::effects::{Effect, EffectKind};
use dynamics_runtime::Robot;

/// One effect as a report names it.
#[derive(Debug, Clone)]
pub struct Entry {
    /// Vocabulary name, e.g. `coulomb_friction`.
    pub kind: String,
    /// Joint name, for joint effects.
    pub joint: Option<String>,
    /// Its parameters by name (`fc`, `mass`, ...); `std` is not used.
    pub parameters: Vec<Parameter>,
}

/// Why a report entry cannot become an effect.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BaselineError {
    /// Not a kind of the vocabulary, or one that names no effect.
    #[error("unknown effect kind `{0}` (known: coulomb_friction, viscous_friction, stribeck_friction, armature, payload_mass, joint_elasticity, backlash, environment_resistance, encoder_offset, time_delay)")]
    Kind(String),
    /// A joint effect without a joint, or a joint the robot does not have.
    #[error("effect `{kind}`: joint {joint:?} is not one of the robot's joints ({known})")]
    Joint {
        /// The kind.
        kind: String,
        /// The joint named (or `None`).
        joint: Option<String>,
        /// The robot's joints.
        known: String,
    },
    /// A parameter the kind needs is missing or not a finite number.
    #[error("effect `{kind}`: parameter `{name}` is missing or not a finite number (it takes: {expected})")]
    Missing {
        /// The kind.
        kind: String,
        /// The parameter.
        name: String,
        /// The names this kind takes.
        expected: String,
    },
    /// A parameter this kind does not take.
    #[error("effect `{kind}`: unknown parameter `{name}` (it takes: {expected})")]
    Unknown {
        /// The kind.
        kind: String,
        /// The parameter.
        name: String,
        /// The names this kind takes.
        expected: String,
    },
}

/// The parameter names of a kind, as the diagnosis reports them.
pub fn parameter_names(kind: EffectKind) -> &'static [&'static str] {
    match kind {
        EffectKind::CoulombFriction => &["fc", "vw"],
        EffectKind::ViscousFriction => &["fv"],
        EffectKind::StribeckFriction => &["fc", "fs_minus_fc", "vs"],
        EffectKind::Armature => &["inertia"],
        EffectKind::PayloadMass => &["mass"],
        EffectKind::EnvironmentResistance => &["mu", "alpha"],
        EffectKind::EncoderOffset => &["offset"],
        EffectKind::TimeDelay => &["delay"],
        EffectKind::JointElasticity => &["motor_inertia", "stiffness", "damping"],
        EffectKind::Backlash => &["motor_inertia", "half_width", "contact_stiffness"],
        EffectKind::EffortScale => &["scale_minus_one"],
        EffectKind::EffortOffset => &["offset"],
        EffectKind::JointSpring => &["stiffness", "preload"],
        EffectKind::None | EffectKind::InertialParameters => &[],
    }
}

/// The effect `entry` names on robot `R`.
///
/// ```
/// use dynamics_sim2real::diagnose::Parameter;
/// use dynamics_sim2real::{baseline::{effect, Entry}, effects::Effect};
/// dynamics_macros::robot! {
///     pub robot Pendulum; gravity = [0.0, -9.81, 0.0];
///     link base; link rod { mass = 1.0; com = [1.0, 0.0, 0.0]; }
///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
/// }
/// let entry = Entry {
///     kind: "coulomb_friction".into(), joint: Some("j".into()),
///     parameters: vec![Parameter { name: "fc".into(), value: 0.3, std: 0.01 }],
/// };
/// assert_eq!(effect::<Pendulum, 1>(&entry).unwrap(), Effect::coulomb(0, 0.3));
/// let bad = Entry { joint: Some("elbow".into()), ..entry };
/// assert!(effect::<Pendulum, 1>(&bad).unwrap_err().to_string().contains("elbow"));
/// ```
pub fn effect<R: Robot<N>, const N: usize>(entry: &Entry) -> Result<Effect, BaselineError> {
    let kind: EffectKind = entry
        .kind
        .parse()
        .map_err(|_| BaselineError::Kind(entry.kind.clone()))?;
    let expected = parameter_names(kind);
    let list = || expected.join(", ");
    if let Some(p) = entry
        .parameters
        .iter()
        .find(|p| !expected.contains(&p.name.as_str()))
    {
        return Err(BaselineError::Unknown {
            kind: entry.kind.clone(),
            name: p.name.clone(),
            expected: list(),
        });
    }
    let get = |name: &str| -> Result<f64, BaselineError> {
        entry
            .parameters
            .iter()
            .find(|p| p.name == name)
            .map(|p| p.value)
            .filter(|v| v.is_finite())
            .ok_or_else(|| BaselineError::Missing {
                kind: entry.kind.clone(),
                name: name.to_string(),
                expected: list(),
            })
    };
    let joint = || -> Result<usize, BaselineError> {
        entry
            .joint
            .as_deref()
            .and_then(R::joint_index)
            .ok_or_else(|| BaselineError::Joint {
                kind: entry.kind.clone(),
                joint: entry.joint.clone(),
                known: R::JOINT_NAMES.join(", "),
            })
    };
    let candidate = match kind {
        // Link inertial corrections come from `identify`, not from a
        // diagnosis report entry.
        EffectKind::None | EffectKind::InertialParameters => {
            return Err(BaselineError::Kind(entry.kind.clone()))
        }
        // (Reports before the width was searched have none: sharp.)
        EffectKind::CoulombFriction => {
            Candidate::Coulomb(joint()?, get("vw").unwrap_or(SIGN_SMOOTHING))
        }
        EffectKind::ViscousFriction => Candidate::Viscous(joint()?),
        EffectKind::StribeckFriction => Candidate::Stribeck(joint()?, get("vs")?),
        EffectKind::Armature => Candidate::Armature(joint()?),
        EffectKind::PayloadMass => Candidate::Payload,
        EffectKind::EnvironmentResistance => Candidate::Environment(get("alpha")?),
        EffectKind::EncoderOffset => Candidate::EncoderOffset(joint()?),
        EffectKind::TimeDelay => Candidate::TimeDelay,
        EffectKind::EffortScale => Candidate::EffortScale(joint()?),
        EffectKind::EffortOffset => Candidate::EffortOffset(joint()?),
        EffectKind::JointSpring => Candidate::Spring(joint()?),
        EffectKind::JointElasticity => {
            return Ok(Effect::JointElasticity {
                joint: joint()?,
                stiffness: get("stiffness")?,
                damping: get("damping")?,
                motor_inertia: get("motor_inertia")?,
            })
        }
        EffectKind::Backlash => {
            // The report gives the contact stiffness; its damping is the
            // generator's (`synth::draw`): 10 % of critical on the rotor.
            let (jm, k) = (get("motor_inertia")?, get("contact_stiffness")?);
            return Ok(Effect::Backlash {
                joint: joint()?,
                half_width: get("half_width")?,
                motor_inertia: jm,
                contact_stiffness: k,
                contact_damping: 0.2 * (k * jm).sqrt(),
            });
        }
    };
    let theta = candidate
        .linear_parameters()
        .iter()
        .map(|(name, _)| get(name))
        .collect::<Result<Vec<f64>, _>>()?;
    candidate
        .effect(&theta)
        .ok_or_else(|| BaselineError::Kind(entry.kind.clone()))
}
