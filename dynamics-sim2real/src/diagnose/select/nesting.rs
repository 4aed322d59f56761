//! Nested candidates: a richer effect that contains a simpler one at the
//! same place (Stribeck friction contains Coulomb friction, a wider
//! Coulomb friction the sharp one, elasticity and backlash a rigid rotor,
//! a spring an effort offset, a link's inertial correction a point mass at
//! the tip, a payload with its centre of mass one at the tip's origin), and the margin by which the richer must win. The ranking and
//! the compound explanation both decide parsimony by these rules.

use crate::diagnose::candidates::Candidate;
use crate::diagnose::Options;
use crate::effects::EffectKind;

/// The simpler term a richer one nests at its place.
pub fn simpler(c: Candidate) -> Option<fn(&Candidate) -> bool> {
    match c {
        Candidate::Stribeck(..) => Some(|s| matches!(s, Candidate::Coulomb(..))),
        // A width is one more parameter than the sharp law.
        c if c.widened() => Some(|s| matches!(s, Candidate::Coulomb(..)) && !s.widened()),
        Candidate::Elasticity(_) | Candidate::Backlash(_) => {
            Some(|s| matches!(s, Candidate::Armature(_)))
        }
        // A spring is an effort offset that grows with the position.
        Candidate::Spring(_) => Some(|s| matches!(s, Candidate::EffortOffset(_))),
        // A point mass at the tip is an inertial change of the tip's link
        // with one parameter (four with its centre of mass) instead of up
        // to ten.
        Candidate::Inertial(_) => {
            Some(|s| matches!(s, Candidate::Payload | Candidate::PayloadCom(_)))
        }
        // A centre of mass off the tip's origin is three more parameters.
        Candidate::PayloadCom(_) => Some(|s| matches!(s, Candidate::Payload)),
        _ => None,
    }
}

/// What a richer term must gain over the simpler one it nests (or a term
/// over another of its family it replaces): Stribeck's breakaway level is
/// one more parameter on top of Coulomb friction, and must earn it like
/// a first effect (a Stribeck curve at 0.01 rad/s otherwise reshapes
/// the smooth sign of a large Coulomb friction); the motor sides and link
/// corrections the nesting margin.
pub fn nesting(c: Candidate, options: &Options) -> f64 {
    match c {
        Candidate::Stribeck(..) => options.none_margin.max(options.nesting_margin),
        _ => options.nesting_margin,
    }
}

/// A Stribeck breakaway level this far above the Coulomb level (as a
/// fraction of it) is physically meaningful: below it the hump at low
/// speed is a few percent of the friction a drive shows and no one acts on
/// it (measured breakaway levels of robot joints lie 10-100 % above their
/// Coulomb level).
pub const MEANINGFUL_BREAKAWAY: f64 = 0.1;

/// Standard deviations either side of a value that bound what the data
/// determine of it (about 95 % for a Gaussian estimate).
pub const INTERVAL_STDS: f64 = 2.0;

/// What the data say of the parameters a richer effect adds to the simpler
/// one it nests at its place.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Extra {
    /// Determined near zero: the interval excludes every physically
    /// meaningful value, so the simpler effect is the answer whatever the
    /// information criterion's margin.
    Absent,
    /// Determined away from zero: the richer effect's extra is there.
    Present,
    /// The interval covers both zero and a meaningful value (or the
    /// extra has no interval here): the data cannot tell the two apart.
    Undetermined,
}

/// What the fitted `parameters` (name, value, standard deviation) of a
/// richer effect of kind `richer` say of its extra over the simpler effect
/// it nests. Stribeck friction over Coulomb friction: the breakaway excess
/// `fs_minus_fc`, against zero and [`MEANINGFUL_BREAKAWAY`] times the
/// Coulomb level `fc`, each within [`INTERVAL_STDS`] standard deviations
/// (an excess held at zero by its sign constraint is judged at the spread
/// it has when freed; one without a spread has no interval).
/// The other nested pairs (a motor side over its rotor, a spring over an
/// offset, a link over a payload) have no interval of their extra on one
/// physical scale here: `Undetermined`, so the information criterion's
/// margin alone decides whether they are ambiguous.
pub fn extra(richer: EffectKind, parameters: &[(&str, f64, f64)]) -> Extra {
    let get = |name: &str| {
        parameters
            .iter()
            .find(|p| p.0 == name)
            .map(|p| (p.1, p.2))
            .filter(|(v, s)| v.is_finite() && s.is_finite() && *s >= 0.0)
    };
    match richer {
        EffectKind::StribeckFriction => {
            let (Some((fc, _)), Some((x, s))) = (get("fc"), get("fs_minus_fc")) else {
                return Extra::Undetermined;
            };
            // No spread is no interval. An excess held at zero by its
            // sign constraint carries the spread it has when freed: the
            // data asked for a negative excess, and the interval around
            // zero at that spread holds (conservatively) what a positive
            // one could be.
            if s == 0.0 {
                return Extra::Undetermined;
            }
            let meaningful = MEANINGFUL_BREAKAWAY * fc.abs();
            let (lo, hi) = (x - INTERVAL_STDS * s, x + INTERVAL_STDS * s);
            if lo > 0.0 || hi < 0.0 {
                Extra::Present
            } else if hi < meaningful && lo > -meaningful {
                Extra::Absent
            } else {
                Extra::Undetermined
            }
        }
        _ => Extra::Undetermined,
    }
}

/// How much spread the data leave the spread estimate itself and the
/// Stribeck velocity the fit picks from its grid: a motion is asked to
/// determine the breakaway excess this much tighter than the bare
/// interval rule needs.
pub const DATA_MARGIN: f64 = 1.5;

/// Beyond this many times the data of the same kind, a longer run is no
/// way to settle a breakaway excess (a hundred times a 10 s record is
/// most of a day): the motion must change instead (slow reversals, the
/// verdict's separating motion), and no figure is given.
pub const MOST_DATA: f64 = 100.0;

/// How many times as much data of the same kind would settle a
/// breakaway excess `excess +- std` over a Coulomb level `fc` (the
/// Stribeck fit's `fs_minus_fc` and `fc`): the interval of
/// [`INTERVAL_STDS`] standard deviations, shrinking as one over the square
/// root of the data's length, must leave out zero or every meaningful
/// value ([`MEANINGFUL_BREAKAWAY`] of `fc`), with [`DATA_MARGIN`] to
/// spare. One where these data already settle it; `None` where they give
/// no spread or no Coulomb level to judge by, or where more than
/// [`MOST_DATA`] times the data would be needed.
///
/// ```
/// use dynamics_sim2real::diagnose::breakaway_data_needed;
/// // 10 % of fc = 1 is 0.1; an excess held at zero to +- 0.1 needs its
/// // spread 2 x 1.5 = 3 times smaller for the interval to stay under
/// // 0.1: nine times the data.
/// let f = breakaway_data_needed(1.0, 0.0, 0.1).unwrap();
/// assert!((f - 9.0).abs() < 1e-9);
/// // Settled already: absent (+- 0.01) or present (0.5 +- 0.05).
/// assert_eq!(breakaway_data_needed(1.0, 0.0, 0.01), Some(1.0));
/// assert_eq!(breakaway_data_needed(1.0, 0.5, 0.05), Some(1.0));
/// // Held at zero to +- 12 over a level of 1: millions of times the
/// // data, out of reach of a longer run.
/// assert_eq!(breakaway_data_needed(1.0, 0.0, 12.0), None);
/// ```
pub fn breakaway_data_needed(fc: f64, excess: f64, std: f64) -> Option<f64> {
    let meaningful = MEANINGFUL_BREAKAWAY * fc.abs();
    if !(meaningful > 0.0 && std > 0.0 && std.is_finite() && excess.is_finite()) {
        return None;
    }
    let wanted = INTERVAL_STDS * DATA_MARGIN * std;
    // Absent: |excess| + wanted' < meaningful; present: excess - wanted' > 0.
    let absent =
        (meaningful > excess.abs()).then(|| (wanted / (meaningful - excess.abs())).powi(2));
    let present = (excess > 0.0).then(|| (wanted / excess).powi(2));
    let f = match (absent, present) {
        (Some(a), Some(p)) => a.min(p),
        (Some(a), None) => a,
        (None, Some(p)) => p,
        (None, None) => return None,
    };
    (f <= MOST_DATA).then_some(f.max(1.0))
}

/// A fitted effect: its kind and its parameters (name, value, standard
/// deviation).
pub type Fitted<'a> = (EffectKind, &'a [(&'a str, f64, f64)]);

/// Whether `rival`, at the same place as the `chosen` effect and within
/// the information criterion's ambiguity margin of it, leaves the choice
/// ambiguous. When one of the two nests the other, the richer one's extra
/// parameter decides ([`extra`]): a richer rival whose extra the data
/// determine near zero does not (the simpler chosen effect is the answer;
/// no motion could make a nested rival fit worse, it only costs its extra
/// parameter), nor does a simpler rival of a chosen richer effect whose
/// extra the data determine away from zero; while the data leave the extra
/// undetermined, it does. Pairs that do not nest: always.
pub fn nested_rival_stands(chosen: Fitted, rival: Fitted) -> bool {
    let nests = |rich: EffectKind, simple: EffectKind| {
        matches!(
            (rich, simple),
            (EffectKind::StribeckFriction, EffectKind::CoulombFriction)
        )
    };
    if nests(rival.0, chosen.0) {
        extra(rival.0, rival.1) != Extra::Absent
    } else if nests(chosen.0, rival.0) {
        extra(chosen.0, chosen.1) != Extra::Present
    } else {
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_breakaway_excess_is_judged_by_its_interval() {
        use EffectKind::{CoulombFriction as C, StribeckFriction as S};
        // fc = 1: meaningful excess 0.1; intervals at 2 std.
        let p = |x: f64, s: f64| [("fc", 1.0, 0.01), ("fs_minus_fc", x, s)];
        // [-0.02, 0.06]: covers zero, excludes 0.1 -> absent.
        assert_eq!(extra(S, &p(0.02, 0.02)), Extra::Absent);
        // [0.1, 0.5]: excludes zero -> present.
        assert_eq!(extra(S, &p(0.3, 0.1)), Extra::Present);
        // [-0.1, 0.3]: covers both -> undetermined.
        assert_eq!(extra(S, &p(0.1, 0.1)), Extra::Undetermined);
        // An undetermined spread is no interval, nor is a value with no
        // spread.
        assert_eq!(extra(S, &p(0.0, f64::INFINITY)), Extra::Undetermined);
        assert_eq!(extra(S, &p(0.0, 0.0)), Extra::Undetermined);
        // Held at zero with the spread it has when freed: [-0.04, 0.04]
        // excludes 0.1 -> absent; [-0.2, 0.2] does not.
        assert_eq!(extra(S, &p(0.0, 0.02)), Extra::Absent);
        assert_eq!(extra(S, &p(0.0, 0.1)), Extra::Undetermined);
        // Coulomb chosen, Stribeck rival: it stands unless its excess is
        // determined near zero.
        let c = [("fc", 1.0, 0.01)];
        let stands = |chosen: Fitted, rival: Fitted| nested_rival_stands(chosen, rival);
        assert!(!stands((C, &c), (S, &p(0.02, 0.02))));
        assert!(stands((C, &c), (S, &p(0.1, 0.1))));
        assert!(stands((C, &c), (S, &p(0.3, 0.1))));
        // Stribeck chosen, Coulomb rival: it stands unless the excess is
        // determined away from zero.
        assert!(!stands((S, &p(0.3, 0.1)), (C, &c)));
        assert!(stands((S, &p(0.1, 0.1)), (C, &c)));
        // Pairs without such an interval: the margin decides.
        assert!(stands(
            (EffectKind::Armature, &[("inertia", 0.1, 1e-4)]),
            (EffectKind::Backlash, &[("half_width", 1e-3, 1e-5)])
        ));
    }
}
