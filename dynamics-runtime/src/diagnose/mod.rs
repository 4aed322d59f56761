//! Sim-to-real gap diagnosis: given a model and measured data, say WHERE
//! the model and the robot disagree (joint, time windows, motion phase),
//! WHICH unmodelled effect explains it (every candidate of the vocabulary
//! fitted and ranked by a corrected information criterion), and HOW FAR
//! the gap shrinks on held-out data once that effect is added.
//!
//! Method: the torque residual `tau - ID(q, qd, qdd)` along the measured
//! motion, every signal smoothed by one Savitzky-Golay filter (40 ms
//! half-width; accelerations from its derivative, never from double
//! differencing), rows whitened by a noise floor estimated from the data.
//! Effects linear in their parameters (friction, rotor inertia, payload,
//! resistance, encoder offset through the emitted perturbation Jacobian K,
//! delay through the model effort's rate) are fitted by sign-constrained
//! least squares on columns filtered like the efforts: friction laws are
//! evaluated on a lightly smoothed velocity and then smoothed (the sign of
//! a smoothed velocity switches sharply where the smoothed effort does
//! not); columns built from the acceleration estimate are smoothed once
//! more, so that they do not add its noise a second time (rotor inertia
//! was otherwise taken for a stiff elastic joint). Elasticity and backlash
//! are fitted by a grid search on a motor-side simulation driven by the
//! measured effort (its link following the measured motion plus the
//! effect of the transmitted effort's departure from the model), refined by a compass search on the logarithms of their
//! parameters; their standard deviations come from the objective's
//! curvature there (`spread`). Rotor inertia is fitted both ways (its acceleration column,
//! and a rotor on a very stiff coupling simulated like the motor-side
//! models, which see the effort's fast content the same way) and keeps the
//! better. Candidates are ranked by AICc; a richer model nesting a
//! simpler one at the same joint (Stribeck over Coulomb, elasticity or
//! backlash over rotor inertia) must win by [`Options::nesting_margin`].

mod analysis;
mod basis;
mod candidate;
mod filter;
mod fit;
mod horizon;
mod refine;
mod report;
mod signals;
mod spread;
pub mod traces;
mod windows;
mod yardstick;

pub use analysis::{Fit, Prepared};
pub use candidate::{Candidate, MotorGuess};
pub use filter::SavitzkyGolay;
pub use fit::aicc;
pub use report::*;

use std::sync::atomic::{AtomicUsize, Ordering};

use nalgebra::SVector;
use thiserror::Error;

use crate::data::Measured;
use crate::effects::{EffectKind, Tip};
use crate::Robot;
use signals::robust_std;

/// Options of [`diagnose`].
#[derive(Debug, Clone, PartialEq)]
pub struct Options {
    /// Candidate kinds (empty: all).
    pub kinds: Vec<EffectKind>,
    /// AICc improvement over the nominal model below which the verdict is
    /// `none`.
    pub none_margin: f64,
    /// AICc difference under which two candidates are `ambiguous`.
    pub ambiguity_margin: f64,
    /// When no candidate qualifies, the verdict is `unexplained` rather than
    /// `none` if some joint's torque residual RMS is at least this many
    /// times its noise floor: the gap is real, the candidates miss it.
    pub unexplained_ratio: f64,
    /// AICc improvement a richer nested model must add over the simpler one
    /// it contains to be preferred (10: "strong evidence" on the usual
    /// scale of AIC differences).
    pub nesting_margin: f64,
    /// Threads (0: all cores).
    pub threads: usize,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            kinds: vec![],
            none_margin: 100.0,
            ambiguity_margin: 10.0,
            unexplained_ratio: 3.0,
            nesting_margin: 10.0,
            threads: 0,
        }
    }
}

/// Why a diagnosis could not run.
#[derive(Debug, Error)]
pub enum DiagnoseError {
    /// A data set is too short for the filter.
    #[error(
        "{which} data: {samples} samples over {duration:.3} s are too few (need at least {need})"
    )]
    TooShort {
        /// `training` or `held-out`.
        which: &'static str,
        /// Samples.
        samples: usize,
        /// Duration.
        duration: f64,
        /// Samples needed.
        need: usize,
    },
    /// The sample interval is not uniform enough.
    #[error("{which} data: the sample interval varies from {min:e} to {max:e} s; resample to a fixed rate")]
    Irregular {
        /// `training` or `held-out`.
        which: &'static str,
        /// Smallest interval.
        min: f64,
        /// Largest.
        max: f64,
    },
}

fn check<const N: usize>(m: &Measured<N>, which: &'static str) -> Result<(), DiagnoseError> {
    let need = 200;
    if m.len() < need {
        return Err(DiagnoseError::TooShort {
            which,
            samples: m.len(),
            duration: m.duration(),
            need,
        });
    }
    let (mut min, mut max) = (f64::INFINITY, 0.0f64);
    for w in m.t.windows(2) {
        min = min.min(w[1] - w[0]);
        max = max.max(w[1] - w[0]);
    }
    if max > 1.5 * min {
        return Err(DiagnoseError::Irregular { which, min, max });
    }
    Ok(())
}

/// Diagnoses the gap between `robot` and the measured `train` data, and
/// checks the chosen effect on `holdout`; `progress(done, total)` is called
/// as candidates are fitted.
///
/// ```
/// use dynamics_runtime::diagnose::{diagnose, Options, Report};
/// use dynamics_runtime::{data::Measured, Robot};
/// fn run<R: Robot<3> + Clone + Sync>(robot: &R, train: &Measured<3>, holdout: &Measured<3>) -> Report {
///     diagnose(robot, train, holdout, &Options::default(), &|_, _| {}).expect("enough data")
/// }
/// ```
pub fn diagnose<R: Robot<N> + Clone + Sync, const N: usize>(
    robot: &R,
    train: &Measured<N>,
    holdout: &Measured<N>,
    options: &Options,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<Report, DiagnoseError> {
    check(train, "training")?;
    check(holdout, "held-out")?;
    let (p, h) = std::thread::scope(|s| {
        let h = s.spawn(|| Prepared::new(robot, holdout));
        let p = Prepared::new(robot, train);
        (p, h.join())
    });
    let h = match h {
        Ok(h) => h,
        Err(e) => std::panic::resume_unwind(e),
    };
    let n = p.n();
    let sse0 = p.sse(&p.sig.residual);
    let aicc0 = aicc(sse0, n, 0);
    let hsse0 = h.sse(&h.sig.residual);

    // Fit every candidate, on all cores.
    let candidates = Candidate::all::<N>(&options.kinds);
    let total = candidates.len();
    let done = AtomicUsize::new(0);
    let threads = if options.threads == 0 {
        std::thread::available_parallelism()
            .map(|n| n.get())
            .unwrap_or(1)
    } else {
        options.threads
    };
    let chunk = total.div_ceil(threads.max(1)).max(1);
    let fits: Vec<Fit> = std::thread::scope(|s| {
        let handles: Vec<_> = candidates
            .chunks(chunk)
            .map(|cs| {
                let (p, done) = (&p, &done);
                s.spawn(move || {
                    cs.iter()
                        .map(|&c| {
                            let f = analysis::fit::<R, N>(c, p);
                            progress(done.fetch_add(1, Ordering::Relaxed) + 1, total);
                            f
                        })
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        handles
            .into_iter()
            .flat_map(|h| match h.join() {
                Ok(v) => v,
                Err(e) => std::panic::resume_unwind(e),
            })
            .collect()
    });

    // Best grid variant per (kind, place), ranked by AICc.
    let mut best: Vec<Fit> = Vec::new();
    for f in fits {
        let key = (f.candidate.kind(), f.candidate.joint());
        match best
            .iter_mut()
            .find(|b| (b.candidate.kind(), b.candidate.joint()) == key)
        {
            Some(b) if b.aicc(n) <= f.aicc(n) => {}
            Some(b) => *b = f,
            None => best.push(f),
        }
    }
    best.sort_by(|a, b| a.aicc(n).total_cmp(&b.aicc(n)));
    // Parsimony: a richer model that contains a simpler one at the same
    // joint (Stribeck contains Coulomb; elasticity and backlash contain a
    // rigid rotor) must beat it clearly, or the simpler one goes first.
    if best.len() > 1 {
        let top = best[0].candidate;
        let simpler = match top {
            Candidate::Stribeck(j, _) => Some(Candidate::Coulomb(j)),
            Candidate::Elasticity(j) | Candidate::Backlash(j) => Some(Candidate::Armature(j)),
            _ => None,
        };
        if let Some(s) = simpler {
            if let Some(i) = best.iter().position(|f| f.candidate == s) {
                let gain = best[i].aicc(n) - best[0].aicc(n);
                if gain < options.nesting_margin {
                    let f = best.remove(i);
                    best.insert(0, f);
                }
            }
        }
    }
    let tip_name = Tip::of::<R, N>().name::<R, N>().to_string();
    let excess = |sse: f64, sse0: f64, n: usize| -> f64 {
        let gap0 = (sse0 - n as f64).max(1e-12);
        ((sse0 - sse) / gap0).clamp(0.0, 1.0)
    };
    let ranked: Vec<Ranked> = best
        .iter()
        .map(|f| {
            let hs = h.sse(&f.corrected(&h));
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

    // Verdict.
    let verdict = match ranked.first() {
        Some(top) if top.delta_aicc >= options.none_margin && top.holdout_share > 0.0 => {
            let rival = ranked
                .iter()
                .skip(1)
                .find(|r| top.aicc - r.aicc > -options.ambiguity_margin);
            Verdict {
                kind: top.kind.clone(),
                joint: top.joint.clone(),
                point: top.point.clone(),
                status: if rival.is_some() {
                    "ambiguous"
                } else {
                    "clear"
                }
                .into(),
                separating_motion: rival.map(|r| separating_motion(&top.kind, &r.kind)),
                rival: rival.map(|r| Box::new(r.clone())),
            }
        }
        _ => {
            let gap = (0..N)
                .map(|j| rms(&p, &p.sig.residual, j) / p.sig.floor[j])
                .fold(0.0, f64::max);
            let word = if gap >= options.unexplained_ratio {
                "unexplained"
            } else {
                "none"
            };
            Verdict {
                kind: word.into(),
                joint: None,
                point: None,
                status: if word == "none" { "within_noise" } else { word }.into(),
                rival: None,
                separating_motion: None,
            }
        }
    };
    let chosen = if verdict.names_effect() {
        best.first()
    } else {
        None
    };

    // Where (training data, nominal model).
    let pred = horizon::prediction_error(robot, &p, None);
    let q_noise = yardstick::prediction_floor(robot, train, &p);
    let joints = (0..N)
        .map(|j| {
            let rms = rms(&p, &p.sig.residual, j);
            JointGap {
                joint: R::JOINT_NAMES[j].to_string(),
                torque_rms: rms,
                torque_noise: p.sig.floor[j],
                torque_ratio: rms / p.sig.floor[j],
                prediction_rms: pred[j],
                prediction_noise: q_noise[j],
                prediction_ratio: pred[j] / q_noise[j],
                windows: windows::windows(&p, &p.sig.residual, j, 3.0, 5),
            }
        })
        .collect();

    // How far it shrinks (held-out data).
    let after = chosen.map(|f| f.corrected(&h));
    let effect = chosen.and_then(|f| f.effect());
    let sim_before = horizon::prediction_error(robot, &h, None);
    let sim_after = match effect {
        Some(e) => horizon::prediction_error(robot, &h, Some(e)),
        None => sim_before,
    };
    let hq_noise = position_noise(holdout, &h);
    let mut gap = [0.0f64; 4];
    let shrink_joints = (0..N)
        .map(|j| {
            let before = rms(&h, &h.sig.residual, j);
            let aft = after.as_ref().map(|a| rms(&h, a, j)).unwrap_or(before);
            let above = |x: f64, floor: f64| (x * x - floor * floor).max(0.0).sqrt() / floor;
            gap[0] += above(before, h.sig.floor[j]).powi(2);
            gap[1] += above(aft, h.sig.floor[j]).powi(2);
            gap[2] += above(sim_before[j], hq_noise[j]).powi(2);
            gap[3] += above(sim_after[j], hq_noise[j]).powi(2);
            JointShrink {
                joint: R::JOINT_NAMES[j].to_string(),
                torque_before: before,
                torque_after: aft,
                simulation_before: sim_before[j],
                simulation_after: sim_after[j],
            }
        })
        .collect();
    let frac = |b: f64, a: f64| if b > 0.0 { 1.0 - (a / b).sqrt() } else { 0.0 };
    let torque_fraction = frac(gap[0], gap[1]);
    Ok(Report {
        robot: R::NAME.to_string(),
        samples: [train.len(), holdout.len()],
        where_: Where { joints },
        which: Which { ranked, verdict },
        shrink: Shrink {
            joints: shrink_joints,
            torque_fraction,
            simulation_fraction: frac(gap[2], gap[3]),
            fraction: torque_fraction,
        },
    })
}

fn rms<const N: usize>(p: &Prepared<N>, r: &[SVector<f64, N>], j: usize) -> f64 {
    let s: f64 = p.rows.iter().map(|&k| r[k][j].powi(2)).sum();
    (s / p.rows.len().max(1) as f64).sqrt()
}

/// Position noise per joint: robust spread of raw minus smoothed positions.
fn position_noise<const N: usize>(m: &Measured<N>, p: &Prepared<N>) -> SVector<f64, N> {
    let (a, z) = p.sig.range;
    SVector::from_fn(|j, _| {
        let d: Vec<f64> = (a..z).map(|k| m.q[k][j] - p.sig.q[k][j]).collect();
        robust_std(&d).max(1e-12)
    })
}

fn ranked_entry<R: Robot<N>, const N: usize>(
    f: &Fit,
    tip: &str,
    aicc0: f64,
    n: usize,
    share: f64,
    holdout_share: f64,
) -> Ranked {
    let c = f.candidate;
    let mut parameters: Vec<Parameter> = c
        .linear_parameters()
        .iter()
        .zip(f.theta.iter().zip(&f.std))
        .map(|((name, _), (v, s))| Parameter {
            name: name.to_string(),
            value: *v,
            std: *s,
        })
        .collect();
    match c {
        Candidate::Stribeck(_, vs) => parameters.push(Parameter {
            name: "vs".into(),
            value: vs,
            std: vs * 0.5,
        }),
        Candidate::Environment(alpha) => parameters.push(Parameter {
            name: "alpha".into(),
            value: alpha,
            std: 0.25,
        }),
        _ => {}
    }
    if let (Some(g), false) = (f.motor, matches!(c, Candidate::Armature(_))) {
        let mut push = |name: &str, value: f64, std: f64| {
            parameters.push(Parameter {
                name: name.into(),
                value,
                std,
            })
        };
        let sd = f.motor_std.unwrap_or(MotorGuess {
            jm: f64::INFINITY,
            stiffness: f64::INFINITY,
            damping: f64::INFINITY,
            half_width: f64::INFINITY,
        });
        push("motor_inertia", g.jm, sd.jm);
        if matches!(c, Candidate::Backlash(_)) {
            push("half_width", g.half_width, sd.half_width);
            push("contact_stiffness", g.stiffness, sd.stiffness);
        } else {
            push("stiffness", g.stiffness, sd.stiffness);
            push("damping", g.damping, sd.damping);
        }
    }
    let a = f.aicc(n);
    Ranked {
        kind: c.kind().name().to_string(),
        joint: c.joint().map(|j| R::JOINT_NAMES[j].to_string()),
        point: matches!(c, Candidate::Payload | Candidate::Environment(_)).then(|| tip.to_string()),
        parameters,
        share,
        aicc: a,
        delta_aicc: aicc0 - a,
        holdout_share,
    }
}

/// A motion that would tell `a` and `b` apart.
fn separating_motion(a: &str, b: &str) -> String {
    let pair = |x: &str, y: &str| (a == x && b == y) || (a == y && b == x);
    if pair("viscous_friction", "armature") {
        "decorrelate speed and acceleration: a chirp, or fast cruising at low acceleration followed by hard starts at low speed".into()
    } else if pair("coulomb_friction", "encoder_offset") || pair("payload_mass", "encoder_offset") {
        "hold still at several poses across the joint's range and reverse the velocity at different positions: gravity's dependence on the angle separates an offset from friction and mass".into()
    } else if pair("coulomb_friction", "stribeck_friction") {
        "slow velocity reversals (below 0.1 rad/s) where the breakaway level shows".into()
    } else if a == "joint_elasticity"
        || b == "joint_elasticity"
        || a == "backlash"
        || b == "backlash"
    {
        "quick effort reversals and steps at the joint, so that the motor side rings (elasticity) or crosses its gap (backlash)".into()
    } else {
        "a richer excitation: a chirp up to 5 Hz, slow reversals and holds at several poses".into()
    }
}
