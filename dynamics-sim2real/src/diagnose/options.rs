//! The options of a diagnosis: which effects, the margins of the
//! information criterion, the noise floor's ratio, the threads.

use super::SensorNoise;
use crate::effects::EffectKind;

/// Options of [`diagnose`](super::diagnose()).
#[derive(Debug, Clone, PartialEq)]
pub struct Options {
    /// Candidate kinds (empty: all).
    pub kinds: Vec<EffectKind>,
    /// AICc improvement over the nominal model below which the verdict is
    /// `none`.
    pub none_margin: f64,
    /// AICc difference under which two candidates are `ambiguous`.
    pub ambiguity_margin: f64,
    /// When no candidate qualifies, the verdict is `unexplained` rather than
    /// `none` if some joint's torque residual RMS is at least this many
    /// times its noise floor: the gap is real, the candidates miss it.
    pub unexplained_ratio: f64,
    /// AICc improvement a richer nested model must add over the simpler one
    /// it contains to be preferred (10: "strong evidence" on the usual
    /// scale of AIC differences).
    pub nesting_margin: f64,
    /// AICc improvement each effect after the first must add to the
    /// compound explanation (the first must add `none_margin`).
    pub add_margin: f64,
    /// Cross-validated deviance (block cross-validation on the training
    /// data, `validate.rs`) each effect of the compound explanation must
    /// save: an effect is added, and kept, only if the set predicts blocks
    /// of the data it was not fitted on better with it than without.
    pub cv_margin: f64,
    /// The compound explanation stops adding effects once the residual RMS
    /// is within this many times the noise floor on every joint; and a
    /// motor side (elasticity, backlash) is not ranked before the rigid
    /// rotor it contains where that rotor leaves its joint within it.
    pub floor_ratio: f64,
    /// Threads (0: all cores).
    pub threads: usize,
    /// Samples the model is evaluated at a time along a record, and the
    /// most the link columns hold of it at once (0: 4096); the result does
    /// not depend on it. `usize::MAX` evaluates each record whole.
    pub chunk: usize,
    /// Sensor noise, when known: the torque residual's noise floor is then
    /// what this noise makes of it (pushed through the same smoothing and
    /// inverse dynamics) rather than what noise of the levels estimated
    /// from the data makes of it.
    pub noise: Option<SensorNoise>,
    /// Hold a link correction the fit takes beyond every body at the
    /// nearest physical one in the metric of the data, and name it when it
    /// holds on the held-out record (`select/pool/physical.rs`); off, such
    /// a correction is left out with the reason, unless the data ask for
    /// such corrections on most links (the model's inertials are rough:
    /// [`HeldLinks::Rough`](crate::diagnose::HeldLinks::Rough)). For a model whose
    /// inertial parameters are known to be rough (a CAD model of a real
    /// arm): on logs of real arms it names corrections that predict the
    /// held-out record better than a least-squares identification; on
    /// simulated data whose links are exact, the held corrections also
    /// stand in for effects of other kinds the diagnosis models more simply
    /// than the simulator (docs/diagnosis.md).
    pub hold_links: bool,
    /// Never hold link corrections to bodies, not even where the data ask
    /// for corrections without a body on most links (a nominal model whose
    /// inertials are trusted); `hold_links` takes precedence.
    pub judge_links: bool,
    /// The calibration the nominal model carries (a report used as the
    /// baseline): the spread its data left on each joint's friction. A
    /// friction correction within what that spread and its own allow is
    /// no change since the calibration: a suggestion, not a named effect
    /// (`evaluate/calibration.rs`). `None`: every confirmed correction is
    /// named.
    pub calibration: Option<CalibrationSpread>,
}

/// Per joint (in the robot's order), the standard deviation a
/// calibration's data left on the Coulomb level and on the viscous
/// coefficient: a report's `which.friction[].coulomb_std` and
/// `viscous_std` (`NaN` or a missing joint: not known, no test); and
/// whether the calibration corrected each (its level differs from the
/// nominal one).
///
/// ```
/// use dynamics_sim2real::diagnose::{CalibrationSpread, Options};
/// let calibration = CalibrationSpread {
///     coulomb: vec![0.01, 0.02],
///     viscous: vec![0.004, f64::NAN],
///     coulomb_corrected: vec![true, true],
///     viscous_corrected: vec![false, false],
/// };
/// let options = Options { calibration: Some(calibration), ..Options::default() };
/// assert_eq!(options.calibration.unwrap().viscous.len(), 2);
/// ```
#[derive(Debug, Clone, PartialEq, Default)]
pub struct CalibrationSpread {
    /// Coulomb level per joint (N m or N).
    pub coulomb: Vec<f64>,
    /// Viscous coefficient per joint (N m s/rad or N s/m).
    pub viscous: Vec<f64>,
    /// Whether the calibration corrected the Coulomb level (else it kept
    /// the nominal one: the data could not tell it from it).
    pub coulomb_corrected: Vec<bool>,
    /// The same for the viscous coefficient.
    pub viscous_corrected: Vec<bool>,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            kinds: vec![],
            none_margin: 100.0,
            ambiguity_margin: 10.0,
            unexplained_ratio: 3.0,
            nesting_margin: 10.0,
            add_margin: 40.0,
            cv_margin: 0.0,
            floor_ratio: 1.0,
            threads: 0,
            chunk: 0,
            noise: None,
            hold_links: false,
            judge_links: false,
            calibration: None,
        }
    }
}
