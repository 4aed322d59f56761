//! What the sensors of a synthetic run report late: the state by a delay.

use nalgebra::SVector;

/// The true (q, qd) at time `t` from samples at `times` (increasing, from
/// 0), by cubic Hermite interpolation; before the start, the initial state.
pub(super) fn delayed<const N: usize>(
    times: &[f64],
    samples: &[(SVector<f64, N>, SVector<f64, N>)],
    t: f64,
    first: &(SVector<f64, N>, SVector<f64, N>),
) -> (SVector<f64, N>, SVector<f64, N>) {
    if t <= 0.0 {
        return *first;
    }
    let i = times
        .partition_point(|&x| x <= t)
        .saturating_sub(1)
        .min(samples.len() - 1);
    if i + 1 >= samples.len() {
        return samples[i];
    }
    let dt = times[i + 1] - times[i];
    let s = (t - times[i]) / dt;
    let ((p0, v0), (p1, v1)) = (samples[i], samples[i + 1]);
    let (h00, h10, h01, h11) = (
        2.0 * s.powi(3) - 3.0 * s * s + 1.0,
        s.powi(3) - 2.0 * s * s + s,
        -2.0 * s.powi(3) + 3.0 * s * s,
        s.powi(3) - s * s,
    );
    let p = p0 * h00 + v0 * (h10 * dt) + p1 * h01 + v1 * (h11 * dt);
    let (d00, d10, d01, d11) = (
        6.0 * s * s - 6.0 * s,
        3.0 * s * s - 4.0 * s + 1.0,
        -6.0 * s * s + 6.0 * s,
        3.0 * s * s - 2.0 * s,
    );
    let v = (p0 * d00 + p1 * d01) / dt + v0 * d10 + v1 * d11;
    (p, v)
}

/// The applied effort at time `t` from the controller's samples `applied`
/// at `times` (increasing), interpolated linearly between samples (the
/// sequence of samples delayed, as a late effort channel records it);
/// before the start, the first sample.
pub(super) fn effort_at<const N: usize>(
    times: &[f64],
    applied: &[SVector<f64, N>],
    t: f64,
) -> SVector<f64, N> {
    let last = applied.len().min(times.len()).saturating_sub(1);
    if applied.is_empty() {
        return SVector::zeros();
    }
    if t <= times[0] {
        return applied[0];
    }
    let i = times[..=last]
        .partition_point(|&x| x <= t)
        .saturating_sub(1);
    if i >= last {
        return applied[last];
    }
    let s = (t - times[i]) / (times[i + 1] - times[i]);
    applied[i] * (1.0 - s) + applied[i + 1] * s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_late_effort_is_the_applied_sequence_shifted() {
        // A ramp sampled every 0.1 s: read 0.25 s late at t = 1.0 it is
        // the ramp's value at 0.75, between its samples.
        let times: Vec<f64> = (0..11).map(|k| k as f64 * 0.1).collect();
        let applied: Vec<SVector<f64, 1>> =
            times.iter().map(|&t| SVector::from([2.0 * t])).collect();
        assert!((effort_at(&times, &applied, 1.0 - 0.25)[0] - 1.5).abs() < 1e-12);
        assert_eq!(effort_at(&times, &applied, -0.1)[0], 0.0);
        assert!((effort_at(&times, &applied, 0.3)[0] - applied[3][0]).abs() < 1e-12);
    }
}
