//! Link corrections that leave no physical body are not candidates
//! (`resume.rs`: the selection resumes without them).
//!
//! A link correction whose fit leaves no physical body once the
//! combinations the data do not determine are moved (mass <= 0, or a
//! pseudo-inertia that is not positive semi-definite) is not named
//! (`evaluate/confirm.rs`, rule 3). Chosen, it has also taken from the
//! other terms what it explains on the training record: left out only
//! afterwards, its place stays empty, and a joint whose gap it took (an
//! effort scale at a shoulder, a payload at the tip) is left unexplained.
//! So every term of such a link leaves the pool's candidates. With
//! `hold_links` they are held to the nearest body instead
//! (`Pool::solve_physical`) and no link is left out here.
//!
//! A payload is a change of the body that carries the tip: one that leaves
//! that body no physical body (`pool/carrier.rs`) leaves the candidates
//! the same way (with `hold_links` too: a payload is not held).

use nalgebra::SVector;

use super::left_out::{LeftOut, Why};
use crate::diagnose::select::pool::{is_body, payload_leaves_no_body, Carrier, Pool, Solution};
use crate::diagnose::Options;

/// The link corrections of `set` (fitted `sol`) that leave no physical
/// body (links of `nominal` parameters) and the payloads that leave the
/// tip's `carrier` none; and the terms to ban for them: every term of
/// such a link, and such a payload.
pub fn bodiless(
    pool: &Pool,
    set: &[usize],
    sol: &Solution,
    nominal: &[SVector<f64, 10>],
    carrier: Option<&Carrier>,
    options: &Options,
) -> (Vec<LeftOut>, Vec<usize>) {
    let links_judged = !options.hold_links && !nominal.is_empty();
    let mut left_out: Vec<LeftOut> = Vec::new();
    let mut links: Vec<usize> = Vec::new();
    let mut banned: Vec<usize> = Vec::new();
    for (i, &t) in set.iter().enumerate() {
        let term = &pool.terms[t];
        let no_body = match term.link.as_ref() {
            Some(b) if links_judged && !is_body(b, &sol.theta[i], nominal.get(b.link)) => {
                links.push(b.link);
                true
            }
            Some(_) => false,
            None if payload_leaves_no_body(
                carrier,
                term.fit.candidate,
                &sol.theta[i],
                &sol.std[i],
            ) =>
            {
                banned.push(t);
                true
            }
            None => false,
        };
        if no_body {
            left_out.push(LeftOut {
                term: t,
                theta: sol.theta[i].clone(),
                std: sol.std[i].clone(),
                why: Why::NoBody,
            });
        }
    }
    banned.extend((0..pool.terms.len()).filter(|&t| {
        pool.terms[t]
            .link
            .as_ref()
            .is_some_and(|b| links.contains(&b.link))
    }));
    (left_out, banned)
}
