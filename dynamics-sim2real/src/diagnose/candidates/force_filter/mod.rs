//! A force as the torque residual shows it: filtered the way the
//! acceleration estimate filters the motion it causes.

#[cfg(test)]
use crate::smoothing::SavitzkyGolay;

/// A force `f` (one value a sample) as the torque residual shows it: the
/// derivative of the smoothing fit of its running integral where the
/// accelerations are the derivative of the measured velocities' fit (the
/// second derivative of its double integral where they come from the
/// positions). A friction force acts on the motion: where it turns fast
/// (a velocity reversal, a Stribeck breakaway) the effort a controller
/// applies stays smooth and the acceleration takes the turn, so the
/// residual `tau - ID(q, qd, qdd)` holds the force filtered as the
/// acceleration estimate filters the motion, not as the smoothing filters
/// the efforts (the two agree on slow signals, cubics within a window,
/// and differ at a turn). On a generated Stribeck friction at the MAR's
/// q1 (its noise scaled by 1/1000) the
/// residual across a reversal at 2.3 rad/s^2 departed from the law
/// smoothed like the efforts by up to 0.37 N m (0.16 RMS over the
/// reversal, fs - fc = 0.98) and from the law filtered this way by 0.06
/// (0.03 RMS): smoothed like the efforts, the fitted Stribeck friction
/// predicted the held-out record worse than Coulomb's, and was named
/// behind it. Filtered this way, the training AICc of both fell, by 83
/// (Coulomb) and 92 (Stribeck), on the case as generated.
///
/// The column cache runs it a chunk at a time with the [`Carry`]
/// (`row_series.rs`); this whole-record form is what the tests compare
/// with.
#[cfg(test)]
pub fn through_motion(sg: &SavitzkyGolay, f: &[f64], dt: f64, qd_measured: bool) -> Vec<f64> {
    let mut carry = Carry::default();
    let running: Vec<f64> = f.iter().map(|&x| carry.step(x, dt, qd_measured)).collect();
    sg.apply(&running, if qd_measured { 1 } else { 2 })
}

/// The running integrals [`through_motion`] differentiates, as carried
/// from one sample to the next: a stretch of a record integrated from the
/// carry at its first sample gives the same values as the whole record
/// integrated from its start.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Carry {
    /// The integral up to the next sample's interval.
    sum: f64,
    /// The double integral at the last sample.
    double: f64,
    /// The integral at the last sample.
    last: f64,
    /// Whether a sample was taken.
    started: bool,
}

impl Carry {
    /// Takes the next sample's value `x` (the mean over its own interval,
    /// half of it on either side) and gives the running integral at it
    /// (`qd_measured`), or the double integral (trapezoids of the
    /// integral).
    pub fn step(&mut self, x: f64, dt: f64, qd_measured: bool) -> f64 {
        let integral = self.sum + 0.5 * x * dt;
        self.sum += x * dt;
        if qd_measured {
            return integral;
        }
        if self.started {
            self.double += 0.5 * (self.last + integral) * dt;
        }
        self.started = true;
        self.last = integral;
        self.double
    }
}

#[cfg(test)]
mod tests;
