//! The effects of a diagnosis report, back as [`Effect`]s attached to a
//! robot: one report entry (kind, joint or point, named parameters, as in
//! `which.ranked[]` and `which.effects[]`) to one effect, through the
//! diagnosis' own candidate ([`Candidate::effect`]) so that a report reads
//! back as the model the diagnosis corrected with.
//!
//! - here: an entry to an effect (and its window, when it has one);
//! - `undo.rs`: what a calibrated baseline cannot fold into the rigid
//!   model, undone on measured data: the sensors' effects, the motor
//!   sides (the effort that reaches the link, simulated along the record),
//!   the effects limited to a window.

mod undo;

pub use undo::{undo, UndoError};

use crate::diagnose::{Candidate, Channel, Explained, Parameter, Unnamed};
use crate::effects::{Effect, EffectKind, Window};
use dynamics_runtime::Robot;

/// One effect as a report names it.
#[derive(Debug, Clone)]
pub struct Entry {
    /// Vocabulary name, e.g. `coulomb_friction`.
    pub kind: String,
    /// Joint name, for joint effects.
    pub joint: Option<String>,
    /// Point or link name, for effects at a point (the link of an
    /// `inertial_parameters` correction).
    pub point: Option<String>,
    /// For `time_delay`: the late channel (`None`: `all`, the motion late
    /// against the effort).
    pub channel: Option<Channel>,
    /// Its parameters by name (`fc`, `mass`, ...); `std` is not used.
    pub parameters: Vec<Parameter>,
    /// The time span of an effect limited in time, in the record's own
    /// times (`None`: on all the time).
    pub window: Option<Window>,
}

/// A report's effect as a baseline entry, its window included.
///
/// ```
/// use dynamics_sim2real::baseline::Entry;
/// use dynamics_sim2real::data::Measured;
/// use dynamics_sim2real::diagnose::{diagnose, Options};
/// use dynamics_runtime::Robot;
/// fn entries<R: Robot<3> + Clone + Send + Sync + 'static>(robot: &R, train: &Measured<3>, holdout: &Measured<3>) {
///     let report = diagnose(robot, train, holdout, &Options::default(), &|_, _| {}).expect("enough data");
///     let back: Vec<Entry> = report.which.effects.iter().map(Entry::from).collect();
///     assert_eq!(back.len(), report.which.effects.len());
/// }
/// ```
impl From<&Explained> for Entry {
    fn from(e: &Explained) -> Self {
        Entry {
            kind: e.kind.name().to_string(),
            joint: e.joint.clone(),
            point: e.point.clone(),
            channel: e.channel,
            parameters: e.parameters.clone(),
            window: e.window.as_ref().map(|w| Window {
                start: w.start,
                end: w.end,
            }),
        }
    }
}

/// Why a report entry cannot become an effect.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BaselineError {
    /// Not a kind of the vocabulary, or one that names no effect.
    #[error("unknown effect kind `{0}` (known: {known})", known = known_kinds())]
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
    /// A link correction without a link, or a link the robot does not have.
    #[error(
        "effect `inertial_parameters`: link {link:?} is not one of the robot's links ({known})"
    )]
    Link {
        /// The link named (or `None`).
        link: Option<String>,
        /// The robot's links.
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
    /// A window that is not a span of time.
    #[error("effect `{kind}`: {reason}")]
    Window {
        /// The kind.
        kind: String,
        /// What is wrong with the window.
        reason: String,
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

/// The kinds a report entry can name as an effect, comma-separated.
///
/// ```
/// let known = dynamics_sim2real::baseline::known_kinds();
/// assert!(known.starts_with("coulomb_friction, ") && known.ends_with("joint_spring"));
/// ```
pub fn known_kinds() -> String {
    EffectKind::ALL
        .iter()
        .filter(|k| **k != EffectKind::None)
        .map(|k| k.name())
        .collect::<Vec<_>>()
        .join(", ")
}

/// The parameter names of a kind, as the diagnosis reports them.
pub fn parameter_names(kind: EffectKind) -> &'static [&'static str] {
    match kind {
        EffectKind::CoulombFriction => &["fc", "vw"],
        EffectKind::ViscousFriction => &["fv"],
        EffectKind::StribeckFriction => &["fc", "fs_minus_fc", "vs"],
        EffectKind::Armature => &["inertia"],
        EffectKind::PayloadMass => &["mass", "com_x", "com_y", "com_z"],
        EffectKind::EnvironmentResistance => &["mu", "alpha"],
        EffectKind::EncoderOffset => &["offset"],
        EffectKind::TimeDelay => &["delay"],
        EffectKind::JointElasticity => &["motor_inertia", "stiffness", "damping"],
        EffectKind::Backlash => &[
            "motor_inertia",
            "half_width",
            "contact_stiffness",
            "contact_damping",
        ],
        EffectKind::EffortScale => &["scale"],
        EffectKind::EffortOffset => &["offset"],
        EffectKind::JointSpring => &["stiffness", "preload"],
        EffectKind::InertialParameters => &crate::inertial::PARAMETER_NAMES_DELTA,
        EffectKind::None => &[],
    }
}

/// The effect `entry` names on robot `R`, and its window when it is
/// limited in time (checked to be a span of time).
///
/// ```
/// use dynamics_sim2real::diagnose::Parameter;
/// use dynamics_sim2real::{baseline::{timed, Entry}, effects::{Effect, Window}};
/// dynamics_macros::robot! {
///     pub robot Pendulum; gravity = [0.0, -9.81, 0.0];
///     link base; link rod { mass = 1.0; com = [1.0, 0.0, 0.0]; }
///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
/// }
/// let held = Window { start: 2.0, end: 4.0 };
/// let entry = Entry {
///     kind: "payload_mass".into(), joint: None, point: Some("rod".into()), channel: None,
///     parameters: vec![Parameter { name: "mass".into(), value: 0.5, std: 0.01, note: None }],
///     window: Some(held),
/// };
/// let (e, w) = timed::<Pendulum, 1>(&entry).unwrap();
/// assert!(matches!(e, Effect::PayloadMass { mass, .. } if mass == 0.5));
/// assert_eq!(w, Some(held));
/// let backwards = Entry { window: Some(Window { start: 4.0, end: 2.0 }), ..entry };
/// assert!(timed::<Pendulum, 1>(&backwards).unwrap_err().to_string().contains("window"));
/// ```
pub fn timed<R: Robot<N>, const N: usize>(
    entry: &Entry,
) -> Result<(Effect, Option<Window>), BaselineError> {
    let e = effect::<R, N>(entry)?;
    if let Some(w) = entry.window {
        w.validate().map_err(|err| BaselineError::Window {
            kind: entry.kind.clone(),
            reason: err.to_string(),
        })?;
    }
    Ok((e, entry.window))
}

/// The effect `entry` names on robot `R` (its window, if any, aside:
/// [`timed`]).
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
///     kind: "coulomb_friction".into(), joint: Some("j".into()), point: None, channel: None,
///     parameters: vec![Parameter { name: "fc".into(), value: 0.3, std: 0.01, note: None }],
///     window: None,
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
    if kind == EffectKind::InertialParameters {
        let link = entry
            .point
            .as_deref()
            .and_then(|p| R::LINK_NAMES.iter().position(|l| *l == p))
            .ok_or_else(|| BaselineError::Link {
                link: entry.point.clone(),
                known: R::LINK_NAMES.join(", "),
            })?;
        let mut delta = [0.0; 10];
        for (d, name) in delta.iter_mut().zip(expected) {
            *d = get(name)?;
        }
        return Ok(Effect::InertialParameters { link, delta });
    }
    let joint = entry.joint.as_deref().and_then(R::joint_index);
    let value = |name: &str| get(name).ok();
    let candidate = Candidate::named(kind, joint, entry.channel, &value).map_err(|e| match e {
        Unnamed::Kind(_) | Unnamed::Channel(_) => BaselineError::Kind(entry.kind.clone()),
        Unnamed::Joint => BaselineError::Joint {
            kind: entry.kind.clone(),
            joint: entry.joint.clone(),
            known: R::JOINT_NAMES.join(", "),
        },
        Unnamed::Missing(name) => BaselineError::Missing {
            kind: entry.kind.clone(),
            name: name.to_string(),
            expected: list(),
        },
    })?;
    match candidate {
        Candidate::Elasticity(joint) => {
            return Ok(Effect::JointElasticity {
                joint,
                stiffness: get("stiffness")?,
                damping: get("damping")?,
                motor_inertia: get("motor_inertia")?,
            })
        }
        Candidate::Backlash(joint) => {
            // The report gives the contact's damping as fitted; an entry
            // without it (a report of an earlier version, a hand-written
            // baseline) takes the diagnosis's grid value: 10 % of critical
            // on the rotor.
            let (jm, k) = (get("motor_inertia")?, get("contact_stiffness")?);
            let damping = match entry.parameters.iter().any(|p| p.name == "contact_damping") {
                true => get("contact_damping")?,
                false => 0.2 * (k * jm).sqrt(),
            };
            return Ok(Effect::Backlash {
                joint,
                half_width: get("half_width")?,
                motor_inertia: jm,
                contact_stiffness: k,
                contact_damping: damping,
            });
        }
        _ => {}
    }
    // The report gives an effort scale as the scale; it is fitted as the
    // scale less one. A payload's centre of mass is fitted as its first
    // moments (mass times the centre).
    let theta = candidate
        .linear_parameters()
        .iter()
        .map(|(name, _)| match *name {
            "scale_minus_one" => get("scale").map(|s| s - 1.0),
            "mass_com_x" => Ok(get("mass")? * get("com_x")?),
            "mass_com_y" => Ok(get("mass")? * get("com_y")?),
            "mass_com_z" => Ok(get("mass")? * get("com_z")?),
            _ => get(name),
        })
        .collect::<Result<Vec<f64>, _>>()?;
    candidate
        .effect(&theta)
        .ok_or_else(|| BaselineError::Kind(entry.kind.clone()))
}

#[cfg(test)]
mod tests {
    use super::*;

    dynamics_macros::robot! {
        robot Arm2;
        gravity = [0.0, -9.81, 0.0];
        link base;
        link upper { mass = 1.0; com = [0.2, 0.0, 0.0]; inertia = [1e-4, 0.01, 0.01]; }
        link lower { mass = 0.5; com = [0.1, 0.0, 0.0]; inertia = [1e-4, 0.005, 0.005]; }
        joint j1 = revolute(base -> upper) { transfer = [rot_z(q)]; }
        joint j2 = revolute(upper -> lower) { transfer = [tu(0.4), rot(q)]; }
    }

    fn entry(kind: &str, channel: Option<Channel>, parameters: &[(&str, f64)]) -> Entry {
        Entry {
            kind: kind.into(),
            joint: Some("j2".into()),
            point: None,
            channel,
            window: None,
            parameters: parameters
                .iter()
                .map(|&(name, value)| Parameter {
                    name: name.into(),
                    value,
                    std: 0.0,
                    note: None,
                })
                .collect(),
        }
    }

    /// A late effort is the motion early: a negative delay, as the
    /// diagnosis's own late-effort candidate makes it; positions or the
    /// whole motion late are a positive one.
    #[test]
    fn a_delay_comes_back_on_its_channel() {
        let delay = [("delay", 0.01)];
        let of = |channel| effect::<Arm2, 2>(&entry("time_delay", channel, &delay));
        assert_eq!(of(None), Ok(Effect::TimeDelay { delay: 0.01 }));
        assert_eq!(
            of(Some(Channel::All)),
            Ok(Effect::TimeDelay { delay: 0.01 })
        );
        assert_eq!(
            of(Some(Channel::Positions)),
            Ok(Effect::TimeDelay { delay: 0.01 })
        );
        assert_eq!(
            of(Some(Channel::Effort)),
            Ok(Effect::TimeDelay { delay: -0.01 })
        );
    }

    /// Every kind the function takes back is one the error for an unknown
    /// kind lists, and every kind it lists is taken back.
    #[test]
    fn the_unknown_kind_error_lists_every_kind_taken() {
        let message = BaselineError::Kind("glue".into()).to_string();
        for kind in EffectKind::ALL
            .into_iter()
            .filter(|k| *k != EffectKind::None)
        {
            let parameters: Vec<(&str, f64)> = parameter_names(kind)
                .iter()
                .map(|&n| (n, if n == "scale" { 1.1 } else { 0.5 }))
                .collect();
            let e = effect::<Arm2, 2>(&entry(kind.name(), None, &parameters));
            assert!(e.is_ok(), "{kind}: {e:?}");
            assert!(message.contains(kind.name()), "{kind} not in: {message}");
        }
    }

    /// The report writes an effort scale as the scale; it comes back as
    /// that scale.
    #[test]
    fn an_effort_scale_comes_back_as_the_report_writes_it() {
        let e = effect::<Arm2, 2>(&entry("effort_scale", None, &[("scale", 1.1)]));
        match e {
            Ok(Effect::EffortScale { joint: 1, scale }) => assert!((scale - 1.1).abs() < 1e-12),
            other => panic!("{other:?}"),
        }
    }
}
