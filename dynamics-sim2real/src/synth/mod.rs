//! Synthetic "measured" data with a withheld effect: the robot with the
//! effect attached follows an exciting reference under a computed-torque
//! controller built on the nominal model (which does not know the effect);
//! positions, velocities and efforts are recorded at a fixed rate with
//! sensor noise, sensor faults applied to what is measured.
//!
//! The controller is a cascade, as in a real drive: the position loop
//! closes on the link-side position that is recorded, the velocity
//! (damping) loop on the drive's own motor encoder. For a rigid joint the
//! two speeds are one; across a joint with a motor side (elasticity,
//! backlash) the damping acts where the torque is applied, which keeps the
//! loop stable without the controller knowing about the effect (a damping
//! loop closed across a lightly damped spring would not be).

mod compound;
mod damage;
mod draw;
mod excitation;
mod phases;
mod run;
mod sensors;

pub use crate::rng::Rng;
pub use compound::{draw_compound, CompoundCase, MOTOR_RATIO};
pub use damage::Damage;
pub use draw::{draw_effect, Scales};
pub use excitation::{Excitation, ExcitationKind};

use run::Run;

use nalgebra::SVector;
use thiserror::Error;

use crate::data::Measured;
use crate::effects::{Effect, PlantError};
use dynamics_runtime::Robot;

/// Sensor noise (standard deviations).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Noise {
    /// Position noise (rad or m).
    pub q: f64,
    /// Velocity noise (rad/s or m/s).
    pub qd: f64,
    /// Effort noise as a fraction of each joint's peak nominal effort.
    pub tau_relative: f64,
}

impl Default for Noise {
    /// 2e-5 rad (a 17-18 bit encoder), 2e-3 rad/s, 0.2 % of peak effort.
    fn default() -> Self {
        Noise {
            q: 2e-5,
            qd: 2e-3,
            tau_relative: 2e-3,
        }
    }
}

/// How to generate a data set.
#[derive(Debug, Clone, PartialEq)]
pub struct SynthOptions<const N: usize> {
    /// Length of the run, s.
    pub duration: f64,
    /// Sample rate, Hz.
    pub rate: f64,
    /// Reference motion kind (drawn with the seed; not used when `motion`
    /// is given).
    pub excitation: ExcitationKind,
    /// A reference given in full (a designed motion,
    /// [`Excitation::designed`], or samples of one,
    /// [`Excitation::samples`]): followed instead of one drawn of
    /// `excitation` about `home`; `None` (the default): drawn.
    pub motion: Option<Excitation<N>>,
    /// Pose the reference moves about.
    pub home: SVector<f64, N>,
    /// Amplitude of the reference per joint.
    pub amplitude: SVector<f64, N>,
    /// Closed-loop natural frequency of the tracking controller, rad/s.
    pub bandwidth: f64,
    /// Sensor noise.
    pub noise: Noise,
    /// Random seed (reference and noise).
    pub seed: u64,
    /// What real logs carry, made on purpose (none by default).
    pub damage: Damage,
    /// Effects that start and stop: effect `i` of the run is on only
    /// inside `windows[i]` when that is given (missing entries, `None`:
    /// always on). Not for motor sides (elasticity, backlash) or a delay.
    pub windows: Vec<Option<crate::effects::Window>>,
}

impl<const N: usize> Default for SynthOptions<N> {
    fn default() -> Self {
        SynthOptions {
            duration: 8.0,
            rate: 1000.0,
            excitation: ExcitationKind::Sines,
            motion: None,
            home: SVector::zeros(),
            amplitude: SVector::repeat(0.6),
            bandwidth: 12.0,
            noise: Noise::default(),
            seed: 1,
            damage: Damage::default(),
            windows: Vec::new(),
        }
    }
}

impl<const N: usize> SynthOptions<N> {
    /// The reference the run follows: `motion` when given, else one drawn
    /// of `excitation` about `home` with a generator seeded by `seed` (the
    /// one [`synthesize`] draws: the same reference for the same options).
    ///
    /// ```
    /// use dynamics_sim2real::excite::Fourier;
    /// use dynamics_sim2real::synth::{Excitation, SynthOptions};
    /// let o = SynthOptions::<2>::default();
    /// assert_eq!(o.reference().at(1.3), o.reference().at(1.3));
    /// let mut f = Fourier::<2>::new([0.1, 0.2].into(), 4.0, 3);
    /// f.sin[1][0] = 0.2;
    /// f.to_rest();
    /// let o = SynthOptions { motion: Some(Excitation::designed(f.clone())), ..o };
    /// assert_eq!(o.reference().at(1.3), f.at(1.3));
    /// ```
    pub fn reference(&self) -> Excitation<N> {
        self.drawn_reference(&mut Rng::new(self.seed))
    }

    /// [`SynthOptions::reference`], drawing (when it draws) from `rng`.
    pub(crate) fn drawn_reference(&self, rng: &mut Rng) -> Excitation<N> {
        match &self.motion {
            Some(m) => m.clone(),
            None => Excitation::new(
                self.excitation,
                self.home,
                self.amplitude,
                self.duration,
                rng,
            ),
        }
    }
}

/// Why generation failed.
#[derive(Debug, Error)]
pub enum SynthError {
    /// The plant could not be built or simulated.
    #[error(transparent)]
    Plant(#[from] PlantError),
    /// The options are unusable.
    #[error("bad option: {0}")]
    Options(String),
    /// The closed loop went unstable (e.g. a soft elastic joint under a
    /// controller that only sees the link side): the data would be useless.
    #[error("at t = {t:.3} s joint {joint} is {error:.3e} off its reference: the closed loop went unstable")]
    Unstable {
        /// Time.
        t: f64,
        /// Joint index.
        joint: usize,
        /// Tracking error.
        error: f64,
    },
}

/// Simulates `robot` with `effects` attached and records the measured data.
///
/// ```
/// use dynamics_sim2real::effects::Effect;
/// use dynamics_sim2real::synth::{synthesize, SynthOptions};
/// dynamics_macros::robot! {
///     pub robot Pendulum;
///     gravity = [0.0, -9.81, 0.0];
///     link base;
///     link rod { mass = 1.0; com = [0.5, 0.0, 0.0]; inertia = [1e-4, 0.02, 0.02]; }
///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
/// }
/// let opts = SynthOptions::<1> { duration: 1.0, ..Default::default() };
/// let data = synthesize(&Pendulum::default(), &[Effect::coulomb(0, 0.1)], &opts).unwrap();
/// assert_eq!(data.len(), 1001);
/// ```
pub fn synthesize<R: Robot<N> + Clone, const N: usize>(
    robot: &R,
    effects: &[Effect],
    opts: &SynthOptions<N>,
) -> Result<Measured<N>, SynthError> {
    let run = Run::new(robot, effects, opts)?;
    let mut data = run.record(opts.noise, &mut run.rng.clone())?.0;
    let tau_noise = run.scales.peak_effort * opts.noise.tau_relative;
    opts.damage.apply_rows(&mut data, &tau_noise, opts.seed);
    Ok(data)
}

/// Measured data and, from the truth side, how large the withheld effects
/// are against the effort noise.
#[derive(Debug, Clone)]
pub struct Synthesized<const N: usize> {
    /// What the sensors recorded.
    pub data: Measured<N>,
    /// Per joint, the RMS of the effort the nominal model misses, along the
    /// same experiment run without sensor noise: the applied effort minus
    /// the nominal inverse dynamics of the motion the sensors report (away
    /// from the record's first and last 40 ms, as is whether a velocity
    /// reverses, below: what no smoothing window of the diagnosis covers),
    /// through the diagnosis's smoothing ([`crate::smoothing`]: what lies
    /// above the band it passes is in none of its fits). Zero
    /// (to the integrator's rounding) without effects. (Without noise, so
    /// that the controller's reaction to sensor noise, which no sensor
    /// resolves in the motion, does not count as part of a delay.)
    pub effect_rms: SVector<f64, N>,
    /// Per joint, the RMS of the part of that effort the simpler effect it
    /// contains does not explain: at a joint with a motor side
    /// (elasticity, backlash), the effort less its least-squares fit by an
    /// inertia times the link's acceleration (a plain rotor inertia,
    /// `armature`); at a joint with Stribeck friction whose velocity never
    /// reverses, less its fit by a Coulomb friction (a constant effort
    /// there: what is left is the rise at low speed, none if the joint never
    /// slows to the Stribeck velocity); elsewhere the same as `effect_rms`.
    /// The size of what tells those effects from the simpler one.
    pub distinct_rms: SVector<f64, N>,
    /// Per joint, the standard deviation of the effort noise of one sample.
    pub noise_sigma: SVector<f64, N>,
}

impl<const N: usize> Synthesized<N> {
    /// The signal-to-noise ratio of the withheld effects: the largest over
    /// the joints of `effect_rms / noise_sigma`.
    pub fn snr(&self) -> f64 {
        (0..N)
            .map(|j| self.effect_rms[j] / self.noise_sigma[j].max(1e-300))
            .fold(0.0, f64::max)
    }

    /// The same ratio for `distinct_rms`: how far the withheld effects
    /// stand out from the simpler effect they contain (a rigid rotor
    /// inertia, a Coulomb friction).
    pub fn distinct_snr(&self) -> f64 {
        (0..N)
            .map(|j| self.distinct_rms[j] / self.noise_sigma[j].max(1e-300))
            .fold(0.0, f64::max)
    }
}

/// [`synthesize`], also measuring the size of the withheld effects against
/// the effort noise (see [`Synthesized`]): the truth a scoring can use to
/// decide whether a case is identifiable at all, without asking the
/// diagnoser. Costs a second, noise-free run.
///
/// ```
/// use dynamics_sim2real::effects::Effect;
/// use dynamics_sim2real::synth::{synthesize_with_size, SynthOptions};
/// dynamics_macros::robot! {
///     pub robot Pendulum;
///     gravity = [0.0, -9.81, 0.0];
///     link base;
///     link rod { mass = 1.0; com = [0.5, 0.0, 0.0]; inertia = [1e-4, 0.02, 0.02]; }
///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
/// }
/// let opts = SynthOptions::<1> { duration: 1.0, ..Default::default() };
/// let robot = Pendulum::default();
/// let none = synthesize_with_size(&robot, &[], &opts).unwrap();
/// let fc = synthesize_with_size(&robot, &[Effect::coulomb(0, 0.1)], &opts).unwrap();
/// assert!(none.snr() < 1e-3 && fc.effect_rms[0] > 0.05 && fc.effect_rms[0] <= 0.1);
/// ```
pub fn synthesize_with_size<R: Robot<N> + Clone, const N: usize>(
    robot: &R,
    effects: &[Effect],
    opts: &SynthOptions<N>,
) -> Result<Synthesized<N>, SynthError> {
    let run = Run::new(robot, effects, opts)?;
    let (mut data, ..) = run.record(opts.noise, &mut run.rng.clone())?;
    let tau_noise = run.scales.peak_effort * opts.noise.tau_relative;
    opts.damage.apply_rows(&mut data, &tau_noise, opts.seed);
    let quiet = Noise {
        q: 0.0,
        qd: 0.0,
        tau_relative: 0.0,
    };
    let (_, effect_rms, distinct_rms) = run.record(quiet, &mut run.rng.clone())?;
    Ok(Synthesized {
        data,
        effect_rms,
        distinct_rms,
        noise_sigma: run.scales.peak_effort * opts.noise.tau_relative,
    })
}
