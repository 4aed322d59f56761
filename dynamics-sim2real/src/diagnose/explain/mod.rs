//! Explanation: the report, in the user's words. The only stage that knows
//! the report's schema (`report.rs`) and writes kinds, statuses and
//! channels as strings.
//!
//! - `report.rs`: the report's types (serialised as the JSON schema);
//! - `entries.rs`: the compound explanation's entries and the held-out
//!   steps;
//! - `ranked.rs`: the single-effect ranking's entries;
//! - `determinacy.rs`: values the data do not determine, or that are not
//!   physical, reported as the reason instead of a number;
//! - `verdict.rs`: the verdict on the best single effect;
//! - `words.rs`, `friction_table.rs`: joint effects and friction in words
//!   and as a table;
//! - `late.rs`, `reversal.rs`: warnings and ambiguities the data leave;
//! - `inseparable.rs`: ambiguous pairs no motion separates (one base
//!   parameter), said so instead of a separating motion.

mod determinacy;
mod entries;
mod friction_table;
mod inseparable;
mod late;
mod ranked;
pub mod report;
mod reversal;
mod verdict;
mod words;

pub use entries::{annotate, entries, suggested};
pub use friction_table::friction_table;
pub use inseparable::mark_inseparable;
pub use late::warn_delays;
pub use ranked::ranked_entry;
pub use reversal::mark_reversals;
pub use verdict::verdict;
pub use words::{add_encoder_words, add_payload_words, add_placement_words, add_spring_words};

use crate::diagnose::candidates::Records;
use crate::diagnose::evaluate::Evaluation;
use crate::diagnose::fit::corrected_rows;
use crate::diagnose::numeric::aicc;
use crate::diagnose::select::{HeldLinks, Selection};
use crate::diagnose::Options;
use crate::effects::Tip;
use dynamics_runtime::Robot;
use nalgebra::SVector;
use rayon::prelude::*;
use report::{JointGap, JointShrink, Ranked, Report, Shrink, Where, Which};

/// The joints beyond which no joint moves: the frames a later joint
/// moves are none of those the joint moves (in the depth-first order of
/// the coordinates, a later joint is beyond it or on another branch).
fn leaf_joints<R: Robot<N>, const N: usize>(robot: &R) -> [bool; N] {
    let q0 = SVector::<f64, N>::from_fn(|j, _| 0.3 + 0.37 * j as f64);
    let frames = R::FRAME_NAMES.len();
    let moves = |j: usize| -> Vec<bool> {
        let mut q = q0;
        q[j] += 1e-3;
        (0..frames)
            .map(
                |f| match (robot.frame_pose(f, &q0), robot.frame_pose(f, &q)) {
                    (Some(a), Some(b)) => (a - b).amax() > 1e-9,
                    _ => false,
                },
            )
            .collect()
    };
    let moved: Vec<Vec<bool>> = (0..N).map(moves).collect();
    std::array::from_fn(|j| {
        (j + 1..N).all(|k| !moved[k].iter().zip(&moved[j]).any(|(a, b)| *a && *b))
    })
}

/// The report of a diagnosis of `robot`: where the gap is, the ranking and verdict,
/// the explanation in words with its friction table, how far it shrinks
/// the gap; the warnings of every stage in the order of the data.
pub fn report<R: Robot<N>, const N: usize>(
    robot: &R,
    records: &Records<N>,
    selection: &Selection,
    evaluation: &Evaluation<N>,
    options: &Options,
) -> Report {
    let (p, h) = (&records.p, &records.h);
    let (pool, e) = (&selection.pool, &evaluation.confirmed.explanation);
    let tip_name = Tip::of::<R, N>().name::<R, N>().to_string();
    let n = p.n();
    let sse0 = p.sse(&p.sig.residual);
    let aicc0 = aicc(sse0, n, 0);
    let hsse0 = h.sse(&h.sig.residual);
    let excess = |sse: f64, sse0: f64, n: usize| -> f64 {
        let gap0 = (sse0 - n as f64).max(1e-12);
        ((sse0 - sse) / gap0).clamp(0.0, 1.0)
    };
    // (Each fit's held-out residual on the threads: a motor side's is a
    // simulation over the whole record.)
    let ranked: Vec<Ranked> = selection
        .best
        .par_iter()
        .map(|f| {
            let hs = h.sse_rows(&corrected_rows(f, h, &selection.windows));
            ranked_entry::<R, N>(
                f,
                &tip_name,
                aicc0,
                n,
                excess(f.sse, sse0, n),
                excess(hs, hsse0, h.n()),
            )
        })
        .collect();
    let excitation = &records.excitation;
    let joint_at = |name: &str| {
        let j = R::JOINT_NAMES.iter().position(|n| *n == name)?;
        let (lo, hi) = excitation.range[j];
        Some((R::JOINT_KINDS[j], hi - lo))
    };
    let mut ranked = ranked;
    determinacy::mark_ranked(&mut ranked, &joint_at);
    let mut verdict = verdict(&ranked, p.gap_ratio(), options);

    let joints = (0..N)
        .map(|j| {
            let rms = p.rms(&p.sig.residual, j);
            let pred = evaluation.prediction;
            let q_noise = evaluation.prediction_noise;
            JointGap {
                joint: R::JOINT_NAMES[j].to_string(),
                torque_rms: rms,
                torque_noise: p.sig.floor[j],
                torque_ratio: rms / p.sig.floor[j],
                prediction_rms: pred.map(|x| x[j]),
                prediction_noise: q_noise[j],
                prediction_ratio: pred.map(|x| x[j] / q_noise[j]),
                windows: evaluation.gap_windows[j].clone(),
            }
        })
        .collect();

    let (mut effects, steps) = entries::<R, N>(
        pool,
        e,
        &evaluation.hold,
        &tip_name,
        aicc0,
        &selection.nominal,
        &p.basis.friction,
        &evaluation.confirmed.confidence,
    );
    determinacy::mark_explained(&mut effects, &joint_at);
    let mut suggested = suggested::<R, N>(pool, &evaluation.confirmed.suggested, &tip_name);
    determinacy::mark_suggested(&mut suggested, &joint_at);
    add_spring_words(&mut effects, &R::JOINT_NAMES, &records.excitation.range);
    add_encoder_words(
        &mut effects,
        &R::JOINT_NAMES,
        &R::JOINT_KINDS,
        &leaf_joints(robot),
    );
    add_payload_words(&mut effects);
    add_placement_words(&mut effects, R::LINK_NAMES);
    annotate(&mut effects, pool, e);
    let mut warnings = records.warnings.clone();
    warnings.extend(evaluation.training_warnings.iter().cloned());
    if let HeldLinks::Rough { links, of } = selection.held_links {
        warnings.push(crate::Warning::RoughInertials { links, of });
    }
    if let Some((delay, interval)) = evaluation.confirmed.within_sample {
        warnings.push(crate::Warning::WithinSample { delay, interval });
    }
    // A late effort stream, or a late motion whose channel is unresolved.
    warn_delays(
        records.train.qd_measured,
        &effects,
        &verdict,
        &ranked,
        &mut warnings,
    );
    // Coulomb friction or an effort offset where a velocity never reverses.
    mark_reversals(
        &mut verdict,
        &mut effects,
        &ranked,
        &R::JOINT_NAMES,
        &records.excitation,
    );
    // Pairs no motion separates: said so, not sent to a motion.
    mark_inseparable(robot, &records.excitation.range, &mut verdict, &mut effects);
    warnings.extend(evaluation.held_out_warnings.iter().cloned());
    let s = &evaluation.shrink;
    let shrink = Shrink {
        joints: (0..N)
            .map(|j| {
                let f = &s.joints[j];
                JointShrink {
                    joint: R::JOINT_NAMES[j].to_string(),
                    torque_before: f.torque_before,
                    torque_after: f.torque_after,
                    simulation_before: f.simulation_before,
                    simulation_after: f.simulation_after,
                }
            })
            .collect(),
        torque_fraction: s.torque_fraction,
        simulation_fraction: s.simulation_fraction,
        fraction: s.torque_fraction,
        rms_fraction: evaluation.rms_fraction,
        steps,
    };
    Report {
        robot: R::NAME.to_string(),
        samples: [records.train.len(), records.holdout.len()],
        where_: Where { joints },
        which: Which {
            ranked,
            verdict,
            friction: friction_table(
                &R::JOINT_NAMES,
                &p.basis.friction.0,
                &p.basis.friction.1,
                &effects,
                &evaluation.friction_spread,
            ),
            effects,
            suggested,
        },
        shrink,
        warnings,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    dynamics_macros::robot! {
        robot Fork;
        gravity = [0.0, 0.0, -9.81];
        link base;
        link a { mass = 1.0; com = [0.2, 0.0, 0.0]; inertia = [1e-3, 1e-2, 1e-2]; }
        link b { mass = 1.0; com = [0.2, 0.0, 0.0]; inertia = [1e-3, 1e-2, 1e-2]; }
        link c { mass = 1.0; com = [0.2, 0.0, 0.0]; inertia = [1e-3, 1e-2, 1e-2]; }
        joint j1 = revolute(base -> a) { transfer = [rot_z(q)]; }
        joint j2 = revolute(a -> b) { transfer = [trans_x(0.4), rot_y(q)]; }
        joint j3 = revolute(a -> c) { transfer = [trans_x(0.4), rot_x(q)]; }
    }

    /// A fork: j1 carries both branches; j2 and j3 carry one body each,
    /// j3 coming after j2 in the coordinates but on another branch. In a
    /// chain only the last joint is one.
    #[test]
    fn a_joint_is_a_leaf_when_no_joint_moves_beyond_it() {
        assert_eq!(leaf_joints(&Fork::default()), [false, true, true]);
        let serial = crate::test_robots::Arm2::default();
        assert_eq!(leaf_joints(&serial), [false, true]);
    }
}
