//! A nominal model whose inertial parameters are rough: the compound
//! explanation asks, on most of the links it may correct, for corrections
//! that leave no physical body (`compound/bodies.rs`). A model whose links
//! are right asks that of a link now and then, where another effect stands
//! in for a link; a CAD model of a real arm asks it of nearly every link
//! (the Panda's and the KUKA's logs: six of seven). The diagnosis then holds
//! link corrections to the nearest physical body, as
//! [`Options::hold_links`](crate::diagnose::Options::hold_links) asks,
//! rather than leaving each link out and the effects of every other kind
//! to stand in for the model's masses.
//!
//! An arm of three links cannot tell: on our generator's simulated arms,
//! whose links are exact, an elastic joint and a payload together took all
//! three links of the mar beyond every body, and the arm3r's three too.

use super::compound::{LeftOut, Why};
use super::pool::Pool;
use crate::diagnose::candidates::Candidate;

/// The least number of links whose correction leaves no body for the
/// model's inertials to be rough (besides being more than half of the
/// links the diagnosis may correct): see the module's doc.
pub const ROUGH_LEAST: usize = 4;

/// How link corrections that leave no physical body were treated.
///
/// ```
/// use dynamics_sim2real::diagnose::HeldLinks;
/// assert!(HeldLinks::Rough { links: 6, of: 7 }.held());
/// assert!(!HeldLinks::Judged.held());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HeldLinks {
    /// Left out with the reason (the nominal model's inertials trusted).
    Judged,
    /// Held to the nearest body because the options ask it.
    Asked,
    /// Held to the nearest body because the data ask for corrections
    /// without a body on `links` of the `of` links the diagnosis may
    /// correct.
    Rough {
        /// Links whose correction leaves no body.
        links: usize,
        /// Links the diagnosis may correct.
        of: usize,
    },
}

impl HeldLinks {
    /// Whether link corrections are held to the nearest physical body.
    pub fn held(self) -> bool {
        !matches!(self, HeldLinks::Judged)
    }
}

/// `Some((links, of))` where the selection left out (`left_out`), for
/// leaving no physical body, the corrections of `links` of the `of` links
/// of the pool, and they are more than half of them and at least
/// [`ROUGH_LEAST`].
pub fn rough(pool: &Pool, left_out: &[LeftOut]) -> Option<(usize, usize)> {
    let mut all: Vec<usize> = pool
        .terms
        .iter()
        .filter_map(|t| match t.fit.candidate {
            Candidate::Inertial(l) => Some(l),
            _ => None,
        })
        .collect();
    all.sort_unstable();
    all.dedup();
    let mut out: Vec<usize> = left_out
        .iter()
        .filter(|l| l.why == Why::NoBody)
        .filter_map(|l| match pool.terms[l.term].fit.candidate {
            Candidate::Inertial(link) => Some(link),
            _ => None,
        })
        .collect();
    out.sort_unstable();
    out.dedup();
    let (links, of) = (out.len(), all.len());
    (links >= ROUGH_LEAST && 2 * links > of).then_some((links, of))
}

#[cfg(test)]
mod tests {
    use nalgebra::{DMatrix, DVector};

    use super::*;
    use crate::diagnose::select::pool::{test_pool, test_term};

    /// A pool of `links` links' corrections (two terms each, as a link's
    /// moments and its full correction) and a friction term.
    fn pool(links: usize) -> Pool {
        let mut terms: Vec<_> = (0..links)
            .flat_map(|l| {
                [
                    test_term(Candidate::Inertial(l), vec![0], vec![false], None),
                    test_term(Candidate::Inertial(l), vec![0], vec![false], None),
                ]
            })
            .collect();
        terms.push(test_term(Candidate::Viscous(0), vec![0], vec![false], None));
        test_pool(
            DMatrix::from_element(4, 1, 1.0),
            DVector::zeros(4),
            terms,
            1,
        )
    }

    fn left(term: usize, why: Why) -> LeftOut {
        LeftOut {
            term,
            theta: vec![],
            std: vec![],
            why,
        }
    }

    #[test]
    fn most_links_without_a_body_make_the_model_rough() {
        let pool = pool(7);
        // Links 0-5 (terms 0, 2, .., 10), link 2 twice.
        let mut out: Vec<LeftOut> = (0..6).map(|l| left(2 * l, Why::NoBody)).collect();
        out.push(left(5, Why::NoBody));
        assert_eq!(rough(&pool, &out), Some((6, 7)));
        // Three of seven: one effect standing in for another, not a rough model.
        assert_eq!(rough(&pool, &out[..3]), None);
        // Four of seven are most of them.
        assert_eq!(rough(&pool, &out[..4]), Some((4, 7)));
        // Four of eight are not.
        assert_eq!(rough(&self::pool(8), &out[..4]), None);
    }

    #[test]
    fn a_short_arm_is_never_rough_and_other_kinds_do_not_count() {
        let all = [
            left(0, Why::NoBody),
            left(2, Why::NoBody),
            left(4, Why::NoBody),
        ];
        assert_eq!(rough(&pool(3), &all), None, "three of three");
        let pool = pool(5);
        let four: Vec<LeftOut> = (0..4).map(|l| left(2 * l, Why::NoBody)).collect();
        assert_eq!(rough(&pool, &four), Some((4, 5)));
        let scale = Why::PartOfTheEffort {
            common: 0.1,
            scales: crate::diagnose::select::pool::Parts {
                part: (0.0, 0.0),
                rest: (0.0, 0.0),
            },
        };
        // The friction term left out for another reason is no link.
        let mut mixed = four[..3].to_vec();
        mixed.push(left(10, scale));
        assert_eq!(rough(&pool, &mixed), None);
    }
}
