//! The diagnosis report (serialised as the JSON documented in the README).

use serde::Serialize;

use crate::diagnose::evaluate::held_at_zero;
use crate::effects::EffectKind;
use crate::Warning;

pub use crate::diagnose::candidates::Channel;
pub use crate::diagnose::evaluate::GapWindow;

/// The whole report.
#[derive(Debug, Clone, Serialize)]
pub struct Report {
    /// Robot name.
    pub robot: String,
    /// Samples in the training and held-out data.
    pub samples: [usize; 2],
    /// Where the model and the data disagree.
    #[serde(rename = "where")]
    pub where_: Where,
    /// Which effect explains it.
    pub which: Which,
    /// How far the gap shrinks on held-out data.
    pub shrink: Shrink,
    /// What the preparation repaired and what the data cannot show
    /// (training data first).
    pub warnings: Vec<Warning>,
}

/// Where: per joint.
#[derive(Debug, Clone, Serialize)]
pub struct Where {
    /// Per joint.
    pub joints: Vec<JointGap>,
}

/// The gap at one joint (training data, nominal model).
#[derive(Debug, Clone, Serialize)]
pub struct JointGap {
    /// Joint name.
    pub joint: String,
    /// RMS of the smoothed torque residual.
    pub torque_rms: f64,
    /// Its noise floor.
    pub torque_noise: f64,
    /// `torque_rms / torque_noise`.
    pub torque_ratio: f64,
    /// RMS short-horizon position prediction error (`None`: the
    /// simulation could not be made; a warning says why).
    pub prediction_rms: Option<f64>,
    /// Its yardstick: the same error for an exact model (`yardstick.rs`).
    pub prediction_noise: f64,
    /// `prediction_rms / prediction_noise`.
    pub prediction_ratio: Option<f64>,
    /// Windows where the residual concentrates.
    pub windows: Vec<GapWindow>,
}

/// Which: ranking, verdict and the compound explanation.
#[derive(Debug, Clone, Serialize)]
pub struct Which {
    /// Candidates, best first.
    pub ranked: Vec<Ranked>,
    /// The verdict.
    pub verdict: Verdict,
    /// The effects that together explain the gap, in the order of their gains
    /// (empty when the model explains the data within noise or nothing
    /// explains the gap).
    pub effects: Vec<Explained>,
    /// What the selection chose on the training record that did not hold
    /// (not named, with the reason).
    pub suggested: Vec<Suggested>,
    /// Each joint's friction in the calibrated model: the nominal model's
    /// own with the explanation's corrections.
    pub friction: Vec<JointFriction>,
}

/// A joint's friction in the calibrated model.
#[derive(Debug, Clone, Serialize)]
pub struct JointFriction {
    /// Joint.
    pub joint: String,
    /// The nominal model's Coulomb level (N m or N).
    pub coulomb_nominal: f64,
    /// The Coulomb level with the explanation's corrections (>= 0).
    pub coulomb: f64,
    /// The level as the joint starts to move (>= `coulomb`): the Coulomb
    /// level plus a Stribeck friction's excess `fs - fc`, which fades over
    /// its Stribeck velocity.
    pub breakaway: f64,
    /// The nominal model's viscous coefficient (N m s/rad or N s/m).
    pub viscous_nominal: f64,
    /// The viscous coefficient with the explanation's corrections (>= 0).
    pub viscous: f64,
    /// Whether the explanation corrects the friction at this joint (else
    /// the nominal values stand).
    pub corrected: bool,
    /// The standard deviation of the Coulomb level on these data: the
    /// fit's where corrected, else the one a correction would have had
    /// (what these data could tell; a later diagnosis with this report as
    /// its baseline names a change only beyond it).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub coulomb_std: Option<f64>,
    /// The same for the viscous coefficient.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub viscous_std: Option<f64>,
}

/// One effect of the compound explanation.
#[derive(Debug, Clone, Serialize)]
pub struct Explained {
    /// Effect kind.
    pub kind: EffectKind,
    /// Joint, for joint effects.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub joint: Option<String>,
    /// Point, for tip effects.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub point: Option<String>,
    /// Parameters from the joint fit of the whole set, with their
    /// standard deviations.
    pub parameters: Vec<Parameter>,
    /// The effect in words, where numbers alone say little (a link's
    /// inertial correction).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub description: Option<String>,
    /// Share of the training gap above noise it explains, in the order
    /// chosen (the shares add up to the set's).
    pub share: f64,
    /// How much the held-out gap (whitened squared residual above noise)
    /// grows, as a share of that gap, when this effect alone is left out of
    /// the set (the others refitted on the training data).
    pub holdout_contribution: f64,
    /// When the effect is limited in time.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub window: Option<EffectWindow>,
    /// For `time_delay`: the late channel (see [`Ranked::channel`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub channel: Option<Channel>,
    /// How it was confirmed on data it was not fitted on.
    pub confidence: Confidence,
    /// An effect the data cannot tell from this one within the set (the
    /// two are one ambiguous pair).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ambiguous_with: Option<Rival>,
}

/// How an effect of the explanation was confirmed: chosen on the training
/// record (information criterion and block cross-validation over its time
/// segments), then held on the held-out record.
#[derive(Debug, Clone, Serialize)]
pub struct Confidence {
    /// `confirmed`: leaving it out raises the held-out residual by more
    /// than sensor noise could.
    pub status: &'static str,
    /// What the held-out residual gains when the effect is left out (the
    /// others refitted on the training record), as a share of the held-out
    /// gap above noise.
    pub held_out_gain: f64,
    /// The share noise alone could give at `level` (the chi-square quantile
    /// at its parameter count): `held_out_gain` exceeds it.
    pub chance: f64,
    /// The effect's effort on the held-out record as a share of the noise
    /// floor (what the sensors' noise leaves in the smoothed residual; RMS
    /// over the samples, summed over the joints).
    pub effort_to_noise: f64,
    /// The largest share of one joint's held-out gap above noise that the
    /// effect removes. An effect named has `effort_to_noise` at least 1 or
    /// this at least 1e-4.
    pub joint_gap_share: f64,
    /// The chance level of the test (0.001 shared by the effects tested).
    pub level: f64,
}

/// An effect the selection chose that the data do not confirm: not named,
/// shown with the reason.
#[derive(Debug, Clone, Serialize)]
pub struct Suggested {
    /// Effect kind.
    pub kind: EffectKind,
    /// Joint, for joint effects.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub joint: Option<String>,
    /// Point or link, for effects at a point.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub point: Option<String>,
    /// Its parameters as fitted in the set it was chosen in (none for a
    /// link correction).
    pub parameters: Vec<Parameter>,
    /// For `time_delay`: the late channel (see [`Ranked::channel`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub channel: Option<Channel>,
    /// `suggested`: not confirmed.
    pub status: &'static str,
    /// Why it is not named.
    pub reason: String,
}

/// The time span of a time-limited effect.
#[derive(Debug, Clone, Serialize)]
pub struct EffectWindow {
    /// Start, s.
    pub start: f64,
    /// End, s.
    pub end: f64,
}

/// The other half of an ambiguous pair.
#[derive(Debug, Clone, Serialize)]
pub struct Rival {
    /// Effect kind.
    pub kind: EffectKind,
    /// Joint, for joint effects.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub joint: Option<String>,
    /// Point, for tip effects.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub point: Option<String>,
    /// Why no motion separates the two, when none does (their columns
    /// share a direction once the base parameters are regrouped); absent
    /// when another motion could.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub inseparable: Option<String>,
}

/// The held-out gap left after the first few effects of the explanation.
#[derive(Debug, Clone, Serialize)]
pub struct ShrinkStep {
    /// Effects in the model (the first `effects` of the explanation).
    pub effects: usize,
    /// The effect this step added (`kind at place`).
    pub added: String,
    /// Torque gap above noise left (root of the sum over joints of the
    /// squared residual RMS above the floor, in floor units).
    pub torque_gap: f64,
    /// 1 - gap left / gap of the nominal model.
    pub torque_fraction: f64,
    /// 1 - RMS of the raw effort residual over all joints (noise included)
    /// / the nominal model's.
    pub rms_fraction: f64,
}

/// A fitted parameter.
#[derive(Debug, Clone)]
pub struct Parameter {
    /// Name.
    pub name: String,
    /// Value (SI); `null` in JSON where [`Parameter::note`] says why it
    /// cannot be acted on, except a value held at zero by its sign
    /// constraint: zero, with the spread it has if freed (how firmly the
    /// data hold it there).
    pub value: f64,
    /// Standard deviation (grid-searched parameters: half the grid step);
    /// infinite (`null` in JSON) where the data do not determine it.
    pub std: f64,
    /// Why the value is not reported as a number: the data do not
    /// determine it, or it lies outside what its kind can physically be
    /// (`determinacy.rs`).
    pub note: Option<String>,
}

impl Serialize for Parameter {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeStruct;
        let shown = self.note.is_none() || held_at_zero(&self.name, self.value);
        let mut st = s.serialize_struct("Parameter", 3 + usize::from(!shown))?;
        st.serialize_field("name", &self.name)?;
        st.serialize_field("value", &shown.then_some(self.value))?;
        st.serialize_field("std", &shown.then_some(self.std))?;
        if let Some(note) = &self.note {
            st.serialize_field("note", note)?;
        }
        st.end()
    }
}

/// One ranked candidate.
#[derive(Debug, Clone, Serialize)]
pub struct Ranked {
    /// Effect kind.
    pub kind: EffectKind,
    /// Joint, for joint effects.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub joint: Option<String>,
    /// Point, for tip effects.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub point: Option<String>,
    /// Fitted parameters.
    pub parameters: Vec<Parameter>,
    /// Share of the gap above noise explained on the training data.
    pub share: f64,
    /// Corrected Akaike information criterion.
    pub aicc: f64,
    /// AICc of the nominal model minus this one's (larger is better).
    pub delta_aicc: f64,
    /// Share of the held-out gap above noise it explains.
    pub holdout_share: f64,
    /// For `time_delay`: the late channel (`all`: positions and
    /// velocities late together against the effort; `positions`: the
    /// position stream late against velocity and effort; `effort`: the
    /// effort stream late against position and velocity).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub channel: Option<Channel>,
    /// For `stribeck_friction`: how many times as much data of this kind
    /// would settle its breakaway excess over the Coulomb level, present
    /// or absent (1 where these data settle it; see
    /// [`breakaway_data_needed`](crate::diagnose::breakaway_data_needed)).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub data_needed: Option<f64>,
}

/// The verdict.
#[derive(Debug, Clone, Serialize)]
pub struct Verdict {
    /// Effect kind (`none` when the model explains the data within noise,
    /// `unexplained` when it does not and no candidate explains the gap).
    pub kind: VerdictKind,
    /// Joint name, for joint effects.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub joint: Option<String>,
    /// Point, for tip effects.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub point: Option<String>,
    /// For `time_delay`: the late channel (see [`Ranked::channel`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub channel: Option<Channel>,
    /// `clear`, `ambiguous`, `within_noise` or `unexplained`.
    pub status: Status,
    /// The rival that these data cannot tell apart, when ambiguous.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rival: Option<Box<Ranked>>,
    /// A motion that would separate the two, when ambiguous and some
    /// motion does.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub separating_motion: Option<String>,
    /// Why no motion separates the two, when none does (in place of
    /// `separating_motion`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub inseparable: Option<String>,
}

impl Verdict {
    /// Whether the verdict names an effect (the first of the ranking):
    /// false for `none` and `unexplained`.
    ///
    /// ```
    /// use dynamics_sim2real::diagnose::{Status, Verdict, VerdictKind};
    /// let v = Verdict { kind: VerdictKind::Unexplained, joint: None, point: None, channel: None,
    ///     status: Status::Unexplained, rival: None, separating_motion: None,
    ///     inseparable: None };
    /// assert!(!v.names_effect());
    /// ```
    pub fn names_effect(&self) -> bool {
        self.effect().is_some()
    }

    /// The effect the verdict names, if any.
    ///
    /// ```
    /// use dynamics_sim2real::diagnose::VerdictKind;
    /// use dynamics_sim2real::effects::EffectKind;
    /// assert_eq!(VerdictKind::Effect(EffectKind::Backlash).effect(), Some(EffectKind::Backlash));
    /// assert_eq!(VerdictKind::Effect(EffectKind::None).effect(), None);
    /// ```
    pub fn effect(&self) -> Option<EffectKind> {
        self.kind.effect()
    }
}

/// What the verdict names: an effect of the vocabulary (`none` when the
/// model explains the data within noise), or `unexplained`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VerdictKind {
    /// An effect kind, or `none`.
    Effect(EffectKind),
    /// The gap is real and no candidate explains it.
    Unexplained,
}

impl VerdictKind {
    /// The effect named, if any (`none` and `unexplained` name none).
    pub fn effect(self) -> Option<EffectKind> {
        match self {
            VerdictKind::Effect(EffectKind::None) | VerdictKind::Unexplained => None,
            VerdictKind::Effect(k) => Some(k),
        }
    }

    /// The name the report writes.
    pub fn name(self) -> &'static str {
        match self {
            VerdictKind::Effect(k) => k.name(),
            VerdictKind::Unexplained => "unexplained",
        }
    }
}

impl Serialize for VerdictKind {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.name())
    }
}

impl std::fmt::Display for VerdictKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.pad(self.name())
    }
}

/// How sure the verdict is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Status {
    /// The top candidate wins clearly.
    Clear,
    /// A rival is close behind: these data cannot tell them apart.
    Ambiguous,
    /// The model explains the data within noise.
    WithinNoise,
    /// The gap is real and no candidate explains it.
    Unexplained,
}

impl Status {
    /// The name the report writes.
    pub fn name(self) -> &'static str {
        match self {
            Status::Clear => "clear",
            Status::Ambiguous => "ambiguous",
            Status::WithinNoise => "within_noise",
            Status::Unexplained => "unexplained",
        }
    }
}

impl std::fmt::Display for Status {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.pad(self.name())
    }
}

/// Shrink on held-out data.
#[derive(Debug, Clone, Serialize)]
pub struct Shrink {
    /// Per joint.
    pub joints: Vec<JointShrink>,
    /// 1 - gap after / gap before, torque residual above noise.
    pub torque_fraction: f64,
    /// 1 - error after / error before, short-horizon simulation (`None`,
    /// `null` in JSON: a simulation could not be made; a warning says why).
    pub simulation_fraction: Option<f64>,
    /// The overall figure (the torque fraction).
    pub fraction: f64,
    /// 1 - RMS of the raw effort residual over all joints after / before
    /// (noise included): the plain figure other tools report.
    pub rms_fraction: f64,
    /// The held-out gap of the nominal model (`effects` 0) and the gap
    /// left after each added effect of the explanation (empty when nothing
    /// was added).
    pub steps: Vec<ShrinkStep>,
}

/// Before and after at one joint (held-out data).
#[derive(Debug, Clone, Serialize)]
pub struct JointShrink {
    /// Joint name.
    pub joint: String,
    /// Torque residual RMS before.
    pub torque_before: f64,
    /// After.
    pub torque_after: f64,
    /// Short-horizon position error RMS before (`None`: the simulation
    /// could not be made; a warning says why).
    pub simulation_before: Option<f64>,
    /// After (`None` likewise).
    pub simulation_after: Option<f64>,
}

/// A one-parameter joint effect of the explanation, for unit tests.
#[cfg(test)]
pub(crate) fn test_entry(
    kind: crate::effects::EffectKind,
    joint: &str,
    name: &str,
    value: f64,
) -> Explained {
    Explained {
        kind,
        joint: Some(joint.to_string()),
        point: None,
        description: None,
        parameters: vec![Parameter {
            name: name.to_string(),
            value,
            std: 0.01,
            note: None,
        }],
        share: 0.1,
        holdout_contribution: 0.1,
        window: None,
        channel: None,
        confidence: Confidence {
            status: "confirmed",
            held_out_gain: 0.1,
            chance: 0.0,
            effort_to_noise: 3.0,
            joint_gap_share: 0.1,
            level: 1e-3,
        },
        ambiguous_with: None,
    }
}
