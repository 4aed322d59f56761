//! A fitted candidate as the report's ranking shows it: its parameters
//! with their spreads (grid values and motor-side parameters included),
//! its share of the gap, its AICc and what it gains.

use crate::diagnose::candidates::Candidate;
use crate::diagnose::explain::report::{Parameter, Ranked};
use crate::diagnose::fit::Fit;
use crate::diagnose::select::breakaway_data_needed;
use dynamics_runtime::Robot;

/// The report's entry of a fit: parameters with their spreads, share of
/// the gap explained (training and held-out), AICc and its gain.
pub fn ranked_entry<R: Robot<N>, const N: usize>(
    f: &Fit,
    tip: &str,
    aicc0: f64,
    n: usize,
    share: f64,
    holdout_share: f64,
) -> Ranked {
    let c = f.candidate;
    let parameters = f
        .parameters()
        .into_iter()
        .map(|(name, value, std)| Parameter {
            name: name.into(),
            value,
            std,
            note: None,
        })
        .collect();
    let a = f.aicc(n);
    Ranked {
        channel: c.channel(),
        kind: c.kind(),
        joint: c.joint().map(|j| R::JOINT_NAMES[j].to_string()),
        point: matches!(
            c,
            Candidate::Payload | Candidate::PayloadCom(_) | Candidate::Environment(_)
        )
        .then(|| tip.to_string()),
        parameters,
        share,
        aicc: a,
        delta_aicc: aicc0 - a,
        holdout_share,
        data_needed: data_needed(f),
    }
}

/// A Stribeck fit's [`breakaway_data_needed`], from its Coulomb level and
/// breakaway excess; none where the data do not determine the Coulomb
/// level (its spread above its value): a tenth of it is then no yardstick.
fn data_needed(f: &Fit) -> Option<f64> {
    if !matches!(f.candidate, Candidate::Stribeck(..)) {
        return None;
    }
    let p = f.parameters();
    let get = |name: &str| p.iter().find(|x| x.0 == name).map(|x| (x.1, x.2));
    let ((fc, fc_std), (x, s)) = (get("fc")?, get("fs_minus_fc")?);
    if fc_std.is_nan() || fc_std > fc.abs() {
        return None;
    }
    breakaway_data_needed(fc, x, s)
}
