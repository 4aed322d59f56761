//! The time series behind a diagnosis, for plots: per joint the smoothed
//! measured effort, the nominal model's effort along the measured motion,
//! the effort with the chosen effect added, and the two residuals.
//!
//! The chosen effect is refitted on the training data from its entry in
//! the ranking (kind, place and grid parameter), which reproduces the fit
//! [`diagnose`](super::diagnose) made, and then applied unchanged to the
//! held-out data.

use crate::effects::SIGN_SMOOTHING;
use thiserror::Error;

use crate::data::Measured;
use crate::diagnose::candidates::Prepared;
use crate::diagnose::candidates::{Candidate, Channel};
use crate::diagnose::explain::report::Ranked;
use crate::diagnose::fit::fit;
use crate::diagnose::signals::SensorNoise;
use crate::effects::EffectKind;
use dynamics_runtime::{JointKind, Robot};

/// Why traces could not be made.
#[derive(Debug, Error)]
pub enum TracesError {
    /// The ranked entry names something this robot does not have.
    #[error("ranked entry `{kind}` at `{place}`: {cause}")]
    Entry {
        /// Effect kind.
        kind: String,
        /// Joint or point.
        place: String,
        /// What is wrong.
        cause: String,
    },
    /// The stated sensor noise cannot be used.
    #[error(transparent)]
    Noise(#[from] crate::diagnose::DiagnoseError),
}

/// One data set's series (samples with a full smoothing window only).
#[derive(Debug, Clone, PartialEq)]
pub struct DataTraces {
    /// Times, s.
    pub t: Vec<f64>,
    /// Per joint.
    pub joints: Vec<JointTraces>,
}

/// One joint's series.
#[derive(Debug, Clone, PartialEq)]
pub struct JointTraces {
    /// Joint name.
    pub joint: String,
    /// `N·m` for a revolute joint, `N` for a prismatic one.
    pub unit: &'static str,
    /// Noise floor of the smoothed residual.
    pub floor: f64,
    /// Measured effort, smoothed.
    pub measured: Vec<f64>,
    /// The nominal model's effort along the (smoothed) measured motion.
    pub nominal: Vec<f64>,
    /// The same with the chosen effect added (equal to `nominal` without one).
    pub corrected: Vec<f64>,
    /// `measured - nominal`.
    pub residual: Vec<f64>,
    /// `measured - corrected`.
    pub residual_after: Vec<f64>,
}

/// Series of the training and the held-out data.
#[derive(Debug, Clone, PartialEq)]
pub struct Traces {
    /// Training data.
    pub train: DataTraces,
    /// Held-out data.
    pub holdout: DataTraces,
}

/// Series of `train` and `holdout` for `robot`, with `chosen` (normally
/// `report.which.ranked[0]` when the verdict is not `none`) fitted on
/// `train`; `noise`: the sensor noise the diagnosis was told
/// (`Options::noise`), for the same noise floors.
///
/// ```
/// use dynamics_sim2real::data::Measured;
/// use dynamics_sim2real::diagnose::{diagnose, traces::traces, Options};
/// use dynamics_runtime::Robot;
/// fn plot<R: Robot<3> + Clone + Sync>(robot: &R, train: &Measured<3>, holdout: &Measured<3>) {
///     let report = diagnose(robot, train, holdout, &Options::default(), &|_, _| {}).expect("enough data");
///     let chosen = report.which.verdict.names_effect().then(|| &report.which.ranked[0]);
///     let t = traces(robot, train, holdout, chosen, None).expect("a candidate of this robot");
///     assert_eq!(t.train.joints.len(), 3);
/// }
/// ```
pub fn traces<R: Robot<N> + Clone, const N: usize>(
    robot: &R,
    train: &Measured<N>,
    holdout: &Measured<N>,
    chosen: Option<&Ranked>,
    noise: Option<&SensorNoise>,
) -> Result<Traces, TracesError> {
    let candidate = chosen.map(candidate::<R, N>).transpose()?;
    let levels = noise.map(SensorNoise::per_joint::<N>).transpose()?;
    let p = Prepared::with_noise(robot, train, levels.as_ref());
    let h = Prepared::with_noise(robot, holdout, levels.as_ref());
    let fitted = candidate.map(|c| fit::<R, N>(c, &p));
    let series = |p: &Prepared<N>| -> DataTraces {
        let after = fitted.as_ref().map(|f| f.corrected(p));
        let (a, z) = p.sig.range;
        let joints = (0..N)
            .map(|j| {
                let col = |v: &[nalgebra::SVector<f64, N>]| -> Vec<f64> {
                    v[a..z].iter().map(|x| x[j]).collect()
                };
                let measured = col(&p.sig.tau);
                let nominal = col(&p.sig.model);
                let residual = col(&p.sig.residual);
                let residual_after = after.as_deref().map(col).unwrap_or(residual.clone());
                let corrected = measured
                    .iter()
                    .zip(&residual_after)
                    .map(|(m, r)| m - r)
                    .collect();
                JointTraces {
                    joint: R::JOINT_NAMES[j].to_string(),
                    unit: match R::JOINT_KINDS[j] {
                        JointKind::Prismatic => "N",
                        _ => "N·m",
                    },
                    floor: p.sig.floor[j],
                    measured,
                    nominal,
                    corrected,
                    residual,
                    residual_after,
                }
            })
            .collect();
        DataTraces {
            t: p.sig.t[a..z].to_vec(),
            joints,
        }
    };
    Ok(Traces {
        train: series(&p),
        holdout: series(&h),
    })
}

/// The candidate a ranked entry stands for.
fn candidate<R: Robot<N>, const N: usize>(r: &Ranked) -> Result<Candidate, TracesError> {
    let place = r.joint.clone().or(r.point.clone()).unwrap_or_default();
    let err = |cause: String| TracesError::Entry {
        kind: r.kind.name().to_string(),
        place: place.clone(),
        cause,
    };
    let kind = r.kind;
    let joint = || -> Result<usize, TracesError> {
        let name = r
            .joint
            .as_deref()
            .ok_or_else(|| err("no joint named".into()))?;
        R::joint_index(name).ok_or_else(|| {
            err(format!(
                "robot `{}` has no joint `{name}` (joints: {})",
                R::NAME,
                R::JOINT_NAMES.join(", ")
            ))
        })
    };
    let parameter = |name: &str| -> Result<f64, TracesError> {
        r.parameters
            .iter()
            .find(|p| p.name == name)
            .map(|p| p.value)
            .ok_or_else(|| err(format!("no parameter `{name}`")))
    };
    Ok(match kind {
        EffectKind::CoulombFriction => Candidate::Coulomb(joint()?, SIGN_SMOOTHING),
        EffectKind::ViscousFriction => Candidate::Viscous(joint()?),
        EffectKind::StribeckFriction => Candidate::Stribeck(joint()?, parameter("vs")?),
        EffectKind::Armature => Candidate::Armature(joint()?),
        EffectKind::PayloadMass => Candidate::Payload,
        EffectKind::EnvironmentResistance => Candidate::Environment(parameter("alpha")?),
        EffectKind::EncoderOffset => Candidate::EncoderOffset(joint()?),
        EffectKind::TimeDelay => match r.channel {
            Some(Channel::Positions) => Candidate::LatePositions,
            Some(Channel::Effort) => Candidate::LateEffort(parameter("delay")?),
            _ => Candidate::TimeDelay,
        },
        EffectKind::JointElasticity => Candidate::Elasticity(joint()?),
        EffectKind::Backlash => Candidate::Backlash(joint()?),
        EffectKind::EffortScale => Candidate::EffortScale(joint()?),
        EffectKind::EffortOffset => Candidate::EffortOffset(joint()?),
        EffectKind::JointSpring => Candidate::Spring(joint()?),
        EffectKind::InertialParameters => {
            return Err(err(
                "`inertial_parameters` has no single-effect candidate".into()
            ))
        }
        EffectKind::None => return Err(err("`none` is not an effect to fit".into())),
    })
}
