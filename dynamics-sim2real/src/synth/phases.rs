//! Effects that start and stop: the experiment split at the windows'
//! edges into phases, each with the plant of the effects on in it, and the
//! sensor effects (encoder offsets, effort scale and offset) on at a time.

use nalgebra::SVector;

use super::SynthError;
use crate::effects::{Effect, Plant, Window};
use dynamics_runtime::Robot;

/// The phases of one experiment.
pub(super) struct Phases<R, const N: usize> {
    /// Each phase's start time and plant (the first starts at -inf).
    plants: Vec<(f64, Plant<R, N>)>,
    /// Every effect with its window (`None`: always on).
    effects: Vec<(Effect, Option<Window>)>,
}

fn on(w: &Option<Window>, t: f64) -> bool {
    w.is_none_or(|w| w.contains(t))
}

impl<R: Robot<N> + Clone, const N: usize> Phases<R, N> {
    /// The phases of `effects`, effect `i` on only inside `windows[i]`
    /// when that is given (missing entries: always on). Motor sides
    /// (elasticity, backlash) and a delay cannot be limited in time.
    pub(super) fn new(
        robot: &R,
        effects: &[Effect],
        windows: &[Option<Window>],
    ) -> Result<Self, SynthError> {
        let effects: Vec<(Effect, Option<Window>)> = effects
            .iter()
            .enumerate()
            .map(|(i, e)| (*e, windows.get(i).copied().flatten()))
            .collect();
        let mut edges = vec![f64::NEG_INFINITY];
        for (i, (e, w)) in effects.iter().enumerate() {
            let Some(w) = w else { continue };
            w.validate()
                .map_err(|err| SynthError::Options(format!("effect {i} ({}): {err}", e.kind())))?;
            if e.has_motor() || matches!(e, Effect::TimeDelay { .. }) {
                return Err(SynthError::Options(format!(
                    "effect {i} ({}) cannot be limited to a window (motor sides and delays are always on)",
                    e.kind()
                )));
            }
            edges.push(w.start);
            if w.end.is_finite() {
                edges.push(w.end);
            }
        }
        edges.sort_by(f64::total_cmp);
        edges.dedup();
        // Every effect is checked once, whatever its window.
        Plant::new(robot.clone(), effects.iter().map(|e| e.0).collect())?;
        let plants = edges
            .iter()
            .map(|&t0| {
                let active = effects
                    .iter()
                    .filter(|(_, w)| on(w, t0))
                    .map(|e| e.0)
                    .collect();
                Ok((t0, Plant::new(robot.clone(), active)?))
            })
            .collect::<Result<Vec<_>, SynthError>>()?;
        Ok(Phases { plants, effects })
    }

    /// The plant of the effects on at time `t`.
    pub(super) fn plant_at(&self, t: f64) -> &Plant<R, N> {
        let i = self.plants.partition_point(|p| p.0 <= t).saturating_sub(1);
        &self.plants[i].1
    }

    /// The plant with every effect (the start state's motor sides).
    pub(super) fn first(&self) -> &Plant<R, N> {
        self.plant_at(0.0)
    }

    /// The encoder offsets on at time `t`.
    pub(super) fn offset_at(&self, t: f64) -> SVector<f64, N> {
        let mut offset = SVector::zeros();
        for (e, w) in &self.effects {
            if let (Effect::EncoderOffset { joint, offset: o }, true) = (e, on(w, t)) {
                offset[*joint] += o;
            }
        }
        offset
    }

    /// The effort-sensor effects (scale, offset) on at time `t`.
    pub(super) fn sensor_at(&self, t: f64) -> Vec<Effect> {
        self.effects
            .iter()
            .filter(|(e, w)| {
                matches!(e, Effect::EffortScale { .. } | Effect::EffortOffset { .. }) && on(w, t)
            })
            .map(|e| e.0)
            .collect()
    }
}
