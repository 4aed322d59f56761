//! Nested candidates: a richer effect that contains a simpler one at the
//! same place (Stribeck friction contains Coulomb friction, a wider
//! Coulomb friction the sharp one, elasticity and backlash a rigid rotor,
//! a spring an effort offset, a link's inertial correction a point mass at
//! the tip, a payload with its centre of mass one at the tip's origin), and the margin by which the richer must win. The ranking and
//! the compound explanation both decide parsimony by these rules.

use crate::diagnose::candidates::Candidate;
use crate::diagnose::Options;

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
        Candidate::Inertial(_) => Some(|s| matches!(s, Candidate::Payload | Candidate::PayloadCom)),
        // A centre of mass off the tip's origin is three more parameters.
        Candidate::PayloadCom => Some(|s| matches!(s, Candidate::Payload)),
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
