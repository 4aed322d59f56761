//! The file's clock: its median interval (the grid's), the jitter about it,
//! the steps long enough to be holes, and whether `t` is in milliseconds.

use nalgebra::SVector;

/// An interval at least this many median intervals long is a hole: "a few
/// periods", beyond the +-30 % jitter and the occasional double step of a
/// logger's clock.
pub const HOLE_PERIODS: f64 = 3.5;

/// What the intervals of a file look like.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Clock {
    /// Median interval, s: the grid's.
    pub(super) interval: f64,
    /// RMS relative deviation of the intervals that are not holes.
    pub(super) jitter: f64,
    /// Shortest interval.
    pub(super) min: f64,
    /// Longest interval that is not a hole.
    pub(super) max: f64,
    /// Whether every interval is the median one to 1e-6.
    pub(super) uniform: bool,
}

/// Median of `v` (reordered).
pub(super) fn median(v: &mut [f64]) -> f64 {
    if v.is_empty() {
        return 0.0;
    }
    let m = v.len() / 2;
    *v.select_nth_unstable_by(m, f64::total_cmp).1
}

impl Clock {
    /// Measures the intervals of `t` (increasing, at least two samples).
    pub(super) fn of(t: &[f64]) -> Clock {
        let mut dts: Vec<f64> = t.windows(2).map(|w| w[1] - w[0]).collect();
        let interval = median(&mut dts.clone());
        let (mut min, mut max, mut sum, mut n) = (f64::INFINITY, 0.0f64, 0.0, 0usize);
        let mut uniform = true;
        for d in dts.iter_mut() {
            min = min.min(*d);
            uniform &= (*d - interval).abs() <= 1e-6 * interval;
            if *d < HOLE_PERIODS * interval {
                max = max.max(*d);
                sum += ((*d - interval) / interval).powi(2);
                n += 1;
            }
        }
        Clock {
            interval,
            jitter: (sum / n.max(1) as f64).sqrt(),
            min,
            max,
            uniform,
        }
    }
}

/// How many times faster the positions move per unit of `t` than the
/// recorded velocities say (near 1 when `t` is in seconds, near 1e-3 when
/// it is in milliseconds): the median over samples where the velocity is
/// at least a tenth of its peak of the ratio of the positions' central
/// difference to the recorded velocity. `None` when nothing moves.
pub(super) fn speed_ratio<const N: usize>(
    t: &[f64],
    q: &[SVector<f64, N>],
    qd: &[SVector<f64, N>],
) -> Option<f64> {
    let mut ratios = Vec::new();
    for j in 0..N {
        let mut speeds: Vec<f64> = qd.iter().map(|v| v[j].abs()).collect();
        let n = speeds.len();
        if n < 3 {
            return None;
        }
        // A robust peak (the 99th percentile), so that a glitch does not set it.
        let peak = *speeds
            .select_nth_unstable_by(n * 99 / 100, f64::total_cmp)
            .1;
        if peak <= 0.0 {
            continue;
        }
        for k in 1..n - 1 {
            let v = qd[k][j];
            if v.abs() >= 0.1 * peak {
                ratios.push((q[k + 1][j] - q[k - 1][j]) / (t[k + 1] - t[k - 1]) / v);
            }
        }
    }
    (!ratios.is_empty()).then(|| median(&mut ratios))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn jitter_and_holes_are_measured() {
        // Intervals 1 ms +- 30 % in turn, and one hole of 10 ms.
        let mut t = vec![0.0];
        for k in 0..1000 {
            let d = if k == 500 {
                0.01
            } else {
                1e-3 * (1.0 + 0.3 * [-1.0, 0.0, 1.0][k % 3])
            };
            t.push(t[k] + d);
        }
        let c = Clock::of(&t);
        assert!((c.interval - 1e-3).abs() < 1e-12);
        assert!(
            (c.jitter - 0.3 * (2.0f64 / 3.0).sqrt()).abs() < 1e-3,
            "{}",
            c.jitter
        );
        assert!((c.max - 1.3e-3).abs() < 1e-12 && (c.min - 0.7e-3).abs() < 1e-12);
        assert!(!c.uniform);
    }

    #[test]
    fn milliseconds_show_in_the_speed_ratio() {
        let t: Vec<f64> = (0..400).map(|k| k as f64).collect(); // ms
        let q: Vec<SVector<f64, 1>> = t.iter().map(|&t| [(t * 1e-3).sin()].into()).collect();
        let qd: Vec<SVector<f64, 1>> = t.iter().map(|&t| [(t * 1e-3).cos()].into()).collect();
        let r = speed_ratio(&t, &q, &qd).unwrap();
        assert!((r - 1e-3).abs() < 1e-6, "{r}");
    }
}
