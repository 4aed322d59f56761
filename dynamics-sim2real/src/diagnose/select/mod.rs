//! Selection: which of the fitted candidates explain the gap.
//!
//! - `criterion.rs`: ties of the information criterion;
//! - `nesting.rs`: richer effects that contain simpler ones, and the
//!   margin they must win by;
//! - `rank/`: the single-effect ranking (the best variant per kind and
//!   place, parsimony, rival motor sides);
//! - `pool/`: every fitted term as whitened columns and one Gram matrix
//!   (changed only through `Pool`'s methods), with the prior toward the
//!   nominal model;
//! - `compound/`: the compound explanation, the set of effects that
//!   together explain the gap (forward selection, elimination from the
//!   full linear model, cross-validation, the prior's strength);
//! - `rough.rs`: a nominal model whose inertials are rough, whose link
//!   corrections are then held to bodies;
//! - `recentre.rs`: a payload's second moments moved to the centre of mass
//!   the explanation finds, and the explanation chosen again.

mod compound;
mod criterion;
mod nesting;
mod pool;
mod rank;
mod recentre;
mod rough;

pub use compound::{
    against_others, effects, joint_fit, partial_offset, partial_offsets, partial_scale,
    partial_scales, BesideGravity, Explanation, Why,
};
pub use nesting::{breakaway_data_needed, nested_rival_stands};
pub use pool::{helps, model_lag, Carrier, Parts, Pool, Solution};
pub(in crate::diagnose) use pool::{is_body, payload_leaves_no_body};
#[cfg(test)]
pub(crate) use pool::{test_pool, test_term};
pub use rough::HeldLinks;

use nalgebra::SVector;

use crate::diagnose::candidates::{regressor_columns, Prepared};
use crate::diagnose::fit::{corrected_rows, fit, window_of, Fit, Fitted, Windows};
use crate::diagnose::Options;
use crate::effects::EffectKind;
use dynamics_runtime::Robot;

/// What the selection chose: the single-effect ranking and the compound
/// explanation over the pool it was chosen from.
pub struct Selection {
    /// The best variant per (kind, place), best first (`rank/`); no
    /// payload that leaves the tip's carrier no physical body.
    pub best: Vec<Fit>,
    /// Every fitted term as whitened columns and their Gram matrix.
    pub pool: Pool,
    /// The compound explanation: the chosen set and its joint fit.
    pub explanation: Explanation,
    /// The links' nominal inertial parameters (empty: the robot gives
    /// none).
    pub nominal: Vec<SVector<f64, 10>>,
    /// The body that carries the tip (`None`: not known).
    pub carrier: Option<Carrier>,
    /// The candidates limited in time, with their training windows.
    pub windows: Windows,
    /// Whether link inertial corrections were candidates.
    pub with_links: bool,
    /// How link corrections that leave no physical body were treated.
    pub held_links: HeldLinks,
}

/// The single-effect ranking of `fitted` on training record `p` (the
/// held-out record `h` adding its evidence where the ranking asks it) and
/// the compound explanation over every fitted term and, unless
/// `options.kinds` leaves them out, every link's inertial correction.
pub fn select<R: Robot<N> + Clone + Sync, const N: usize>(
    robot: &R,
    p: &Prepared<N>,
    h: &Prepared<N>,
    fitted: Fitted,
    options: &Options,
) -> Selection {
    let with_links =
        options.kinds.is_empty() || options.kinds.contains(&EffectKind::InertialParameters);
    let mut nominal = vec![SVector::<f64, 10>::zeros(); R::LINK_NAMES.len()];
    if robot.inertial_parameters(&mut nominal).is_err() {
        nominal.clear();
    }
    let carrier = Carrier::of(robot, &nominal);
    let Fitted { mut fits, windows } = fitted;
    let mut chosen = explained(
        robot,
        p,
        &fits,
        &windows,
        &nominal,
        carrier.as_ref(),
        with_links,
        options,
    );
    // The payload's second moments at the centre the explanation gives,
    // and the explanation chosen again (`recentre.rs`), its single fit
    // refitted there. A payload found in a time window keeps its fit: its
    // window was searched on the columns it has.
    for _ in 0..recentre::PASSES {
        let Some((was, now)) = recentre::recentred(&chosen.0, &chosen.1, carrier.as_ref()) else {
            break;
        };
        if window_of(&windows, was).is_some() {
            break;
        }
        for f in fits.iter_mut().filter(|f| f.candidate == was) {
            *f = fit::<R, N>(now, p);
        }
        chosen = explained(
            robot,
            p,
            &fits,
            &windows,
            &nominal,
            carrier.as_ref(),
            with_links,
            options,
        );
    }
    let (pool, explanation, held_links) = chosen;
    // A payload that would leave the tip's carrier no body is no single
    // effect either: the ranking is what the user reads beside the
    // explanation, which does not name it (`pool/carrier.rs`).
    let best = rank::rank(fits, p, h, &windows, options)
        .into_iter()
        .filter(|f| !payload_leaves_no_body(carrier.as_ref(), f.candidate, &f.theta, &f.std))
        .collect();
    Selection {
        best,
        pool,
        explanation,
        nominal,
        carrier,
        windows,
        with_links,
        held_links,
    }
}

/// The pool of `fits` (with the links' corrections unless `with_links`
/// is false), the compound explanation chosen over it, and how link
/// corrections without a body were treated: a nominal model whose
/// inertials are rough gets its explanation chosen again with the links
/// held to bodies (`rough.rs`).
#[allow(clippy::too_many_arguments)]
fn explained<R: Robot<N> + Clone + Sync, const N: usize>(
    robot: &R,
    p: &Prepared<N>,
    fits: &[Fit],
    windows: &Windows,
    nominal: &[SVector<f64, 10>],
    carrier: Option<&Carrier>,
    with_links: bool,
    options: &Options,
) -> (Pool, Explanation, HeldLinks) {
    let plinks = if with_links {
        regressor_columns(robot, p).unwrap_or_default()
    } else {
        vec![]
    };
    let mut pool = Pool::new(fits, windows, &plinks, nominal, p);
    // The pool holds the links' combinations: their columns are done.
    drop(plinks);
    let beside = BesideGravity::of(robot, p);
    let mut explanation =
        compound::explain::<R, N>(&mut pool, p, nominal, carrier, Some(&beside), options);
    let mut held_links = if options.hold_links {
        HeldLinks::Asked
    } else {
        HeldLinks::Judged
    };
    let rough = (!options.judge_links)
        .then(|| rough::rough(&pool, &explanation.left_out))
        .flatten();
    if let (HeldLinks::Judged, Some((links, of))) = (held_links, rough) {
        pool.restart();
        let held = Options {
            hold_links: true,
            ..options.clone()
        };
        explanation =
            compound::explain::<R, N>(&mut pool, p, nominal, carrier, Some(&beside), &held);
        held_links = HeldLinks::Rough { links, of };
    }
    (pool, explanation, held_links)
}

/// The held-out deviance of fit `f` on `h` (its parameters fitted on the
/// training record, not refitted; a windowed effect limited to the window
/// found on `h`): `n ln(sse / n)` of the whitened residual it leaves.
pub fn held_out_deviance<const N: usize>(f: &Fit, h: &Prepared<N>, windows: &Windows) -> f64 {
    let (hs, hn) = (h.sse_rows(&corrected_rows(f, h, windows)), h.n() as f64);
    hn * (hs.max(1e-300) / hn).ln()
}
