//! Link corrections that leave no physical body are not candidates
//! (`left_out.rs`: the selection resumes without them).
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

#[cfg(test)]
mod tests {
    use nalgebra::{DMatrix, DVector, SVector};

    use super::super::left_out::without_left_out;
    use crate::diagnose::candidates::{Candidate, LinkBasis};
    use crate::diagnose::select::compound::select::select;
    use crate::diagnose::select::pool::{test_pool, test_term};
    use crate::diagnose::Options;
    use crate::rng::Rng;

    /// Two joints' rows interleaved; joint 0's gap is mostly its effort
    /// scale's column `s`, and a little of a column `c`. A link's mass
    /// column is `0.9 s + c`: it fits the gap better than the scale, with
    /// a mass change of -2 kg where the nominal link weighs 1 kg: no body.
    /// The selection without the link chooses the effort scale, and the
    /// link is reported with its fit; held to bodies, nothing is left out.
    #[test]
    fn a_link_that_leaves_no_body_gives_its_place_to_what_explains_the_gap() {
        let (n, joints) = (400, 2);
        let mut rng = Rng::new(11);
        let mut x = DMatrix::<f64>::zeros(n * joints, 2);
        let mut y = DVector::<f64>::zeros(n * joints);
        // Mass change per unit of the link's column: -2 kg fits the gap.
        let a = 0.05 / 0.9 / 2.0;
        for i in 0..n {
            let s = (i as f64 * 0.05).sin() * 20.0;
            let c = (i as f64 * 0.31).cos() * 4.0;
            x[(i * joints, 0)] = a * (0.9 * s + c);
            x[(i * joints, 1)] = s;
            y[i * joints] = -2.0 * a * (0.9 * s + c);
            for j in 0..joints {
                y[i * joints + j] += rng.normal();
            }
        }
        let mut link = test_term(Candidate::Inertial(0), vec![0], vec![false], None);
        let mut v = DMatrix::<f64>::zeros(10, 1);
        v[(0, 0)] = 1.0;
        link.link = Some(LinkBasis {
            link: 0,
            v,
            tip: false,
            moments: true,
        });
        let terms = vec![
            link,
            test_term(Candidate::EffortScale(0), vec![1], vec![false], None),
        ];
        let pool = test_pool(x, y, terms, joints);
        let options = Options::default();
        let set = select::<2>(&pool, vec![], &options);
        assert_eq!(set, vec![0], "the link is chosen first");
        let mut nominal = SVector::<f64, 10>::zeros();
        nominal[0] = 1.0;
        for i in [4, 7, 9] {
            nominal[i] = 0.01;
        }
        let (set, left_out, _) =
            without_left_out::<2>(&pool, set.clone(), &[nominal], None, None, &[], &options);
        assert_eq!(set, vec![1]);
        match &left_out[..] {
            [b] => {
                assert_eq!(b.term, 0);
                assert!(b.theta[0] < -1.0, "{:?}", b.theta);
            }
            other => panic!("{other:?}"),
        }
        let held = Options {
            hold_links: true,
            ..Options::default()
        };
        let (kept, none, _) =
            without_left_out::<2>(&pool, vec![0], &[nominal], None, None, &[], &held);
        assert_eq!(kept, vec![0]);
        assert!(none.is_empty());
    }
}
