//! What the selection chose that is not what it seems leaves the
//! candidates, and the selection resumes without it: a link correction or
//! a payload that leaves no physical body (`bodies.rs`), an effort scale
//! that acts on part of the effort only (`scales.rs`).
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
use super::scales::{partial_scales, BesideGravity};
use super::select::select_except;
use crate::diagnose::select::pool::{Carrier, Parts, Pool};
use crate::diagnose::Options;

/// Rounds of leaving terms out at most.
pub const ROUNDS: usize = 4;

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

/// `set` with what is not what it seems left out (links of `nominal`
/// parameters that leave no body, payloads that leave the tip's `carrier`
/// none, effort scales of part of the effort split by `beside`), and the
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
