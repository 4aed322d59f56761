//! The two records of a diagnosis made ready: prepared as every log is
//! (`data::prepare`), checked long enough, each with its signals, noise
//! floor and column cache ([`Prepared`]), and what the training record can
//! show ([`Excitation`]).

use std::ops::Deref;
use std::sync::Arc;

use super::prepared::Prepared;
use super::visibility::{effort_sign, excitation, Excitation};
use crate::data::{prepare, DataError, Measured};
use crate::diagnose::{DiagnoseError, Options};
use crate::Warning;
use dynamics_runtime::Robot;
use nalgebra::SVector;

/// A record as the caller gave it: lent (the signals then copy what they
/// read of it), or handed over (shared with the signals, not copied).
#[derive(Debug, Clone)]
pub enum Record<'a, const N: usize> {
    /// Lent by the caller.
    Lent(&'a Measured<N>),
    /// Handed over, shared.
    Shared(Arc<Measured<N>>),
}

impl<const N: usize> Deref for Record<'_, N> {
    type Target = Measured<N>;

    fn deref(&self) -> &Measured<N> {
        match self {
            Record::Lent(m) => m,
            Record::Shared(m) => m,
        }
    }
}

/// The training and held-out records, prepared.
#[derive(Debug, Clone)]
pub struct Records<'a, const N: usize> {
    /// The training record as recorded (prepared).
    pub train: Record<'a, N>,
    /// The held-out record as recorded (prepared).
    pub holdout: Record<'a, N>,
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

/// `m` prepared (`data::prepare`) unless it is already (a record
/// prepared here is the diagnosis's own, shared with its signals).
fn prepared<'a, const N: usize>(m: Record<'a, N>, which: &str) -> Result<Record<'a, N>, DataError> {
    Ok(if m.prepared {
        m
    } else {
        Record::Shared(Arc::new(prepare(&m, which)?))
    })
}

/// `m` made ready for fitting, its signals sharing it when handed over.
fn ready<R: Robot<N> + Clone + Send + Sync + 'static, const N: usize>(
    robot: &R,
    m: &Record<'_, N>,
    levels: Option<&[SVector<f64, N>; 3]>,
    chunk: usize,
) -> Prepared<N> {
    match m {
        Record::Lent(m) => Prepared::chunked(robot, m, levels, chunk),
        Record::Shared(m) => Prepared::shared(robot, m, levels, chunk),
    }
}

impl<'a, const N: usize> Records<'a, N> {
    /// Both records prepared for `robot` (data read from a file come
    /// prepared already), at the sensor noise `options` states (else
    /// estimated from each record); refused when a record is too short,
    /// an effort column's sign is flipped, or nothing moves.
    pub fn new<R: Robot<N> + Clone + Send + Sync + 'static>(
        robot: &R,
        train: Record<'a, N>,
        holdout: Record<'a, N>,
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
            || ready(robot, &train, levels.as_ref(), options.chunk),
            || ready(robot, &holdout, levels.as_ref(), options.chunk),
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
