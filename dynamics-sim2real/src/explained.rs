//! The figures' model: the diagnosis's whole explanation read back as
//! `--baseline` reads a report (the model's effects folded into the
//! model, the others undone on the data), evaluated along the measured
//! motion, as time series for the report's plots.

use nalgebra::SVector;

use crate::baseline::{undo, Entry};
use crate::data::Measured;
use crate::diagnose::traces::{data_series, DataTraces, Traces, TracesError};
use crate::diagnose::{Options, Prepared, Report};
use crate::effects::Calibrated;
use dynamics_runtime::Robot;

/// Series of `train` and `holdout` for `robot` with the whole explanation
/// of `report` (its `which.effects`): each effect read back as
/// `--baseline` reads it ([`crate::baseline::timed`]), the model's effects
/// folded into the model ([`Calibrated`]), the others (the sensors', the
/// motor sides, the effects limited to a window) undone on the data
/// ([`undo`]); the corrected residual is the measured effort, so
/// corrected, less the calibrated model's effort along the measured
/// motion. An effect the baseline cannot take back is left out of the
/// series and named in [`Traces::left_out`].
///
/// ```
/// use dynamics_sim2real::data::Measured;
/// use dynamics_sim2real::diagnose::{diagnose, Options};
/// use dynamics_sim2real::explained::traces;
/// use dynamics_runtime::Robot;
/// fn plot<R: Robot<3> + Clone + Send + Sync + 'static>(robot: &R, train: &Measured<3>, holdout: &Measured<3>) {
///     let report = diagnose(robot, train, holdout, &Options::default(), &|_, _| {}).expect("enough data");
///     let t = traces(robot, train, holdout, &report, &Options::default()).expect("traces");
///     assert_eq!(t.explained.len() + t.left_out.len(), report.which.effects.len());
/// }
/// ```
pub fn traces<R: Robot<N> + Clone + Send + Sync + 'static, const N: usize>(
    robot: &R,
    train: &Measured<N>,
    holdout: &Measured<N>,
    report: &Report,
    options: &Options,
) -> Result<Traces, TracesError> {
    let levels = options
        .noise
        .as_ref()
        .map(|n| n.per_joint::<N>())
        .transpose()?;
    let (mut effects, mut left_out) = (Vec::new(), Vec::new());
    for e in &report.which.effects {
        let place = e.joint.clone().or(e.point.clone()).unwrap_or_default();
        match crate::baseline::timed::<R, N>(&Entry::from(e)) {
            Ok(x) if Calibrated::timed(robot.clone(), vec![x]).is_ok() => effects.push(x),
            _ => left_out.push(format!("{} at {place}", e.kind.name())),
        }
    }
    let calibrated =
        Calibrated::timed(robot.clone(), effects.clone()).map_err(|e| TracesError::Entry {
            kind: "explanation".into(),
            place: String::new(),
            cause: e.to_string(),
        })?;
    let series = |m: &Measured<N>| -> Result<DataTraces, TracesError> {
        let p = Prepared::with_noise(robot, m, levels.as_ref());
        let fixed = undo(&calibrated, m).map_err(|e| TracesError::Entry {
            kind: "explanation".into(),
            place: String::new(),
            cause: e.to_string(),
        })?;
        let c = Prepared::with_noise(&calibrated, &fixed, levels.as_ref());
        // The corrected residual at the nominal series' times (an undone
        // delay shifts the record by whole samples; a time it does not
        // reach keeps the nominal residual).
        let (ca, cz) = c.sig.range;
        let after: Vec<SVector<f64, N>> = (0..p.sig.t.len())
            .map(|k| {
                let t = p.sig.t[k];
                let i = c.sig.t[ca..cz].partition_point(|&x| x < t - 1e-9) + ca;
                match c.sig.t.get(i) {
                    Some(&u) if i < cz && (u - t).abs() <= 1e-9 * (1.0 + t.abs()) => {
                        c.sig.residual[i]
                    }
                    _ => p.sig.residual[k],
                }
            })
            .collect();
        Ok(data_series::<R, N>(&p, Some(after)))
    };
    Ok(Traces {
        train: series(train)?,
        holdout: series(holdout)?,
        effect: None,
        window: None,
        explained: effects.into_iter().map(|(e, _)| e).collect(),
        left_out,
    })
}
