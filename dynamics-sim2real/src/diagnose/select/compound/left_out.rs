//! What the selection chose and left out, and why (`resume.rs`): reported
//! as suggestions with the fit that asked for them.

use crate::diagnose::select::pool::Parts;

/// Why a term the selection chose was left out.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Why {
    /// A link correction, or a payload, that leaves no physical body.
    NoBody,
    /// An effort scale that does not act on the whole effort: its fitted
    /// value minus one, and its column's two parts' (the effort beside
    /// gravity, the gravity effort), each with its standard deviation.
    PartOfTheEffort {
        /// The scale minus one.
        common: f64,
        /// The parts' scales minus one.
        scales: Parts,
    },
    /// An encoder offset the data show at its own joint alone: its column
    /// split into its own joint's rows and the other joints', the common
    /// offset not shown to act on the other joints' efforts; the offset,
    /// rad, and the two parts' offsets, each with its standard deviation.
    OwnJointOnly {
        /// The offset as fitted, rad.
        common: f64,
        /// The split's offsets: its own joint's part and the other
        /// joints', rad.
        offsets: Parts,
    },
}

/// A term the selection chose and left out, with its fit in the set it was
/// chosen in.
#[derive(Debug, Clone)]
pub struct LeftOut {
    /// Term index into the pool.
    pub term: usize,
    /// Its parameters in that set's joint fit.
    pub theta: Vec<f64>,
    /// Their standard deviations.
    pub std: Vec<f64>,
    /// Why.
    pub why: Why,
}
