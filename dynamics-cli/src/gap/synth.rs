//! Synthetic measured data of one robot: the effect a request asks for
//! (drawn where it leaves things open), the training and held-out CSVs and
//! the truth; the robot's home pose and amplitudes come with it
//! ([`Motion`]).

use dynamics_runtime::Robot;
use dynamics_sim2real::data::{write_csv, Measured};
use dynamics_sim2real::effects::{Effect, EffectKind, PlaceKind, Tip, Window};
use dynamics_sim2real::synth::{
    draw_effect, synthesize, synthesize_with_size, Damage, Excitation, ExcitationKind, Noise, Rng,
    Scales, SynthOptions,
};
use nalgebra::SVector;
use serde::{Deserialize, Serialize};

use super::GapError;

/// What was withheld in a synthetic data set (the truth file).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Truth {
    /// Robot name.
    pub robot: String,
    /// Effect kind (`none` for a control).
    pub kind: String,
    /// Joint name, for joint effects.
    pub joint: Option<String>,
    /// Point, for tip effects.
    pub point: Option<String>,
    /// The effect's parameters (Rust debug form).
    pub effect: String,
    /// Random seed.
    pub seed: u64,
    /// Excitation.
    pub excitation: String,
    /// How large the withheld effect is against the effort noise, from the
    /// truth side (computed by the generator, never by the diagnoser): the
    /// largest over the joints of the RMS, along the recorded training
    /// motion, of the effort the nominal model misses on noise-free data,
    /// over the standard deviation of one sample's effort noise.
    /// `synth::Synthesized::snr`; about 0 for a control.
    #[serde(default)]
    pub snr: f64,
    /// The same ratio for the part of the effect a rigid rotor inertia
    /// does not explain (`synth::Synthesized::distinct_snr`): what tells
    /// elasticity and backlash from `armature`, which they contain; equal
    /// to `snr` for the other effects.
    #[serde(default)]
    pub distinct_snr: f64,
    /// The effort noise the training data were recorded with, per-sample
    /// standard deviation per joint (N m or N): what `dynamics diagnose
    /// --noise-tau` would be told by a user who knows the sensors.
    #[serde(default)]
    pub noise_tau: Vec<f64>,
    /// When the effect is on in the training data (absent: all the time).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub window: Option<TruthWindow>,
    /// When it is on in the held-out data.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub holdout_window: Option<TruthWindow>,
    /// The late channel (`positions`: the position stream late against
    /// velocity and effort, `synth --q-late`; `effort`: the effort late
    /// against position and velocity, `synth --tau-late`; `all`: positions
    /// and velocities late together against the effort, the `time_delay`
    /// effect); absent when nothing is late.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub late: Option<String>,
}

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

/// The held-out run's window for a training window `w`: moved earlier by a
/// quarter of its start (an encoder that slips at 4 s in training slips at
/// 3 s there), so that a diagnosis that copied the training window's times
/// would miss it.
///
/// ```
/// use dynamics_cli::gap::holdout_window;
/// let w = holdout_window("4:6".parse().unwrap());
/// assert_eq!((w.start, w.end), (3.0, 5.0));
/// ```
pub fn holdout_window(w: Window) -> Window {
    w.shifted(-0.25 * w.start)
}

/// A window as the truth file records it (an open end: the record's end).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct TruthWindow {
    /// Start, s from the record's first sample.
    pub start: f64,
    /// End, s.
    pub end: f64,
}

impl TruthWindow {
    fn of(w: Window, duration: f64) -> Self {
        let w = w.clipped(duration);
        TruthWindow {
            start: w.start,
            end: w.end,
        }
    }
}

/// Largest ratio of a joint's locked to free inertia at which a drawn
/// rotor (armature, or the motor side of elasticity and backlash: 5-30 %
/// of the locked inertia) may sit there. arm3r's joints reach 12, the rrp
/// arm's q1 and q2 about 70.
const MOTOR_RATIO: f64 = 15.0;

/// The effect a request asks for (drawn where it leaves things open).
fn effect_for<R: Robot<N>, const N: usize>(
    robot: &R,
    req: &SynthRequest,
    opts: &SynthOptions<N>,
    rng: &mut Rng,
) -> Result<Option<Effect>, GapError> {
    let kind = match req.kind {
        Some(k) => k,
        None => EffectKind::ALL[1 + rng.below(EffectKind::ALL.len() - 1)],
    };
    let reference = Excitation::new(
        opts.excitation,
        opts.home,
        opts.amplitude,
        opts.duration,
        &mut Rng::new(opts.seed),
    );
    let scales = Scales::of(robot, &reference, opts.duration);
    let joint = match &req.joint {
        Some(name) => R::joint_index(name).ok_or_else(|| {
            GapError::Request(format!(
                "robot `{}` has no joint `{name}` (joints: {})",
                req.robot,
                R::JOINT_NAMES.join(", ")
            ))
        })?,
        None => {
            // A rotor (armature, motor side: a share of the joint's locked
            // inertia, see `draw_effect`) only where the controller can
            // carry it: see MOTOR_RATIO. (On the rrp arm, a 10 kg point
            // load on links of a few hundredths of a kg m^2, q1 and q2 move
            // 70 times more inertia locked than free: a rotor there leaves
            // their light direction almost without stiffness under the
            // nominal computed-torque loop, and the run drifts off.)
            let motor = matches!(
                kind,
                EffectKind::Armature | EffectKind::JointElasticity | EffectKind::Backlash
            );
            let carried: Vec<usize> = (0..N)
                .filter(|&j| !motor || scales.inertia[j] <= MOTOR_RATIO * scales.free_inertia[j])
                .collect();
            let carried = if carried.is_empty() {
                (0..N).collect()
            } else {
                carried
            };
            // Angle-based magnitudes (backlash, offsets) go to revolute joints.
            let revolute: Vec<usize> = carried
                .iter()
                .copied()
                .filter(|&j| R::JOINT_KINDS[j] == dynamics_runtime::JointKind::Revolute)
                .collect();
            let pool: Vec<usize> = if revolute.is_empty() {
                carried
            } else {
                revolute
            };
            pool[rng.below(pool.len())]
        }
    };
    let tip = Tip::of::<R, N>();
    let tip_speed = (0..=200)
        .map(|k| {
            let r = reference.at(opts.duration * k as f64 / 200.0);
            (tip.position_jacobian(robot, &r.q).1 * r.qd).norm()
        })
        .fold(0.0, f64::max);
    let drawn = draw_effect(kind, joint, &scales, &R::JOINT_KINDS, tip_speed, rng);
    let Some(m) = req.magnitude else {
        return Ok(drawn);
    };
    if !m.is_finite() {
        return Err(GapError::Request(format!(
            "magnitude must be finite, got {m}"
        )));
    }
    Ok(drawn.map(|e| match e {
        Effect::CoulombFriction { joint, vw, .. } => Effect::CoulombFriction { joint, fc: m, vw },
        Effect::ViscousFriction { joint, .. } => Effect::ViscousFriction { joint, fv: m },
        Effect::StribeckFriction { joint, .. } => Effect::StribeckFriction {
            joint,
            fc: m,
            fs: 1.5 * m,
            vs: 0.05,
        },
        Effect::Armature { joint, .. } => Effect::Armature { joint, inertia: m },
        // The magnitude is the mass change (never drawn here yet).
        Effect::InertialParameters { link, mut delta } => {
            delta[0] = m;
            Effect::InertialParameters { link, delta }
        }
        Effect::PayloadMass { .. } => Effect::PayloadMass { mass: m },
        Effect::JointElasticity {
            joint,
            motor_inertia,
            ..
        } => {
            let inertia = scales.free_inertia[joint];
            let w = 2.0 * std::f64::consts::PI * m;
            let stiffness = w * w / (1.0 / motor_inertia + 1.0 / inertia);
            Effect::JointElasticity {
                joint,
                stiffness,
                damping: 0.1 * (stiffness * motor_inertia).sqrt(),
                motor_inertia,
            }
        }
        Effect::Backlash {
            joint,
            motor_inertia,
            contact_stiffness,
            contact_damping,
            ..
        } => Effect::Backlash {
            joint,
            half_width: m,
            motor_inertia,
            contact_stiffness,
            contact_damping,
        },
        Effect::EnvironmentResistance { .. } => Effect::EnvironmentResistance { mu: m, alpha: 2.0 },
        Effect::EncoderOffset { joint, .. } => Effect::EncoderOffset { joint, offset: m },
        Effect::TimeDelay { .. } => Effect::TimeDelay { delay: m },
        Effect::EffortScale { joint, .. } => Effect::EffortScale { joint, scale: m },
        Effect::EffortOffset { joint, .. } => Effect::EffortOffset { joint, offset: m },
    }))
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
            excitation: format!("{:?}", req.excitation),
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
