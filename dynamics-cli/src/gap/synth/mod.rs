//! Synthetic measured data of one robot: the request ([`SynthRequest`]),
//! how the sensors record ([`Recording`]), and the training and held-out
//! CSVs with the truth ([`synth`]); the robot's home pose and amplitudes
//! come with it ([`Motion`]). The effect drawn is in `effect.rs`, the truth
//! file in `truth.rs`.

mod effect;
mod truth;

pub use truth::{holdout_window, Truth, TruthWindow};

use dynamics_runtime::Robot;
use dynamics_sim2real::data::{write_csv, Measured};
use dynamics_sim2real::effects::{Effect, EffectKind, PlaceKind, Tip, Window};
use dynamics_sim2real::synth::{
    synthesize, synthesize_with_size, Damage, Excitation, ExcitationKind, Noise, Rng, SynthOptions,
};
use nalgebra::SVector;

use super::GapError;
use effect::effect_for;

/// A synthesis request.
#[derive(Debug, Clone, PartialEq)]
pub struct SynthRequest {
    /// Robot name.
    pub robot: String,
    /// Effect kind, or `None` to draw one at random.
    pub kind: Option<EffectKind>,
    /// Joint name (joint effects), or `None` to draw.
    pub joint: Option<String>,
    /// Magnitude in the effect's main unit (see `dynamics synth --help`), or
    /// `None` to draw from the realistic range.
    pub magnitude: Option<f64>,
    /// Seed.
    pub seed: u64,
    /// Excitation.
    pub excitation: ExcitationKind,
    /// Duration, s.
    pub duration: f64,
    /// Noise.
    pub noise: Noise,
}

/// Home pose and reference amplitude of a robot's motion (the motion must
/// stay inside its joint limits); a robot without one moves by 0.4 about
/// zero.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Motion {
    /// Home pose, one value per joint (missing entries: 0).
    pub home: Vec<f64>,
    /// Reference amplitude per joint (missing entries: 0.4).
    pub amplitude: Vec<f64>,
}

/// How the sensors record: the sample rate and what real logs carry
/// (`dynamics synth --rate --jitter --repeats --holes --glitches
/// --q-late --tau-late`).
///
/// ```
/// use dynamics_cli::gap::Recording;
/// let r = Recording::default();
/// assert_eq!(r.rate, 1000.0);
/// assert!(!r.damage.any());
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Recording {
    /// Sample rate, Hz.
    pub rate: f64,
    /// Damage to the log.
    pub damage: Damage,
    /// When the withheld effect is on in the training run (`None`: all
    /// the time); the held-out run has it moved earlier by a quarter of its
    /// start (see [`holdout_window`]). Not for motor sides or a delay.
    pub window: Option<Window>,
}

impl Default for Recording {
    fn default() -> Self {
        Recording {
            rate: 1000.0,
            damage: Damage::default(),
            window: None,
        }
    }
}

fn options<const N: usize>(
    motion: &Motion,
    req: &SynthRequest,
    seed: u64,
    rec: &Recording,
) -> SynthOptions<N> {
    let (home, amp) = (&motion.home, &motion.amplitude);
    SynthOptions {
        rate: rec.rate,
        damage: rec.damage,
        duration: req.duration,
        excitation: req.excitation,
        home: SVector::from_fn(|i, _| home.get(i).copied().unwrap_or(0.0)),
        amplitude: SVector::from_fn(|i, _| amp.get(i).copied().unwrap_or(0.4)),
        noise: req.noise,
        seed,
        ..Default::default()
    }
}

/// A training and a held-out data set (different seeds and references,
/// same withheld effect) and the truth.
#[derive(Debug, Clone)]
pub struct SynthOutput {
    /// Training CSV text.
    pub train: String,
    /// Held-out CSV text.
    pub holdout: String,
    /// What was withheld.
    pub truth: Truth,
}

/// Generates data of `robot` moving about `motion` for `req` (training
/// with `req.seed`, held-out with the next seed).
///
/// ```
/// use dynamics_sim2real::effects::EffectKind;
/// use dynamics_cli::gap::{synth, Motion, SynthRequest};
/// dynamics_macros::robot! {
///     robot Arm; gravity = [0.0, -9.81, 0.0];
///     link base; link a { mass = 1.0; com = [0.2, 0.0, 0.0]; inertia = [1e-3, 1e-2, 1e-2]; }
///     link b { mass = 0.5; com = [0.15, 0.0, 0.0]; inertia = [1e-3, 5e-3, 5e-3]; }
///     joint j1 = revolute(base -> a) { transfer = [rot_z(q)]; }
///     joint j2 = revolute(a -> b) { transfer = [tu(0.4), rot_z(q)]; }
/// }
/// let out = synth(&Arm::default(), &Motion::default(), &SynthRequest {
///     robot: "arm".into(), kind: Some(EffectKind::ViscousFriction), joint: Some("j2".into()),
///     magnitude: Some(0.5), seed: 3, excitation: "sines".parse().unwrap(), duration: 0.5,
///     noise: Default::default(),
/// }).unwrap();
/// assert!(out.train.starts_with("t,q_j1,q_j2,qd_j1"));
/// assert_eq!(out.truth.kind, "viscous_friction");
/// ```
pub fn synth<R: Robot<N> + Clone, const N: usize>(
    robot: &R,
    motion: &Motion,
    req: &SynthRequest,
) -> Result<SynthOutput, GapError> {
    synth_recorded(robot, motion, req, &Recording::default())
}

/// [`synth`] with the sensors recording as `rec` says (rate, damage).
pub fn synth_recorded<R: Robot<N> + Clone, const N: usize>(
    robot: &R,
    motion: &Motion,
    req: &SynthRequest,
    rec: &Recording,
) -> Result<SynthOutput, GapError> {
    synth_following(robot, motion, req, rec, None)
}

/// [`synth_recorded`] with the training run following `reference` when
/// given (a designed motion, [`Excitation::designed`], or a motion file's
/// samples): the drawn effect's size is measured against that motion. The
/// held-out run follows a motion drawn of `req.excitation` with the next
/// seed, as without it: the fit is checked on a motion it was not made on.
///
/// ```
/// use dynamics_cli::gap::{synth_following, Motion, Recording, SynthRequest};
/// use dynamics_sim2real::{excite::Fourier, synth::Excitation};
/// dynamics_macros::robot! {
///     robot Arm; gravity = [0.0, -9.81, 0.0];
///     link base; link a { mass = 1.0; com = [0.2, 0.0, 0.0]; inertia = [1e-3, 1e-2, 1e-2]; }
///     joint j1 = revolute(base -> a) { transfer = [rot_z(q)]; }
/// }
/// let mut f = Fourier::<1>::new([0.3].into(), 1.0, 3);
/// f.sin[0][0] = 0.2;
/// f.to_rest();
/// let req = SynthRequest {
///     robot: "arm".into(), kind: None, joint: None, magnitude: None, seed: 3,
///     excitation: "sines".parse().unwrap(), duration: 1.0, noise: Default::default(),
/// };
/// let out = synth_following(&Arm::default(), &Motion::default(), &req, &Recording::default(),
///     Some(&Excitation::designed(f))).unwrap();
/// let second = out.train.lines().nth(1).unwrap(); // t = 0: at rest at q0 (+ noise)
/// let q: f64 = second.split(',').nth(1).unwrap().parse().unwrap();
/// assert!((q - 0.3).abs() < 1e-3);
/// assert_eq!(out.truth.excitation, "designed");
/// ```
pub fn synth_following<R: Robot<N> + Clone, const N: usize>(
    robot: &R,
    motion: &Motion,
    req: &SynthRequest,
    rec: &Recording,
    reference: Option<&Excitation<N>>,
) -> Result<SynthOutput, GapError> {
    if !(rec.rate.is_finite() && rec.rate >= 50.0) {
        return Err(GapError::Request(format!(
            "rate must be at least 50 Hz, got {}",
            rec.rate
        )));
    }
    if !(req.duration.is_finite() && req.duration >= 0.5) {
        return Err(GapError::Request(format!(
            "duration must be at least 0.5 s, got {}",
            req.duration
        )));
    }
    for (name, late) in [
        ("q-late", rec.damage.q_late),
        ("tau-late", rec.damage.tau_late),
    ] {
        if !(late.is_finite() && late >= 0.0 && late < req.duration) {
            return Err(GapError::Request(format!(
                "{name} must be a delay of at least 0 s, shorter than the record ({} s), got {late}",
                req.duration
            )));
        }
    }
    let mut rng = Rng::new(req.seed.wrapping_mul(0x9E37_79B9).wrapping_add(17));
    let mut train_opts = options::<N>(motion, req, req.seed, rec);
    train_opts.motion = reference.cloned();
    let effect = effect_for(robot, req, &train_opts, &mut rng)?;
    let effects: Vec<Effect> = effect.into_iter().collect();
    let mut hold_opts = options::<N>(motion, req, req.seed.wrapping_add(1_000_003), rec);
    if let Some(w) = rec.window {
        if effect.is_none() {
            return Err(GapError::Request(
                "a window needs an effect to limit (--effect)".into(),
            ));
        }
        if w.start >= req.duration {
            return Err(GapError::Request(format!(
                "window [{}, {}) starts after the record's end ({} s)",
                w.start, w.end, req.duration
            )));
        }
        train_opts.windows = vec![Some(w)];
        hold_opts.windows = vec![Some(holdout_window(w))];
    }
    let to_csv = |m: &Measured<N>| -> String {
        let mut out = Vec::new();
        let _ = write_csv(&mut out, m, &R::JOINT_NAMES);
        String::from_utf8(out).unwrap_or_default()
    };
    let sized = synthesize_with_size(robot, &effects, &train_opts)?;
    let (snr, distinct_snr) = (sized.snr(), sized.distinct_snr());
    let noise_tau = sized.noise_sigma.iter().copied().collect();
    let train = sized.data;
    let holdout = synthesize(robot, &effects, &hold_opts)?;
    let kind = effect.map(|e| e.kind()).unwrap_or(EffectKind::None);
    let tip = Tip::of::<R, N>().name::<R, N>().to_string();
    Ok(SynthOutput {
        train: to_csv(&train),
        holdout: to_csv(&holdout),
        truth: Truth {
            robot: req.robot.clone(),
            kind: kind.name().to_string(),
            joint: effect
                .and_then(|e| e.joint())
                .map(|j| R::JOINT_NAMES[j].to_string()),
            point: (kind.place() == PlaceKind::Point).then_some(tip),
            effect: effect
                .map(|e| format!("{e:?}"))
                .unwrap_or_else(|| "none".into()),
            seed: req.seed,
            excitation: match reference {
                Some(_) => "designed".into(),
                None => format!("{:?}", req.excitation),
            },
            snr,
            distinct_snr,
            noise_tau,
            window: rec.window.map(|w| TruthWindow::of(w, req.duration)),
            holdout_window: rec
                .window
                .map(|w| TruthWindow::of(holdout_window(w), req.duration)),
            late: if rec.damage.q_late > 0.0 {
                Some("positions".into())
            } else if rec.damage.tau_late > 0.0 {
                Some("effort".into())
            } else if kind == EffectKind::TimeDelay {
                Some("all".into())
            } else {
                None
            },
        },
    })
}
