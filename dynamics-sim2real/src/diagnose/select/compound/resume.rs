//! What the selection chose that is not what it seems leaves the
//! candidates, and the selection resumes without it: a link correction or
//! a payload that leaves no physical body (`bodies.rs`), an effort scale
//! that acts on part of the effort only (`scales.rs`), an encoder offset
//! that its own joint alone shows (`offsets.rs`).
//!
//! Left out only in the confirmation, such a term's place would stay
//! empty: it has taken from the other terms what it explains on the
//! training record, and the rest of the set was chosen beside it. So its
//! terms leave the pool's candidates, and the selection resumes from the
//! rest of the set under the same criterion, until nothing of the set is
//! left out (at most [`ROUNDS`] times). What was left out is reported as a
//! suggestion with the fit that asked for it.

use nalgebra::SVector;

use super::bodies::bodiless;
use super::left_out::LeftOut;
use super::offsets::partial_offsets;
use super::scales::{partial_scales, BesideGravity};
use super::select::select_except;
use crate::diagnose::select::pool::{Carrier, Pool};
use crate::diagnose::Options;

/// Rounds of leaving terms out at most.
pub const ROUNDS: usize = 4;

/// `set` with what is not what it seems left out (links of `nominal`
/// parameters that leave no body, payloads that leave the tip's `carrier`
/// none, effort scales of part of the effort split by `beside`, encoder
/// offsets their own joint alone shows, split at the rows `beside` counts), and the
/// selection resumed without those terms nor the terms `before` (banned
/// already); the terms left out, in the order found, and the terms banned
/// for them (every term of a link left out).
pub fn without_left_out<const N: usize>(
    pool: &Pool,
    mut set: Vec<usize>,
    nominal: &[SVector<f64, 10>],
    carrier: Option<&Carrier>,
    beside: Option<&BesideGravity>,
    before: &[usize],
    options: &Options,
) -> (Vec<usize>, Vec<LeftOut>, Vec<usize>) {
    let mut left_out: Vec<LeftOut> = Vec::new();
    let mut banned: Vec<usize> = before.to_vec();
    // The split judged as the confirmation judges it: links as fitted, or
    // held to bodies.
    let solve = |q: &Pool, s: &[usize]| {
        if options.hold_links {
            q.solve_physical(s, nominal)
        } else {
            q.solve(s)
        }
    };
    for _ in 0..ROUNDS {
        let sol = pool.solve(&set);
        let (mut out, mut ban) = bodiless(pool, &set, &sol, nominal, carrier, options);
        if let Some(beside) = beside {
            let scales = partial_scales(pool, &set, &sol, beside, solve);
            ban.extend(scales.iter().map(|l| l.term));
            out.extend(scales);
            let offsets = partial_offsets(pool, &set, &sol, beside.inflate(), solve);
            ban.extend(offsets.iter().map(|l| l.term));
            out.extend(offsets);
        }
        if ban.is_empty() {
            break;
        }
        left_out.extend(out);
        banned.extend(ban);
        set.retain(|t| !banned.contains(t));
        set = select_except::<N>(pool, set, options, &banned);
    }
    banned.retain(|t| !before.contains(t));
    (set, left_out, banned)
}

#[cfg(test)]
mod tests {
    use nalgebra::{DMatrix, DVector, SVector};

    use super::*;
    use crate::diagnose::candidates::{Candidate, LinkBasis};
    use crate::diagnose::select::compound::left_out::Why;
    use crate::diagnose::select::compound::select::select;
    use crate::diagnose::select::pool::{test_pool, test_term};
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

    /// Two joints' rows interleaved. Joint 0's model effort is its gravity
    /// effort `g` and the effort beside it `b`; its gap is -30 % of `g`
    /// alone (a mass the model places wrong), which a mass-like column `g`
    /// explains. An effort scale chosen for that gap (the set given) does
    /// not act on the whole effort: it is left out with its split, and the
    /// selection resumed without it chooses the mass. The same gap as -30 %
    /// of the whole effort keeps the scale.
    #[test]
    fn a_scale_of_the_gravity_effort_alone_gives_its_place_to_what_explains_it() {
        let (n, joints) = (600, 2);
        let mut rng = Rng::new(5);
        let g: Vec<f64> = (0..n).map(|i| (i as f64 * 0.013).sin() * 30.0).collect();
        let b: Vec<f64> = (0..n).map(|i| (i as f64 * 0.071).cos() * 20.0).collect();
        let run = |gap: &dyn Fn(usize) -> f64, rng: &mut Rng| {
            let mut x = DMatrix::<f64>::zeros(n * joints, 2);
            let mut y = DVector::<f64>::zeros(n * joints);
            let mut beside = vec![0.0; n * joints];
            for i in 0..n {
                x[(i * joints, 0)] = g[i] + b[i];
                x[(i * joints, 1)] = g[i];
                beside[i * joints] = b[i];
                y[i * joints] = gap(i);
                for j in 0..joints {
                    y[i * joints + j] += rng.normal();
                }
            }
            let terms = vec![
                test_term(Candidate::EffortScale(0), vec![0], vec![false], None),
                test_term(Candidate::Inertial(0), vec![1], vec![false], None),
            ];
            let pool = test_pool(x, y, terms, joints);
            let beside = BesideGravity::given(beside, joints, 1.0);
            let (set, left_out, _) = without_left_out::<2>(
                &pool,
                vec![0],
                &[],
                None,
                Some(&beside),
                &[],
                &Options::default(),
            );
            (set, left_out)
        };
        let (set, left_out) = run(&|i| -0.3 * g[i], &mut rng);
        assert_eq!(set, vec![1], "{left_out:?}");
        match &left_out[..] {
            [l] => match l.why {
                Why::PartOfTheEffort { common, scales } => {
                    assert_eq!(l.term, 0);
                    assert!(common < 0.0, "{common}");
                    assert!(scales.part.0.abs() < 0.01, "{scales:?}");
                    assert!((scales.rest.0 + 0.3).abs() < 0.01, "{scales:?}");
                }
                other => panic!("{other:?}"),
            },
            other => panic!("{other:?}"),
        }
        let (set, left_out) = run(&|i| -0.3 * (g[i] + b[i]), &mut rng);
        assert_eq!(set, vec![0]);
        assert!(left_out.is_empty(), "{left_out:?}");
    }
}
