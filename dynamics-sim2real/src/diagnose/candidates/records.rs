//! The two records of a diagnosis made ready: prepared as every log is
//! (`data::prepare`), checked long enough, each with its signals, noise
//! floor and column cache ([`Prepared`]), and what the training record can
//! show ([`Excitation`]).

use std::borrow::Cow;

use super::prepared::Prepared;
use super::visibility::{effort_sign, excitation, Excitation};
use crate::data::{prepare, DataError, Measured};
use crate::diagnose::{DiagnoseError, Options};
use crate::Warning;
use dynamics_runtime::Robot;

/// The training and held-out records, prepared.
#[derive(Debug, Clone)]
pub struct Records<'a, const N: usize> {
    /// The training record as recorded (prepared).
    pub train: Cow<'a, Measured<N>>,
    /// The held-out record as recorded (prepared).
    pub holdout: Cow<'a, Measured<N>>,
    /// The training record made ready for fitting.
    pub p: Prepared<N>,
    /// The held-out record made ready for fitting.
    pub h: Prepared<N>,
    /// What the training record can show.
    pub excitation: Excitation,
    /// What the records' preparation and checks found, in that order.
    pub warnings: Vec<Warning>,
}

/// Fewest samples a record must have.
const NEED: usize = 200;

fn check<const N: usize>(m: &Measured<N>, which: &'static str) -> Result<(), DiagnoseError> {
    if m.len() < NEED {
        return Err(DiagnoseError::TooShort {
            which,
            samples: m.len(),
            duration: m.duration(),
            need: NEED,
        });
    }
    Ok(())
}

/// `m` prepared (`data::prepare`) unless it is already.
fn prepared<'a, const N: usize>(
    m: &'a Measured<N>,
    which: &str,
) -> Result<Cow<'a, Measured<N>>, DataError> {
    Ok(if m.prepared {
        Cow::Borrowed(m)
    } else {
        Cow::Owned(prepare(m, which)?)
    })
}

impl<'a, const N: usize> Records<'a, N> {
    /// Both records prepared for `robot` (data read from a file come
    /// prepared already), at the sensor noise `options` states (else
    /// estimated from each record); refused when a record is too short,
    /// an effort column's sign is flipped, or nothing moves.
    pub fn new<R: Robot<N> + Clone + Send + Sync + 'static>(
        robot: &R,
        train: &'a Measured<N>,
        holdout: &'a Measured<N>,
        options: &Options,
    ) -> Result<Self, DiagnoseError> {
        let train = prepared(train, "training")?;
        let holdout = prepared(holdout, "held-out")?;
        check(&train, "training")?;
        check(&holdout, "held-out")?;
        let levels = options
            .noise
            .as_ref()
            .map(|n| n.per_joint::<N>())
            .transpose()?;
        let (p, h) = rayon::join(
            || Prepared::chunked(robot, &train, levels.as_ref(), options.chunk),
            || Prepared::chunked(robot, &holdout, levels.as_ref(), options.chunk),
        );
        let mut warnings: Vec<Warning> = train.warnings.clone();
        warnings.extend(holdout.warnings.iter().cloned());
        effort_sign(&p, &R::JOINT_NAMES, "training")?;
        effort_sign(&h, &R::JOINT_NAMES, "held-out")?;
        let excitation = excitation(&p, &R::JOINT_NAMES, &mut warnings)?;
        Ok(Records {
            train,
            holdout,
            p,
            h,
            excitation,
            warnings,
        })
    }
}
