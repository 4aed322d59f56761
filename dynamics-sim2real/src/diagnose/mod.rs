//! Sim-to-real gap diagnosis: given a model and measured data, say WHERE
//! the model and the robot disagree (joint, time windows, motion phase),
//! WHICH unmodelled effect explains it (every candidate of the vocabulary
//! fitted and ranked by a corrected information criterion), and HOW FAR
//! the gap shrinks on held-out data once that effect is added.
//!
//! Method: the torque residual `tau - ID(q, qd, qdd)` along the measured
//! motion, every signal smoothed by one Savitzky-Golay filter (40 ms
//! half-width; accelerations from its derivative, never from double
//! differencing), rows whitened by the residual's noise floor: one draw of
//! the sensor noise (levels stated by the user, or estimated from the
//! data) pushed through the same smoothing and inverse dynamics.
//! Effects linear in their parameters (friction, rotor inertia, payload,
//! resistance, encoder offset through the emitted perturbation Jacobian K,
//! delay through the measured effort's rate) are fitted by sign-constrained
//! least squares on columns filtered like the efforts: friction laws are
//! evaluated on a lightly smoothed velocity and then filtered as the
//! residual shows a force the motion takes (`force_filter.rs`: the
//! acceleration estimate's filter on the force's integral; the sign of a
//! smoothed velocity switches sharply where the residual does not);
//! columns built from the acceleration estimate are smoothed once
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
mod compound;
mod eliminate;
mod error;
mod explain;
mod filter;
mod fit;
mod force_filter;
mod friction_table;
mod horizon;
mod late;
mod links;
mod motor;
mod motor_fit;
mod motor_sim;
mod noise;
mod options;
mod parallel;
mod pool;
mod prior;
mod rank;
mod refine;
mod report;
mod reversal;
mod segments;
mod shift;
mod shrink;
mod signals;
mod spread;
mod strength;
pub mod traces;
mod validate;
mod verdict;
mod visibility;
mod weights;
mod window;
mod windows;
mod words;
mod yardstick;

pub use analysis::{Fit, Prepared};
pub use candidate::Candidate;
pub use error::DiagnoseError;
pub use filter::SavitzkyGolay;
pub use fit::aicc;
pub use motor::MotorGuess;
pub use noise::SensorNoise;
pub use options::Options;
pub use report::*;
pub(crate) use signals::Signals;

use nalgebra::SVector;

use crate::data::{prepare, DataError, Measured};
use crate::effects::{EffectKind, Tip};
use crate::Warning;
use dynamics_runtime::Robot;

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
    Ok(())
}

/// `m` prepared (`data::prepare`) unless it is already.
fn prepared<'a, const N: usize>(
    m: &'a Measured<N>,
    which: &str,
) -> Result<std::borrow::Cow<'a, Measured<N>>, DataError> {
    Ok(if m.prepared {
        std::borrow::Cow::Borrowed(m)
    } else {
        std::borrow::Cow::Owned(prepare(m, which)?)
    })
}

/// Diagnoses the gap between `robot` and the measured `train` data, and
/// checks the chosen effect on `holdout`; `progress(done, total)` is called
/// as candidates are fitted.
///
/// ```
/// use dynamics_sim2real::diagnose::{diagnose, Options, Report};
/// use dynamics_runtime::Robot;
/// use dynamics_sim2real::data::Measured;
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
    // Data as recorded: repeats and glitches marked, a uniform grid, holes
    // (`data::prepare`; data read from a file come prepared already).
    let train = &*prepared(train, "training")?;
    let holdout = &*prepared(holdout, "held-out")?;
    check(train, "training")?;
    check(holdout, "held-out")?;
    let levels = options
        .noise
        .as_ref()
        .map(SensorNoise::per_joint::<N>)
        .transpose()?;
    let (p, h) = std::thread::scope(|s| {
        let h = s.spawn(|| Prepared::with_noise(robot, holdout, levels.as_ref()));
        let p = Prepared::with_noise(robot, train, levels.as_ref());
        (p, h.join())
    });
    let h = match h {
        Ok(h) => h,
        Err(e) => std::panic::resume_unwind(e),
    };
    let mut warnings: Vec<Warning> = train.warnings.clone();
    warnings.extend(holdout.warnings.iter().cloned());
    visibility::effort_sign(&p, &R::JOINT_NAMES, "training")?;
    visibility::effort_sign(&h, &R::JOINT_NAMES, "held-out")?;
    let excitation = visibility::excitation(&p, &R::JOINT_NAMES, &mut warnings)?;
    let n = p.n();
    let sse0 = p.sse(&p.sig.residual);
    let aicc0 = aicc(sse0, n, 0);
    let hsse0 = h.sse(&h.sig.residual);

    // Fit every candidate, on all cores.
    let mut candidates = visibility::identifiable(
        Candidate::all::<N>(&options.kinds),
        &excitation,
        p.sig.dt,
        &mut warnings,
    );
    // A late position stream, where the positions lag the measured velocities.
    late::offer(&mut candidates, train, &p, &mut warnings);
    let fits = parallel::fit_all::<R, N>(&candidates, &p, options.threads, progress);
    // Effects that start and stop: limited to the window the residual shows.
    let (fits, limited) = window::windowed(fits, &p, options);

    // The compound explanation over every fitted term.
    let with_links =
        options.kinds.is_empty() || options.kinds.contains(&EffectKind::InertialParameters);
    let (plinks, hlinks) = if with_links {
        (
            links::regressor_columns(robot, &p).unwrap_or_default(),
            links::regressor_columns(robot, &h).unwrap_or_default(),
        )
    } else {
        (vec![], vec![])
    };
    let mut nominal = vec![SVector::<f64, 10>::zeros(); R::LINK_NAMES.len()];
    if robot.inertial_parameters(&mut nominal).is_err() {
        nominal.clear();
    }
    let mut pool = pool::Pool::new(&fits, &plinks, &nominal, &p);
    window::limit_pool(&mut pool, &limited, &p);
    let explanation = compound::explain::<R, N>(&mut pool, &p, options);

    // Best grid variant per (kind, place), ranked by AICc, simpler nested
    // models first unless the richer one wins clearly (and, for a motor
    // side, unless the rotor alone leaves only noise); elasticity and
    // backlash at one joint, and Stribeck over Coulomb, also on the
    // held-out record's evidence (`rank::best_per_place`).
    let held_out = |f: &Fit| {
        let (hs, hn) = (h.sse(&window::corrected(f, &h, &limited)), h.n() as f64);
        hn * (hs.max(1e-300) / hn).ln()
    };
    let best = rank::best_per_place(
        fits,
        n,
        options.nesting_margin,
        &rank::Judge {
            quiet: &|f| rank::within_floor(f, &p, options.floor_ratio),
            held_out: &held_out,
        },
    );
    let tip_name = Tip::of::<R, N>().name::<R, N>().to_string();
    let excess = |sse: f64, sse0: f64, n: usize| -> f64 {
        let gap0 = (sse0 - n as f64).max(1e-12);
        ((sse0 - sse) / gap0).clamp(0.0, 1.0)
    };
    let ranked: Vec<Ranked> = best
        .iter()
        .map(|f| {
            let hs = h.sse(&window::corrected(f, &h, &limited));
            rank::ranked_entry::<R, N>(
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
    let gap = (0..N)
        .map(|j| rms(&p, &p.sig.residual, j) / p.sig.floor[j])
        .fold(0.0, f64::max);
    let mut verdict = verdict::verdict(&ranked, gap, options);

    // Where (training data, nominal model).
    let pred = horizon::prediction_error(robot, &p, &[])
        .map_err(|reason| {
            warnings.push(Warning::SimulationNotMade {
                model: "the nominal model (training data)".into(),
                reason,
            })
        })
        .ok();
    let q_noise = yardstick::prediction_floor(robot, train, &p);
    let joints = (0..N)
        .map(|j| {
            let rms = rms(&p, &p.sig.residual, j);
            JointGap {
                joint: R::JOINT_NAMES[j].to_string(),
                torque_rms: rms,
                torque_noise: p.sig.floor[j],
                torque_ratio: rms / p.sig.floor[j],
                prediction_rms: pred.map(|x| x[j]),
                prediction_noise: q_noise[j],
                prediction_ratio: pred.map(|x| x[j] / q_noise[j]),
                windows: windows::windows(&p, &p.sig.residual, j, 3.0, 5),
            }
        })
        .collect();

    // The explanation's entries and how far it shrinks the gap (held-out
    // data).
    let mut hold = explain::Holdout::new(&h, &hlinks, &pool, &explanation);
    window::limit_holdout(&mut hold, &h, &pool, &explanation, &limited);
    let (mut effects, steps) = explain::entries::<R, N>(
        &pool,
        &explanation,
        &hold,
        &tip_name,
        aicc0,
        &nominal,
        &p.basis.friction,
    );
    words::add_spring_words(&mut effects, &R::JOINT_NAMES, &excitation.range);
    words::add_encoder_words(&mut effects, &R::JOINT_NAMES, &R::JOINT_KINDS);
    window::annotate(&mut effects, &pool, &explanation, &limited);
    // A late effort stream, or a late motion whose channel is unresolved.
    late::warn(
        train.qd_measured,
        &effects,
        &verdict,
        &ranked,
        &mut warnings,
    );
    // Coulomb friction or an effort offset where a velocity never reverses.
    reversal::mark(
        &mut verdict,
        &mut effects,
        &ranked,
        &R::JOINT_NAMES,
        &excitation,
    );
    let all: Vec<usize> = (0..explanation.set.len()).collect();
    let r = hold.residual(&all, &explanation.sol.theta);
    let rms_fraction = explain::fraction(hold.plain(&hold_y(&hold)), hold.plain(&r));
    let after = (!explanation.set.is_empty()).then(|| {
        let mut v = vec![SVector::<f64, N>::zeros(); h.sig.t.len()];
        for (i, &k) in h.rows.iter().enumerate() {
            for j in 0..N {
                v[k][j] = r[i * N + j] * h.sig.floor[j];
            }
        }
        v
    });
    let shrink = shrink::shrink(
        robot,
        holdout,
        &h,
        after,
        &explain::effects(&pool, &explanation, &p.basis.friction),
        rms_fraction,
        steps,
        &mut warnings,
    );
    Ok(Report {
        robot: R::NAME.to_string(),
        samples: [train.len(), holdout.len()],
        where_: Where { joints },
        which: Which {
            ranked,
            verdict,
            friction: friction_table::friction_table(
                &R::JOINT_NAMES,
                &p.basis.friction.0,
                &p.basis.friction.1,
                &effects,
            ),
            effects,
        },
        shrink,
        warnings,
    })
}

/// The nominal model's whitened held-out residual.
fn hold_y<const N: usize>(hold: &explain::Holdout<N>) -> nalgebra::DVector<f64> {
    hold.residual(&[], &[])
}

/// RMS of joint `j` of `r` over the rows in use.
fn rms<const N: usize>(p: &Prepared<N>, r: &[SVector<f64, N>], j: usize) -> f64 {
    let s: f64 = p.rows.iter().map(|&k| r[k][j].powi(2)).sum();
    (s / p.rows.len().max(1) as f64).sqrt()
}
