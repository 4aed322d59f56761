//! A payload's second moments at the centre the explanation finds.
//!
//! A payload with its centre of mass is linear in its mass and first
//! moments; its point mass's second moments (`m (|c|^2 I - c c^T)` about
//! the tip's origin) are not, and its columns take them at the centre the
//! candidate carries (`Candidate::PayloadCom`). The single fits meet the
//! residual with every other effect still in it, so their centres mean
//! little; the explanation's joint fit places the payload beside the
//! other effects. Where that centre is determined and differs from the
//! one the columns took, the payload is moved there and the explanation
//! chosen again, up to [`PASSES`] times: left at the tip's origin, a hand's second moments
//! (0.76 kg at 7 cm: 4e-3 kg m^2) are a residual the explanation fills
//! with link corrections and encoder offsets that are not there.

use nalgebra::Vector3;

use super::compound::Explanation;
use super::pool::{payload_leaves_no_body, Carrier, Pool};
use crate::diagnose::candidates::{payload_com, Candidate};

/// The farthest from the tip's origin a payload's centre is taken as the
/// centre of its second moments, m: beyond it the first moments are not
/// a body at the tip, and the centre stays where it was.
const REACH: f64 = 0.5;

/// How far a centre must move to be worth choosing the explanation again,
/// m: a millimetre moves a hand's second moments by 3 %.
const MOVE: f64 = 1e-3;

/// The most times the explanation is chosen again: each pass takes the
/// second moments nearer the centre, and the link corrections and offsets
/// they stood in for leave the explanation, which moves the centre again
/// (a hand's from 5.6 to 7.2 cm in two passes).
pub const PASSES: usize = 3;

/// The payload of `explanation` (over `pool`) and the centre its joint fit
/// gives, when the mass is determined (beyond twice its standard
/// deviation), the centre within [`REACH`] of the tip and more than
/// [`MOVE`] from the one its columns took, and the payload leaves the
/// `carrier` of the tip a physical body (`pool/carrier.rs`: a point mass
/// no body could be is no centre to take second moments at); `None`
/// otherwise.
pub fn recentred(
    pool: &Pool,
    explanation: &Explanation,
    carrier: Option<&Carrier>,
) -> Option<(Candidate, Candidate)> {
    explanation.set.iter().enumerate().find_map(|(i, &t)| {
        let c = pool.terms[t].fit.candidate;
        let Candidate::PayloadCom(was) = c else {
            return None;
        };
        let theta = explanation.sol.theta.get(i)?;
        let std = explanation.sol.std.get(i)?;
        if payload_leaves_no_body(carrier, c, theta, std) {
            return None;
        }
        let (m, sm) = (*theta.first()?, *std.first()?);
        let com = payload_com(theta);
        let at = Vector3::from(com);
        let determined = m.abs() > 2.0 * sm && at.norm() <= REACH;
        (determined && (at - Vector3::from(was)).norm() > MOVE)
            .then_some((c, Candidate::PayloadCom(com)))
    })
}
