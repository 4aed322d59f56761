//! Unmodelled effects as run-time add-ons to any generated robot (the dissertation
//! sec. 3.2-3.4; the diagnosis vocabulary of docs/diagnosis.md): friction laws,
//! rotor inertia, payload, two-mass elastic joints, backlash with
//! event-located contact switching, environment resistance at the tip, and
//! sensor faults applied to what is measured.
//!
//! [`Plant`] is a robot with effects attached; [`PlantSim`] integrates it.
//! [`Calibrated`] folds known force effects into a robot's nominal model;
//! [`undo_sensors`] takes known sensor effects out of measured data.

mod calibrated;
mod effect;
mod inertial;
mod kind;
mod nominal_friction;
mod plant;
mod sensors;
mod tip;
mod window;

pub use calibrated::{Calibrated, CalibratedError};
pub(crate) use effect::STRIBECK_GRID;
pub use effect::{smooth_sign, Effect, SIGN_SMOOTHING};
pub use kind::{EffectKind, PlaceKind, UnknownEffect};
pub use nominal_friction::nominal_friction;
pub use plant::{Plant, PlantError, PlantSim, PlantState, Switch};
pub use sensors::undo_sensors;
pub use tip::Tip;
pub use window::{Window, WindowError};

use nalgebra::SVector;

/// `x` moved by `h` and by `-h` along coordinate `k`, and `h` (`1e-6` of
/// the coordinate's size, at least `1e-6`): the two points and the step
/// of a central difference.
pub(crate) fn central_step<const N: usize>(
    x: &SVector<f64, N>,
    k: usize,
) -> (SVector<f64, N>, SVector<f64, N>, f64) {
    let h = 1e-6 * (1.0 + x[k].abs());
    let (mut xp, mut xm) = (*x, *x);
    xp[k] += h;
    xm[k] -= h;
    (xp, xm, h)
}
