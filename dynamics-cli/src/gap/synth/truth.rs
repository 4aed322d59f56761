//! The truth file of a synthetic data set: what was withheld ([`Truth`]),
//! when it was on ([`TruthWindow`]) and where the held-out run's window
//! lies ([`holdout_window`]).

use dynamics_sim2real::effects::Window;
use serde::{Deserialize, Serialize};

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
    /// Excitation of the training run: its kind (`Sines`, `Chirp`,
    /// `PickPlace`), or `designed` when it followed a given motion.
    pub excitation: String,
    /// How large the withheld effect is against the effort noise, from the
    /// truth side (computed by the generator, never by the diagnoser): the
    /// largest over the joints of the RMS, along the recorded training
    /// motion, of the effort the nominal model misses on noise-free data,
    /// seen through the diagnosis's smoothing (`dynamics_sim2real::smoothing`:
    /// what lies above the band it passes is in none of its fits), over
    /// the standard deviation of one sample's effort noise.
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
    pub(super) fn of(w: Window, duration: f64) -> Self {
        let w = w.clipped(duration);
        TruthWindow {
            start: w.start,
            end: w.end,
        }
    }
}
