//! The measured effort at a time between samples and its rate: what a
//! late effort channel records later (`late.rs`, the `effort` candidate's
//! column), and what the model misses when the whole motion is late
//! (`time_delay`, channel `all`).

use nalgebra::SVector;

use crate::diagnose::signals::Signals;

/// The smoothed measured effort `shift` seconds after sample `k` (before
/// it when negative; linear between samples), when every sample from `k`
/// to there has a full filter window and no hole lies between; `None`
/// otherwise.
pub fn effort_after<const N: usize>(
    sig: &Signals<N>,
    k: usize,
    shift: f64,
) -> Option<SVector<f64, N>> {
    let x = k as f64 + shift / sig.dt;
    if !(x.is_finite() && k >= sig.range.0 && x >= sig.range.0 as f64) {
        return None;
    }
    let i = x.floor() as usize;
    let (from, to) = if shift >= 0.0 { (k, i + 2) } else { (i, k + 1) };
    if i + 1 >= sig.range.1 || !sig.mask.clear(from, to) {
        return None;
    }
    let s = x - i as f64;
    let v = sig.tau(i) * (1.0 - s) + sig.tau(i + 1) * s;
    v.iter().all(|c| c.is_finite()).then_some(v)
}

/// The column of an effort `delay` late at sample `k`, what the model
/// misses per second of that delay: the effort recorded `delay` later is
/// the one that goes with the motion now, so the residual is
/// `delay` times `-(tau(t + delay) - tau(t)) / delay`, the secant of the
/// smoothed measured effort (at least a sample long; built from the
/// effort, not from the model's effort, whose acceleration noise would
/// pull a delay fitted on it towards zero). Where the record ends before
/// `t + delay`: minus the model effort's rate.
pub fn late_effort_column<const N: usize>(
    sig: &Signals<N>,
    k: usize,
    delay: f64,
) -> SVector<f64, N> {
    let d = delay.max(sig.dt);
    if let Some(after) = effort_after(sig, k, d) {
        return -(after - sig.tau(k)) / d;
    }
    let rate = sig.model_rate(k);
    if rate.iter().all(|x| x.is_finite()) {
        -rate
    } else {
        SVector::zeros()
    }
}

/// The column of the whole measured motion `d` late against the effort at
/// sample `k`, per second of `d`, taken over `delay` (the secant, as for a
/// late effort: a tangent reads a delay of content at `w` rad/s as
/// `sin(w d) / w`): the measured effort now less the one `delay` before,
/// over `delay`, where `delay` is at least two samples and the record
/// holds it; otherwise the tangent: the effort recorded now goes with the
/// motion recorded `d` later, so the model along the measured motion
/// misses `d` times the effort's rate. The rate of the smoothed measured
/// effort (central difference over one sample either side), not of the
/// model's effort: the model's rate carries the jerk noise of the smoothed
/// positions, which pulls a delay fitted on it towards zero (a generated
/// 15 ms delay read 13.5 +- 0.4 ms, now 15.0 +- 0.4). That difference is
/// odd about `k` and the smoothed effort even, so its noise does not
/// correlate with the residual's. Where a neighbour lacks a full filter
/// window or a hole lies between: the model effort's rate.
pub fn late_motion_column<const N: usize>(
    sig: &Signals<N>,
    k: usize,
    delay: f64,
) -> SVector<f64, N> {
    if delay >= 2.0 * sig.dt {
        if let Some(before) = effort_after(sig, k, -delay) {
            return (sig.tau(k) - before) / delay;
        }
    }
    let (a, z) = sig.range;
    if k > a && k + 1 < z && sig.mask.clear(k - 1, k + 2) {
        let v = (sig.tau(k + 1) - sig.tau(k - 1)) / (sig.t[k + 1] - sig.t[k - 1]);
        if v.iter().all(|c| c.is_finite()) {
            return v;
        }
    }
    let rate = sig.model_rate(k);
    if rate.iter().all(|x| x.is_finite()) {
        rate
    } else {
        SVector::zeros()
    }
}
