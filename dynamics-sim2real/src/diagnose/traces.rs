//! The time series behind a diagnosis, for plots: per joint the smoothed
//! measured effort, the nominal model's effort along the measured motion,
//! the effort with the explanation added, and the two residuals.
//!
//! The report's figures show the model with the whole explanation
//! ([`crate::explained::traces`]); [`traces`] gives the same with one
//! effect, the best single one, as supporting detail:
//!
//! The chosen effect is refitted on the training data from its entry in
//! the ranking (kind, place and grid value, [`Candidate::named`]) as
//! [`diagnose`](super::diagnose) fitted it: an effect that starts and
//! stops limited to the window found on the training data, then applied
//! unchanged to the held-out data (a windowed one in the window found
//! there).

use thiserror::Error;

use nalgebra::SVector;

use crate::data::Measured;
use crate::diagnose::candidates::{Candidate, Prepared};
use crate::diagnose::explain::report::Ranked;
use crate::diagnose::fit::{corrected, corrected_in, fit, fit_windowed, Windows};
use crate::diagnose::Options;
use crate::effects::{Effect, Window};
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
    /// The chosen effect as fitted on the training data (`None`: none
    /// chosen).
    pub effect: Option<Effect>,
    /// Its window on the training data, when it starts and stops.
    pub window: Option<Window>,
    /// The explanation's effects in the corrected series
    /// ([`crate::explained::traces`];
    /// empty for one chosen effect, [`traces`]).
    pub explained: Vec<Effect>,
    /// The explanation's effects left out of them, as "kind at place"
    /// (what the baseline cannot take back).
    pub left_out: Vec<String>,
}

/// Series of `train` and `holdout` for `robot`, with `chosen` (normally
/// `report.which.ranked[0]` when the verdict is not `none`) fitted on
/// `train` as the diagnosis with `options` fitted it (the same noise
/// floors, the same windows).
///
/// ```
/// use dynamics_sim2real::data::Measured;
/// use dynamics_sim2real::diagnose::{diagnose, traces::traces, Options};
/// use dynamics_runtime::Robot;
/// fn plot<R: Robot<3> + Clone + Send + Sync + 'static>(robot: &R, train: &Measured<3>, holdout: &Measured<3>) {
///     let report = diagnose(robot, train, holdout, &Options::default(), &|_, _| {}).expect("enough data");
///     let chosen = report.which.verdict.names_effect().then(|| &report.which.ranked[0]);
///     let t = traces(robot, train, holdout, chosen, &Options::default()).expect("a candidate of this robot");
///     assert_eq!(t.train.joints.len(), 3);
/// }
/// ```
pub fn traces<R: Robot<N> + Clone + Send + Sync + 'static, const N: usize>(
    robot: &R,
    train: &Measured<N>,
    holdout: &Measured<N>,
    chosen: Option<&Ranked>,
    options: &Options,
) -> Result<Traces, TracesError> {
    let candidate = chosen.map(candidate::<R, N>).transpose()?;
    let levels = options
        .noise
        .as_ref()
        .map(|n| n.per_joint::<N>())
        .transpose()?;
    let p = Prepared::with_noise(robot, train, levels.as_ref());
    let h = Prepared::with_noise(robot, holdout, levels.as_ref());
    let mut windows = Windows::new();
    let fitted = candidate.map(|c| {
        let f = fit::<R, N>(c, &p);
        match fit_windowed(&f, &p, options.nesting_margin) {
            Some((g, w)) => {
                windows.push((c, w));
                g
            }
            None => f,
        }
    });
    let series = |p: &Prepared<N>, after| data_series::<R, N>(p, after);
    // The training record's window is the one fitted there.
    let train = {
        let after = fitted.as_ref().map(|f| match windows.first() {
            Some(&(_, w)) => corrected_in(f, &p, Some(w)),
            None => f.corrected(&p),
        });
        series(&p, after)
    };
    let holdout = series(&h, fitted.as_ref().map(|f| corrected(f, &h, &windows)));
    Ok(Traces {
        train,
        holdout,
        effect: fitted.as_ref().and_then(|f| f.effect()),
        window: windows.first().map(|w| w.1),
        explained: Vec::new(),
        left_out: Vec::new(),
    })
}

/// The candidate a ranked entry stands for ([`Candidate::named`]).
fn candidate<R: Robot<N>, const N: usize>(r: &Ranked) -> Result<Candidate, TracesError> {
    let place = r.joint.clone().or(r.point.clone()).unwrap_or_default();
    let err = |cause: String| TracesError::Entry {
        kind: r.kind.name().to_string(),
        place: place.clone(),
        cause,
    };
    let joint = match r.joint.as_deref() {
        Some(name) => Some(R::joint_index(name).ok_or_else(|| {
            err(format!(
                "robot `{}` has no joint `{name}` (joints: {})",
                R::NAME,
                R::JOINT_NAMES.join(", ")
            ))
        })?),
        None => None,
    };
    let value = |name: &str| {
        r.parameters
            .iter()
            .find(|p| p.name == name)
            .map(|p| p.value)
    };
    Candidate::named(r.kind, joint, r.channel, &value).map_err(|e| err(e.to_string()))
}

/// One record's series: measured, nominal and corrected effort and the two
/// residuals per joint over the samples with a full smoothing window;
/// `after` the corrected residual per sample (`None`: none, the nominal).
pub(crate) fn data_series<R: Robot<N>, const N: usize>(
    p: &Prepared<N>,
    after: Option<Vec<SVector<f64, N>>>,
) -> DataTraces {
    let (a, z) = p.sig.range;
    let joints = (0..N)
        .map(|j| {
            let col =
                |v: &[SVector<f64, N>]| -> Vec<f64> { v[a..z].iter().map(|x| x[j]).collect() };
            let measured: Vec<f64> = (a..z).map(|k| p.sig.tau_at(k, j)).collect();
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
}
