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
