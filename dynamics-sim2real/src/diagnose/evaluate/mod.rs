//! Evaluation: how the model and the explanation do on data, mostly the
//! held-out record.
//!
//! - `determinacy.rs`: values the data do not determine or that are not
//!   physical;
//! - `confirm.rs`: the explanation confirmed on data it was not fitted on;
//!   what does not hold is not named;
//! - `holdout.rs`: the explanation's columns on the held-out record and
//!   the measures of a gap;
//! - `horizon.rs`: the short-horizon simulation error;
//! - `yardstick.rs`: the error the same procedure shows for an exact model
//!   with noisy sensors;
//! - `gap_windows.rs`: where in time the residual concentrates, by motion
//!   phase;
//! - `shrink.rs`: how far the gap shrinks on the held-out record once the
//!   explanation's effects are added.

mod calibration;
mod confirm;
mod determinacy;
mod gap_windows;
mod holdout;
mod horizon;
mod shrink;
mod yardstick;

pub use calibration::FrictionSpread;
pub use confirm::{Confidence, Confirmed, Suggestion, Unconfirmed, PRACTICAL_SHARE};
pub(crate) use determinacy::held_at_zero;
pub use determinacy::why_not;
pub use gap_windows::GapWindow;
pub use holdout::{fraction, limit_to_windows, Holdout};
pub use shrink::ShrinkFigures;

use nalgebra::{DVector, SVector};
use rayon::prelude::*;

use crate::diagnose::candidates::{regressor_columns, Records};
use crate::diagnose::select::{effects, Selection};
use crate::diagnose::Options;
use crate::Warning;
use dynamics_runtime::Robot;

/// What the evaluation found.
pub struct Evaluation<'a, const N: usize> {
    /// The nominal model's short-horizon prediction error per joint on the
    /// training record (`None`: the simulation could not be made).
    pub prediction: Option<SVector<f64, N>>,
    /// What the same procedure shows for an exact model (`yardstick.rs`).
    pub prediction_noise: SVector<f64, N>,
    /// Per joint, where in time the training residual concentrates.
    pub gap_windows: Vec<Vec<GapWindow>>,
    /// Warnings of the training record's evaluation.
    pub training_warnings: Vec<Warning>,
    /// The explanation once confirmed on the held-out record
    /// (`confirm.rs`); everything below is of it.
    pub confirmed: Confirmed,
    /// The explanation on the held-out record.
    pub hold: Holdout<'a, N>,
    /// The plain RMS of the held-out effort residual, as a fraction
    /// removed by the explanation.
    pub rms_fraction: f64,
    /// How far the gap shrinks on the held-out record.
    pub shrink: ShrinkFigures<N>,
    /// Warnings of the held-out record's evaluation.
    pub held_out_warnings: Vec<Warning>,
    /// The spread of each joint's friction on the training record, in the
    /// confirmed explanation's fit (`calibration.rs`).
    pub friction_spread: FrictionSpread<N>,
}

/// The nominal model on the training record of `records` (where the gap
/// is), and the explanation of `selection` on the held-out record.
pub fn evaluate<'a, R: Robot<N> + Clone + Sync, const N: usize>(
    robot: &'a R,
    records: &'a Records<N>,
    selection: &Selection,
    options: &Options,
) -> Evaluation<'a, N> {
    let hold_links = selection.held_links.held();
    let (p, h) = (&records.p, &records.h);
    let mut training_warnings = Vec::new();
    let prediction = horizon::prediction_error(robot, p, &[])
        .map_err(|reason| {
            training_warnings.push(Warning::SimulationNotMade {
                model: "the nominal model (training data)".into(),
                reason,
            })
        })
        .ok();
    let prediction_noise = yardstick::prediction_floor(robot, &records.train, p);
    let gap_windows = (0..N)
        .into_par_iter()
        .map(|j| gap_windows::gap_windows(p, &p.sig.residual, j, 3.0, 5))
        .collect();

    let pool = &selection.pool;
    let hlinks = if selection.with_links {
        regressor_columns(robot, h).unwrap_or_default()
    } else {
        vec![]
    };
    let mut confirmed = confirm::confirm::<R, N>(
        robot,
        p,
        h,
        &hlinks,
        pool,
        &selection.explanation,
        &records.excitation,
        &selection.nominal,
        selection.carrier.as_ref(),
        hold_links,
    );
    if let Some(calibration) = &options.calibration {
        calibration::keep_changes(
            &mut confirmed,
            pool,
            calibration,
            options.add_margin,
            |set| {
                if hold_links {
                    pool.solve_physical(set, &selection.nominal)
                } else {
                    pool.solve(set)
                }
            },
        );
    }
    let friction_spread = calibration::friction_spread(pool, &confirmed.explanation);
    let e = &confirmed.explanation;
    let mut hold = Holdout::new(robot, h, &hlinks, pool, e);
    limit_to_windows(&mut hold, h, pool, e);
    let all: Vec<usize> = (0..e.set.len()).collect();
    let r = hold.residual(&all, &e.sol.theta);
    let rms_fraction = fraction(hold.plain(&hold.residual(&[], &[])), hold.plain(&r));
    let after: Option<Vec<SVector<f64, N>>> = (!e.set.is_empty()).then(|| unwhitened(h, &r));
    let mut held_out_warnings = Vec::new();
    let shrink = shrink::shrink(
        robot,
        &records.holdout,
        h,
        after,
        &effects(pool, e, &p.basis.friction),
        &mut held_out_warnings,
    );
    Evaluation {
        prediction,
        prediction_noise,
        gap_windows,
        training_warnings,
        confirmed,
        hold,
        rms_fraction,
        shrink,
        held_out_warnings,
        friction_spread,
    }
}

/// A whitened residual over the rows of `h` back in effort units, one
/// entry a row.
fn unwhitened<const N: usize>(
    h: &crate::diagnose::candidates::Prepared<N>,
    r: &DVector<f64>,
) -> Vec<SVector<f64, N>> {
    (0..h.rows.len())
        .map(|i| SVector::from_fn(|j, _| r[i * N + j] * h.sig.floor[j]))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnose::candidates::Prepared;
    use crate::synth::{synthesize, SynthOptions};
    use crate::test_robots::Arm2;

    /// A whitened residual back in effort units at the rows gives, per
    /// joint, the RMS over the rows of the same residual put back at every
    /// sample (zero off the rows), to the bit.
    #[test]
    fn the_rms_at_the_rows_is_the_whole_records() {
        let robot = Arm2::default();
        let opts = SynthOptions {
            duration: 2.0,
            seed: 5,
            ..Default::default()
        };
        let m = synthesize(&robot, &[], &opts).expect("a generated record");
        let h = Prepared::new(&robot, &m);
        assert!(h.rows.len() > 20);
        let r = DVector::from_fn(h.n(), |i, _| ((i * 7919) % 1013) as f64 * 1e-2 - 5.0);
        let rows = unwhitened(&h, &r);
        assert_eq!(rows.len(), h.rows.len());
        let mut whole = vec![SVector::<f64, 2>::zeros(); h.sig.t.len()];
        for (i, &k) in h.rows.iter().enumerate() {
            for j in 0..2 {
                whole[k][j] = r[i * 2 + j] * h.sig.floor[j];
            }
        }
        for j in 0..2 {
            let (a, b) = (h.rms_rows(&rows, j), h.rms(&whole, j));
            assert!(a > 0.0);
            assert_eq!(a.to_bits(), b.to_bits(), "joint {j}");
        }
    }
}
