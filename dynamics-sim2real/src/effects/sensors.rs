//! The sensors' effects undone on measured data: what a calibrated
//! baseline knows of the encoders, the effort sensors and the streams'
//! timing, taken out of a record before it is compared with the model
//! (the model side of a baseline is [`super::Calibrated`]).

use super::Effect;
use crate::data::Measured;

/// `m` with the sensor effects among `effects` undone (others ignored):
/// an encoder offset subtracted from its joint's positions; an effort
/// scale divided out and an effort offset subtracted; a delay `d` of the
/// motion (positions and velocities recorded `d` late; a late effort
/// stream is a negative `d`) undone by reading the motion `d` later,
/// linearly between samples, the samples at either end that have no such
/// time dropped.
///
/// ```
/// use dynamics_sim2real::data::Measured;
/// use dynamics_sim2real::effects::{undo_sensors, Effect};
/// use nalgebra::Vector1;
/// let t: Vec<f64> = (0..5).map(|k| k as f64 * 0.1).collect();
/// let m = Measured::<1> {
///     q: t.iter().map(|&t| Vector1::new(t + 0.5)).collect(),
///     qd: vec![Vector1::new(1.0); 5],
///     tau: vec![Vector1::new(2.0); 5],
///     t,
///     ..Default::default()
/// };
/// let offset = Effect::EncoderOffset { joint: 0, offset: 0.5 };
/// let scale = Effect::EffortScale { joint: 0, scale: 2.0 };
/// let late = Effect::TimeDelay { delay: 0.1 };
/// let fixed = undo_sensors(&m, &[offset, scale, late]);
/// assert_eq!(fixed.len(), 4); // the last sample has no motion 0.1 s later
/// assert!((fixed.q[0][0] - 0.1).abs() < 1e-12); // read 0.1 s later, offset removed
/// assert!((fixed.tau[0][0] - 1.0).abs() < 1e-12);
/// ```
pub fn undo_sensors<const N: usize>(m: &Measured<N>, effects: &[Effect]) -> Measured<N> {
    let mut out = m.clone();
    for e in effects {
        match *e {
            Effect::EncoderOffset { joint, offset } if joint < N => {
                for q in &mut out.q {
                    q[joint] -= offset;
                }
            }
            Effect::EffortScale { joint, scale } if joint < N && scale != 0.0 => {
                for tau in &mut out.tau {
                    tau[joint] /= scale;
                }
            }
            Effect::EffortOffset { joint, offset } if joint < N => {
                for tau in &mut out.tau {
                    tau[joint] -= offset;
                }
            }
            Effect::TimeDelay { delay } if delay.is_finite() && delay != 0.0 => {
                out = shifted(&out, delay);
            }
            _ => {}
        }
    }
    out
}

/// The motion of `m` read `d` seconds later (earlier for `d < 0`) at each
/// sample time, linearly between samples; samples without such a time
/// dropped. A sample is missing, or in a hole, when its own effort or a
/// sample its motion is read from was (`Measured::missing`,
/// `Measured::holes`): the holes are the runs of such samples.
fn shifted<const N: usize>(m: &Measured<N>, d: f64) -> Measured<N> {
    let n = m.len();
    // The samples (one or two) and weights the motion at time `s` is read
    // from.
    let from = |s: f64| -> Option<(usize, usize, f64)> {
        // The last sample at or before `s`.
        let i = m.t.partition_point(|&t| t <= s);
        if i == 0 {
            return None;
        }
        let i = i - 1;
        if (m.t[i] - s).abs() <= 1e-12 * (1.0 + s.abs()) {
            return Some((i, i, 0.0));
        }
        let j = i + 1;
        (j < n).then(|| (i, j, (s - m.t[i]) / (m.t[j] - m.t[i])))
    };
    let mut in_hole = vec![false; n];
    for &(a, b) in &m.holes {
        in_hole[a.min(n)..b.min(n)].fill(true);
    }
    let mut out = Measured::<N> {
        qd_measured: m.qd_measured,
        warnings: m.warnings.clone(),
        joints: m.joints.clone(),
        prepared: m.prepared,
        interpolation_variance: m.interpolation_variance,
        ..Default::default()
    };
    let mut missing = Vec::new();
    let mut hole = Vec::new();
    for k in 0..n {
        let Some((i, j, f)) = from(m.t[k] + d) else {
            continue;
        };
        out.t.push(m.t[k]);
        out.q.push(m.q[i] * (1.0 - f) + m.q[j] * f);
        out.qd.push(m.qd[i] * (1.0 - f) + m.qd[j] * f);
        out.tau.push(m.tau[k]);
        missing.push(!(m.measured(k) && m.measured(i) && m.measured(j)));
        hole.push(in_hole[k] || in_hole[i] || in_hole[j]);
    }
    if !m.missing.is_empty() {
        out.missing = missing;
    }
    // The runs of samples in a hole.
    let mut start = None;
    for (k, &h) in hole.iter().chain([&false]).enumerate() {
        match (h, start) {
            (true, None) => start = Some(k),
            (false, Some(a)) => {
                out.holes.push((a, k));
                start = None;
            }
            _ => {}
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector2;

    fn record(t: &[f64]) -> Measured<2> {
        Measured {
            t: t.to_vec(),
            q: t.iter().map(|&t| Vector2::new(t.sin(), 2.0 * t)).collect(),
            qd: t.iter().map(|&t| Vector2::new(t.cos(), 2.0)).collect(),
            tau: t.iter().map(|&t| Vector2::new(3.0 * t, -1.0)).collect(),
            ..Default::default()
        }
    }

    #[test]
    fn a_late_motion_is_read_later_and_a_late_effort_earlier() {
        let t: Vec<f64> = (0..1000).map(|k| k as f64 * 1e-3).collect();
        let m = record(&t);
        let fixed = undo_sensors(&m, &[Effect::TimeDelay { delay: 0.0105 }]);
        assert_eq!(fixed.len(), 1000 - 11);
        for k in 0..fixed.len() {
            assert!((fixed.q[k][1] - 2.0 * (fixed.t[k] + 0.0105)).abs() < 1e-12);
            assert_eq!(fixed.tau[k], m.tau[k]);
        }
        let early = undo_sensors(&m, &[Effect::TimeDelay { delay: -0.002 }]);
        assert_eq!(early.len(), 998);
        assert_eq!(early.t[0], m.t[2]);
        assert!((early.q[0][1] - 2.0 * m.t[0]).abs() < 1e-12);
    }

    /// A record with a hole (samples 40..50 filled) and two filled samples:
    /// once its motion is read 10.5 ms later, a sample is missing or in a
    /// hole where its effort, or either sample its motion is read from,
    /// was (by hand: the motion of sample k comes from samples k + 10 and
    /// k + 11).
    #[test]
    fn a_late_motion_undone_keeps_the_records_holes_and_missing_samples() {
        let t: Vec<f64> = (0..100).map(|k| k as f64 * 1e-3).collect();
        let mut m = record(&t);
        m.holes = vec![(40, 50)];
        m.missing = (0..100)
            .map(|k| (40..50).contains(&k) || k == 5 || k == 80)
            .collect();
        m.prepared = true;
        m.interpolation_variance = 0.8;
        let fixed = undo_sensors(&m, &[Effect::TimeDelay { delay: 0.0105 }]);
        assert_eq!(fixed.len(), 89);
        // In a hole: its effort (40..50) or its motion (from 29..39 and
        // 30..40, i.e. k + 10 or k + 11 in 40..50): samples 29..50.
        assert_eq!(fixed.holes, vec![(29, 50)]);
        let missing: Vec<usize> = (0..89).filter(|&k| fixed.missing[k]).collect();
        let mut expected: Vec<usize> = (29..50).collect();
        // Sample 5 (its effort), 80 (its effort) and those reading their
        // motion from 80 (k = 69, 70); sample 5's motion is read by none
        // in range below 0 (k = -5, -6).
        expected.extend([5, 69, 70, 80]);
        expected.sort();
        assert_eq!(missing, expected);
        assert!(fixed.prepared);
        assert_eq!(fixed.interpolation_variance, 0.8);
    }

    #[test]
    fn scales_and_offsets_are_undone_on_their_joint_only() {
        let m = record(&[0.0, 0.5, 1.0]);
        let fixed = undo_sensors(
            &m,
            &[
                Effect::EffortScale {
                    joint: 0,
                    scale: 1.5,
                },
                Effect::EffortOffset {
                    joint: 1,
                    offset: 0.25,
                },
                Effect::EncoderOffset {
                    joint: 1,
                    offset: -0.1,
                },
            ],
        );
        for k in 0..3 {
            assert!((fixed.tau[k][0] - m.tau[k][0] / 1.5).abs() < 1e-15);
            assert!((fixed.tau[k][1] - (m.tau[k][1] - 0.25)).abs() < 1e-15);
            assert!((fixed.q[k][1] - (m.q[k][1] + 0.1)).abs() < 1e-15);
            assert_eq!(fixed.q[k][0], m.q[k][0]);
        }
    }
}
