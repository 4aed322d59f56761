//! Glitches: a sample far outside its signal's course (1e300, a spike of
//! fifty standard deviations, one row of the wrong sign). Each sample is
//! compared with a robust local linear fit from either side (the median of
//! three straight-line extrapolations at its true time from the three
//! samples before it, and the same from after); its departure is the
//! smaller of the two, so that a step (a contact, a friction reversal),
//! which agrees with one side, is not a glitch. A glitch departs by more
//! than [`THRESHOLD`] robust standard deviations of that departure (1.4826
//! x its median over the channel; at least the channel's smallest nonzero
//! change from one row to the next, its quantum).

/// Departure, in robust standard deviations, beyond which a sample is a
/// glitch. For white noise of deviation s, the departure's robust deviation
/// is about 1.3 s, so this flags samples about 20 s off: a noise sample is
/// never that far (both sides would have to miss it by 6.7 of their own
/// deviations), a 50-sigma spike always is.
pub const THRESHOLD: f64 = 15.0;

/// Samples per block of the local scale.
const BLOCK: usize = 32;

/// The glitches of one channel `x` at times `t`: (index, departure in
/// robust standard deviations).
pub(super) fn glitches(t: &[f64], x: &[f64]) -> Vec<(usize, f64)> {
    let n = x.len();
    if n < 8 {
        return vec![];
    }
    let line = |a: usize, b: usize, k: usize| -> f64 {
        x[a] + (x[b] - x[a]) * ((t[k] - t[a]) / (t[b] - t[a]))
    };
    let med3 = |a: f64, b: f64, c: f64| a.max(b).min(a.min(b).max(c));
    // Both sides are needed to tell a spike from a step: the first and last
    // three samples are not tested.
    let dev: Vec<f64> = (0..n)
        .map(|k| {
            if k < 3 || k + 3 >= n {
                return 0.0;
            }
            let left = med3(
                line(k - 2, k - 1, k),
                line(k - 3, k - 1, k),
                line(k - 3, k - 2, k),
            );
            let right = med3(
                line(k + 1, k + 2, k),
                line(k + 1, k + 3, k),
                line(k + 2, k + 3, k),
            );
            (x[k] - left).abs().min((x[k] - right).abs())
        })
        .collect();
    let clean = |d: &f64| if d.is_nan() { f64::INFINITY } else { *d };
    let mut sorted: Vec<f64> = dev[3..n - 3].iter().map(clean).collect();
    let m = sorted.len() / 2;
    let mad = *sorted.select_nth_unstable_by(m, f64::total_cmp).1;
    // Where the signal turns fast (a slow rate, a reversal), its departures
    // are larger than the channel's median: the local median (over blocks
    // of BLOCK samples, the largest of a block and its neighbours) raises
    // the scale there; a lone spike barely moves its block's median.
    let blocks: Vec<f64> = dev
        .chunks(BLOCK)
        .map(|c| {
            let mut v: Vec<f64> = c.iter().map(clean).collect();
            let h = v.len() / 2;
            *v.select_nth_unstable_by(h, f64::total_cmp).1
        })
        .collect();
    let local = |k: usize| -> f64 {
        let b = k / BLOCK;
        blocks[b.saturating_sub(1)..(b + 2).min(blocks.len())]
            .iter()
            .copied()
            .fold(0.0, f64::max)
    };
    let quantum = x
        .windows(2)
        .map(|w| (w[1] - w[0]).abs())
        .filter(|d| *d > 0.0)
        .fold(f64::INFINITY, f64::min);
    let floor = if quantum.is_finite() { quantum } else { 0.0 };
    let scale = |k: usize| (1.4826 * mad.max(local(k))).max(floor).max(1e-300);
    let flagged: Vec<(usize, f64)> = dev
        .iter()
        .enumerate()
        .filter_map(|(k, d)| {
            let s = if d.is_nan() {
                f64::INFINITY
            } else {
                d / scale(k)
            };
            (s > THRESHOLD).then_some((k, s))
        })
        .collect();
    // A glitch is a lone sample (or two): where three or more within two
    // rows of each other depart, the signal turns faster than the blocks'
    // scale follows (a joint starting from rest, sampled at 100 Hz), and
    // that is its course. Departures no turn of a signal reaches
    // ([`BEYOND_ANY_TURN`] thresholds; a non-finite one reads infinite)
    // stay glitches.
    let near = |k: usize| {
        flagged
            .iter()
            .filter(|(j, _)| *j != k && j.abs_diff(k) <= 2)
            .count()
    };
    flagged
        .iter()
        .copied()
        .filter(|&(k, s)| near(k) < 2 || s >= BEYOND_ANY_TURN * THRESHOLD)
        .collect()
}

/// Departure, in thresholds, beyond which a sample is a glitch even among
/// others (a burst of garbage rows, not a fast turn of the signal).
const BEYOND_ANY_TURN: f64 = 1000.0;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synth::Rng;

    #[test]
    fn spikes_are_found_and_steps_and_noise_are_not() {
        let mut rng = Rng::new(7);
        // Jittered clock, a fast sine with noise 1e-3, a step of 0.5 at 0.6 s.
        let mut t = vec![0.0];
        for k in 1..3000 {
            t.push(t[k - 1] + 1e-3 * rng.uniform(0.7, 1.3));
        }
        let mut x: Vec<f64> = t
            .iter()
            .map(|&t| (6.0 * t).sin() + if t > 0.6 { 0.5 } else { 0.0 } + 1e-3 * rng.normal())
            .collect();
        assert!(glitches(&t, &x).is_empty());
        x[100] = 1e300;
        x[1] = 1e300; // too near the start to be told from a step
        x[1500] += 0.05; // 50 sigma
        x[2000] = -x[2000];
        x[2001] += 1e300;
        let found: Vec<usize> = glitches(&t, &x).iter().map(|g| g.0).collect();
        assert_eq!(found, vec![100, 1500, 2000, 2001]);
    }

    #[test]
    fn a_quick_move_at_100_hz_is_its_course_and_a_burst_of_garbage_is_not() {
        // At rest (noise 1e-6), then a quick move of 0.02 over 80 ms (a
        // cosine profile) and at rest again, sampled at 100 Hz: 8 samples
        // of motion in quiet blocks, whose scale is far below the move's
        // curvature.
        let t: Vec<f64> = (0..600).map(|k| k as f64 * 0.01).collect();
        let mut rng = Rng::new(3);
        let mut x: Vec<f64> = t
            .iter()
            .map(|&t| {
                let u = ((t - 2.0) / 0.08).clamp(0.0, 1.0);
                0.3 - 0.01 * (1.0 - (std::f64::consts::PI * u).cos()) + 1e-6 * rng.normal()
            })
            .collect();
        assert!(glitches(&t, &x).len() < 2, "{:?}", glitches(&t, &x));
        for k in 300..303 {
            x[k] = 1e300;
        }
        let found: Vec<usize> = glitches(&t, &x).iter().map(|g| g.0).collect();
        assert!(found.contains(&300) && found.contains(&302), "{found:?}");
    }
}
