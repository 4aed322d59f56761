//! What each case withholds (an effect, a window, a late stream) and the
//! damages of its record.

use dynamics_cli::gap::Recording;
use dynamics_sim2real::effects::{EffectKind, Window};
use dynamics_sim2real::synth::Rng;

use super::{CASES, CYCLED_CASES};

/// The robots a case is drawn on.
pub(super) const ROBOTS: [&str; 3] = ["arm3r", "rrp-rigid", "mar"];

/// The seed base (`LOGS_SEED_BASE`, 0 unless told).
pub(super) fn seed_base() -> u64 {
    std::env::var("LOGS_SEED_BASE")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(0)
}

/// The damages, by name.
const DAMAGES: [&str; 5] = ["jitter", "repeats", "holes", "glitches", "100 Hz"];

pub(super) fn recording(names: &[&str]) -> Recording {
    let mut r = Recording::default();
    for n in names {
        match *n {
            "jitter" => r.damage.jitter = 0.3,
            "repeats" => r.damage.repeats = 0.05,
            "holes" => r.damage.holes = 2,
            "glitches" => r.damage.glitches = 3,
            _ => r.rate = 100.0,
        }
    }
    r
}

/// A late stream: positions or effort, s.
#[derive(Clone, Copy, Default)]
pub(super) struct Late {
    pub(super) q: f64,
    pub(super) tau: f64,
}

/// What case `i` withholds: its effect kind, a window, a late position or
/// effort stream, its damages.
pub(super) fn draw(
    i: usize,
    rng: &mut Rng,
) -> (EffectKind, Option<Window>, Late, Vec<&'static str>) {
    if i < CASES {
        let kind = if i.is_multiple_of(11) {
            EffectKind::None
        } else {
            EffectKind::ALL[i % 11]
        };
        let mut damages = vec![DAMAGES[rng.below(DAMAGES.len())]];
        if rng.below(2) == 0 {
            let second = DAMAGES[rng.below(DAMAGES.len())];
            if second != damages[0] {
                damages.push(second);
            }
        }
        return (kind, None, Late::default(), damages);
    }
    let damages = vec![DAMAGES[rng.below(DAMAGES.len())]];
    if i - CASES >= CYCLED_CASES {
        let tau = rng.uniform(0.01, 0.025);
        return (EffectKind::None, None, Late { q: 0.0, tau }, damages);
    }
    let start = rng.uniform(1.0, 3.0);
    let length = rng.uniform(1.5, 2.5);
    match (i - CASES) % 4 {
        0 => (
            EffectKind::EncoderOffset,
            Some(Window {
                start,
                end: f64::INFINITY,
            }),
            Late::default(),
            damages,
        ),
        1 => (
            EffectKind::EnvironmentResistance,
            Some(Window {
                start,
                end: start + length,
            }),
            Late::default(),
            damages,
        ),
        2 => (
            EffectKind::PayloadMass,
            Some(Window {
                start,
                end: start + length,
            }),
            Late::default(),
            damages,
        ),
        _ => {
            let q = rng.uniform(0.01, 0.025);
            (EffectKind::None, None, Late { q, tau: 0.0 }, damages)
        }
    }
}
