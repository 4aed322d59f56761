//! The motor side's effort as the link receives it: the simulation of
//! `sim/` for one guess.

use nalgebra::SVector;

use super::{transmitted_raw_many, Load};
use crate::diagnose::candidates::MotorGuess;

/// Simulates the motor side of joint `j` of `on` (the record's signals and
/// the model's effort at the joint, [`Load`]) driven by the measured effort
/// (held per sample) and the link of joint `j` (its acceleration per unit
/// of its own effort `compliance[k][j]`, `Basis::compliance`); returns the
/// effort it passes to the link at every sample, before the smoothing the
/// efforts have (NaN outside the range, and everywhere when the
/// simulation diverged). The link follows the measured (smoothed) motion
/// plus what the transmitted effort adds over the nominal model's (times
/// that compliance: the joint's own response with the other joints'
/// efforts held, not one over its mean inertia: on the MAR, q2's and the
/// slide's response is 1.2 to 2.1 times one over their own inertia, and
/// q2's inertia runs from 0.9 to 3.0 kg m^2 with the slide), pulled back
/// to the measurement at [`OBSERVER_HZ`](super::OBSERVER_HZ): a link
/// pinned to the smoothed motion would meet a stiff contact or spring at
/// positions the 40 ms smoothing has blurred (a backlash crossing lasts
/// about as long), and the contact stiffness would turn that blur into
/// effort (on a generated backlash case, the whitened error of the true
/// parameters fell from 7258 to 4623, nominal model 20985).
pub fn motor_transmitted_raw<const N: usize, L: Load<N> + ?Sized>(
    on: &L,
    j: usize,
    g: &MotorGuess,
    backlash: bool,
    compliance: &SVector<f64, N>,
) -> Vec<f64> {
    transmitted_raw_many(on, j, std::slice::from_ref(g), backlash, compliance)
        .pop()
        .unwrap_or_default()
}
