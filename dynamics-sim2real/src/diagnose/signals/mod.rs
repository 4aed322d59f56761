//! From measured samples to what the diagnosis works on: smoothed positions,
//! velocities and accelerations (no double differencing of raw data), the
//! smoothed efforts, the nominal model's efforts along the measured motion,
//! their difference (the torque residual).

mod noise;
mod segments;

use std::ops::Deref;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;

use nalgebra::SVector;

use crate::data::Measured;
use crate::diagnose::along;
use crate::smoothing::SavitzkyGolay;
use dynamics_runtime::Robot;
pub use noise::SensorNoise;
use noise::{known_floor, sensor_levels};
pub use segments::Mask;

/// Half-width of the light smoother of velocities, s.
pub const LIGHT_HALF_WIDTH: f64 = 0.004;

/// One data set, prepared. The per-sample signals that do not change once
/// made are shared (`Arc`) by copies of the signals; what they read of
/// the record as recorded (its times, raw efforts and the velocities the
/// light smoother reads) is the record itself, shared with the
/// diagnosis's own when it was handed over ([`Signals::shared`]), else a
/// copy of those fields.
#[derive(Debug, Clone)]
pub struct Signals<const N: usize> {
    /// Sample interval.
    pub dt: f64,
    /// First and one-past-last sample with a full filter window.
    pub range: (usize, usize),
    /// Times.
    pub t: Times<N>,
    /// The smoothed positions, velocities and accelerations, made where
    /// asked from the record ([`Signals::q`], [`Signals::qd`],
    /// [`Signals::qdd`]; [`Motion::stretch`] for a stretch of samples).
    pub motion: Motion<N>,
    /// Whether the velocities were measured (the accelerations are then
    /// the first derivative of their smoothing fit; else the second of
    /// the positions').
    pub qd_measured: bool,
    /// The light smoother of [`Signals::qd_light`] (over
    /// [`LIGHT_HALF_WIDTH`]).
    pub light: SavitzkyGolay,
    /// The record as recorded, as far as these signals read it: times,
    /// raw efforts, positions and (measured) velocities.
    pub record: Arc<Measured<N>>,
    /// The nominal model's efforts along the smoothed motion.
    pub model: Vec<SVector<f64, N>>,
    /// `tau - model`.
    pub residual: Vec<SVector<f64, N>>,
    /// Noise floor of the smoothed residual per joint: what the sensors'
    /// noise makes of it (`noise.rs`; zero from [`Signals::unfloored`]).
    pub floor: SVector<f64, N>,
    /// The filter.
    pub sg: SavitzkyGolay,
    /// Which samples a fit may use (holes and filled samples excluded).
    pub mask: Mask,
}

/// A record's sample times, read from the record itself (shared, not
/// copied, by the signals of the record and their copies).
#[derive(Debug, Clone)]
pub struct Times<const N: usize>(Arc<Measured<N>>);

impl<const N: usize> Times<N> {
    /// The times of `record`.
    pub fn of(record: &Arc<Measured<N>>) -> Self {
        Times(Arc::clone(record))
    }
}

impl<const N: usize> Deref for Times<N> {
    type Target = [f64];

    fn deref(&self) -> &[f64] {
        &self.0.t
    }
}

/// What [`Signals`] read of `m` as recorded, copied: its times, raw
/// efforts, positions and the velocities when measured (the other fields
/// empty).
fn kept<const N: usize>(m: &Measured<N>) -> Measured<N> {
    let qd = if m.qd_measured {
        m.qd.clone()
    } else {
        Vec::new()
    };
    Measured {
        t: m.t.clone(),
        q: m.q.clone(),
        qd,
        tau: m.tau.clone(),
        qd_measured: m.qd_measured,
        ..Default::default()
    }
}

/// A record's positions, velocities and accelerations smoothed by the
/// diagnosis's filter, made where asked from the record (shared, not
/// copied): the same products summed in the same order as
/// [`SavitzkyGolay::apply`] over the whole record, so the same values to
/// the bit, NaN where the filter's window does not fit. The velocities
/// and accelerations are the smoothing fit's value and first derivative
/// of the measured velocities when measured, else its first and second
/// derivatives of the positions.
#[derive(Debug, Clone)]
pub struct Motion<const N: usize> {
    /// Tells this motion from another's (its copies share it).
    id: u64,
    record: Arc<Measured<N>>,
    sg: SavitzkyGolay,
}

/// Where each [`Motion`] is told from another.
static NEXT_MOTION: AtomicU64 = AtomicU64::new(0);

impl<const N: usize> Motion<N> {
    /// The smoothed motion of `record` by `sg`.
    pub fn of(record: &Arc<Measured<N>>, sg: &SavitzkyGolay) -> Self {
        Motion {
            id: NEXT_MOTION.fetch_add(1, Ordering::Relaxed),
            record: Arc::clone(record),
            sg: sg.clone(),
        }
    }

    /// What tells this motion (and its copies) from another record's or
    /// filter's: a key for values kept made from it.
    pub fn id(&self) -> u64 {
        self.id
    }

    /// Number of samples.
    pub fn len(&self) -> usize {
        self.record.t.len()
    }

    /// Whether the record has no samples.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The samples and derivative order derivative `d` (0, 1, 2) of the
    /// motion is the filter's derivative of.
    fn source(&self, d: usize) -> (&[SVector<f64, N>], usize) {
        match (self.record.qd_measured, d) {
            (_, 0) => (&self.record.q, 0),
            (true, _) => (&self.record.qd, d - 1),
            (false, _) => (&self.record.q, d),
        }
    }

    /// Derivative `d` (0: positions, 1: velocities, 2: accelerations) at
    /// sample `k`, every joint.
    fn filtered(&self, d: usize, k: usize) -> SVector<f64, N> {
        let (x, order) = self.source(d);
        let h = self.sg.half();
        if k < h || k + h >= x.len() {
            return SVector::from_element(f64::NAN);
        }
        // Each joint's sum term by term in `apply`'s order, from the
        // value a float sum starts from (`Iterator::sum`).
        let start: f64 = std::iter::empty::<f64>().sum();
        let mut s = SVector::<f64, N>::from_element(start);
        for (w, v) in self.sg.weights(order).iter().zip(&x[k - h..=k + h]) {
            s += v * *w;
        }
        s
    }

    /// Derivative `d` at sample `k`, joint `j`.
    fn filtered_at(&self, d: usize, k: usize, j: usize) -> f64 {
        let (x, order) = self.source(d);
        self.sg.at_joint(x, order, k, j)
    }

    /// Smoothed positions at sample `k`.
    pub fn q(&self, k: usize) -> SVector<f64, N> {
        self.filtered(0, k)
    }

    /// Smoothed velocities at sample `k`.
    pub fn qd(&self, k: usize) -> SVector<f64, N> {
        self.filtered(1, k)
    }

    /// Accelerations at sample `k`.
    pub fn qdd(&self, k: usize) -> SVector<f64, N> {
        self.filtered(2, k)
    }

    /// Joint `j` of [`Motion::q`].
    pub fn q_at(&self, k: usize, j: usize) -> f64 {
        self.filtered_at(0, k, j)
    }

    /// Joint `j` of [`Motion::qd`].
    pub fn qd_at(&self, k: usize, j: usize) -> f64 {
        self.filtered_at(1, k, j)
    }

    /// Joint `j` of [`Motion::qdd`].
    pub fn qdd_at(&self, k: usize, j: usize) -> f64 {
        self.filtered_at(2, k, j)
    }

    /// Derivative `d` (0: positions, 1: velocities, 2: accelerations) of
    /// joint `j` at samples `lo..hi` (indexed from `lo`): each sample's
    /// [`Motion::q_at`], [`Motion::qd_at`] or [`Motion::qdd_at`] to the
    /// bit, several samples' sums side by side.
    pub fn joint_stretch(&self, d: usize, j: usize, lo: usize, hi: usize) -> Vec<f64> {
        let (x, order) = self.source(d);
        self.sg.joint_run(x, order, j, (lo, hi))
    }

    /// Positions, velocities and accelerations at samples `lo..hi`
    /// (indexed from `lo`).
    pub fn stretch(&self, lo: usize, hi: usize) -> [Vec<SVector<f64, N>>; 3] {
        std::array::from_fn(|d| (lo..hi).map(|k| self.filtered(d, k)).collect())
    }
}

impl<const N: usize> Signals<N> {
    /// The signals of `m` for `robot` with the noise floor of the torque
    /// residual that sensor noise of `levels` (q, qd, tau per joint) makes
    /// of it, the levels estimated from the data when not known
    /// (`noise.rs`); and the levels used.
    pub fn new<R: Robot<N>>(
        robot: &R,
        m: &Measured<N>,
        levels: Option<&[SVector<f64, N>; 3]>,
        chunk: usize,
    ) -> (Self, [SVector<f64, N>; 3]) {
        Self::floored(robot, m, Arc::new(kept(m)), levels, chunk)
    }

    /// [`Signals::new`] on a record handed over: the signals read its
    /// times, raw efforts and velocities from `m` itself, shared, rather
    /// than from a copy.
    pub fn shared<R: Robot<N>>(
        robot: &R,
        m: &Arc<Measured<N>>,
        levels: Option<&[SVector<f64, N>; 3]>,
        chunk: usize,
    ) -> (Self, [SVector<f64, N>; 3]) {
        Self::floored(robot, m, Arc::clone(m), levels, chunk)
    }

    /// [`Signals::new`], reading `record` (`m`, or what [`kept`] copies of
    /// it) where they read the record as recorded.
    fn floored<R: Robot<N>>(
        robot: &R,
        m: &Measured<N>,
        record: Arc<Measured<N>>,
        levels: Option<&[SVector<f64, N>; 3]>,
        chunk: usize,
    ) -> (Self, [SVector<f64, N>; 3]) {
        let mut sig = Self::made(robot, m, record, chunk);
        let levels = match levels {
            Some(l) => *l,
            None => sensor_levels(m, &sig),
        };
        sig.floor = known_floor(robot, m, &sig, &levels);
        (sig, levels)
    }

    /// The signals of `m` for `robot` without a noise floor (zero): what
    /// an identification by plain least squares, and the floor's own noisy
    /// twin, work on.
    pub fn unfloored<R: Robot<N>>(robot: &R, m: &Measured<N>) -> Self {
        Self::unfloored_chunked(robot, m, 0)
    }

    /// [`Signals::unfloored`], the model evaluated `chunk` samples at a
    /// time (`along.rs`; 0: the default).
    pub fn unfloored_chunked<R: Robot<N>>(robot: &R, m: &Measured<N>, chunk: usize) -> Self {
        Self::made(robot, m, Arc::new(kept(m)), chunk)
    }

    /// [`Signals::unfloored_chunked`], reading `record` (`m`, or what
    /// [`kept`] copies of it) where they read the record as recorded.
    fn made<R: Robot<N>>(
        robot: &R,
        m: &Measured<N>,
        record: Arc<Measured<N>>,
        chunk: usize,
    ) -> Self {
        let n = m.len();
        let dt = m.sample_interval();
        let sg = SavitzkyGolay::analysis(dt);
        let half = sg.half();
        let zero = vec![SVector::<f64, N>::zeros(); n];
        let light = SavitzkyGolay::new(((LIGHT_HALF_WIDTH / dt).round() as usize).max(2), dt);
        let motion = Motion::of(&record, &sg);
        let range = (half, n.saturating_sub(half));
        let mut model = zero.clone();
        let mut residual = zero;
        // The motion a chunk at a time: the model's batches are those of
        // the whole record's motion taken `chunk` samples at a time.
        for c in along::chunks(range.0..range.1, chunk) {
            let [q, qd, qdd] = motion.stretch(c.start, c.end);
            let len = c.len();
            along::inverse_dynamics(robot, [&q, &qd, &qdd], 0..len, len, &mut model[c]);
        }
        for k in range.0..range.1 {
            residual[k] = smoothed_effort(&sg, &record.tau, k) - model[k];
        }
        let mask = Mask::new(m, half, range);
        Signals {
            mask,
            dt,
            range,
            t: Times(Arc::clone(&record)),
            motion,
            qd_measured: m.qd_measured,
            light,
            record,
            model,
            residual,
            floor: SVector::zeros(),
            sg,
        }
    }

    /// Smoothed positions at sample `k` ([`Motion::q`]).
    pub fn q(&self, k: usize) -> SVector<f64, N> {
        self.motion.q(k)
    }

    /// Smoothed velocities at sample `k` ([`Motion::qd`]).
    pub fn qd(&self, k: usize) -> SVector<f64, N> {
        self.motion.qd(k)
    }

    /// Accelerations at sample `k` (derivative of the smoothing fit,
    /// [`Motion::qdd`]).
    pub fn qdd(&self, k: usize) -> SVector<f64, N> {
        self.motion.qdd(k)
    }

    /// Measured efforts, raw (the record's own).
    pub fn tau_raw(&self) -> &[SVector<f64, N>] {
        &self.record.tau
    }

    /// The measured efforts smoothed by the filter at sample `k` (NaN
    /// where its window does not fit), made where asked from the raw
    /// efforts rather than kept for every sample.
    pub fn tau(&self, k: usize) -> SVector<f64, N> {
        smoothed_effort(&self.sg, &self.record.tau, k)
    }

    /// Joint `j` of [`Signals::tau`].
    pub fn tau_at(&self, k: usize, j: usize) -> f64 {
        smoothed_effort_at(&self.sg, &self.record.tau, k, j)
    }

    /// Velocities smoothed only lightly (by [`Signals::light`]) at sample
    /// `k`, NaN where its window does not fit: the argument of effects
    /// that are nonlinear in the velocity, whose columns are then
    /// filtered as the residual shows them. Made where asked from the
    /// measured velocities (else the rate of the measured positions),
    /// the same values as the filter over the whole record, rather than
    /// kept for every sample.
    pub fn qd_light(&self, k: usize) -> SVector<f64, N> {
        SVector::from_fn(|j, _| self.qd_light_at(k, j))
    }

    /// Joint `j` of [`Signals::qd_light`].
    pub fn qd_light_at(&self, k: usize, j: usize) -> f64 {
        let (x, d) = if self.qd_measured {
            (&self.record.qd, 0)
        } else {
            (&self.record.q, 1)
        };
        self.light.at_joint(x, d, k, j)
    }

    /// Rate of the model efforts at sample `k`: the derivative of their
    /// smoothing fit over the samples with a full window (`range`), NaN
    /// where the filter's window reaches outside them. Made where asked
    /// (a late channel's fallback, `shift.rs`) rather than kept for every
    /// sample, from these signals' `model`.
    pub fn model_rate(&self, k: usize) -> SVector<f64, N> {
        let h = self.sg.half();
        let (a, z) = self.range;
        let w = self.sg.weights(1);
        SVector::from_fn(|j, _| {
            if k < h || k + h >= self.model.len() {
                return f64::NAN;
            }
            w.iter()
                .zip(k - h..=k + h)
                .map(|(w, i)| {
                    w * if i >= a && i < z {
                        self.model[i][j]
                    } else {
                        f64::NAN
                    }
                })
                .sum()
        })
    }

    /// Number of samples with a full window.
    pub fn valid(&self) -> usize {
        self.range.1.saturating_sub(self.range.0)
    }
}

/// Joint `j` of the measured efforts `raw` smoothed by `sg` at sample
/// `k` (NaN where its window does not fit). Efforts are held from each
/// sample to the next (zero-order hold): centred on a sample, the held
/// signal averages this sample's value and the previous one's (half a
/// sample late otherwise, a delay the fit would read as an effect).
fn smoothed_effort_at<const N: usize>(
    sg: &SavitzkyGolay,
    raw: &[SVector<f64, N>],
    k: usize,
    j: usize,
) -> f64 {
    let h = sg.half();
    if k < h || k + h >= raw.len() {
        return f64::NAN;
    }
    sg.weights(0)
        .iter()
        .zip(k - h..=k + h)
        .map(|(w, i)| w * (0.5 * (raw[i.saturating_sub(1)][j] + raw[i][j])))
        .sum()
}

/// [`smoothed_effort_at`] at every joint, to the bit: each joint's sum
/// term by term in the same order, the joints' sums side by side (one
/// chain of dependent additions for all of them, not one a joint).
fn smoothed_effort<const N: usize>(
    sg: &SavitzkyGolay,
    raw: &[SVector<f64, N>],
    k: usize,
) -> SVector<f64, N> {
    let h = sg.half();
    if k < h || k + h >= raw.len() {
        return SVector::from_element(f64::NAN);
    }
    // The value a float sum starts from (`Iterator::sum`).
    let start: f64 = std::iter::empty::<f64>().sum();
    let mut s = SVector::<f64, N>::from_element(start);
    for (w, i) in sg.weights(0).iter().zip(k - h..=k + h) {
        let (a, b) = (&raw[i.saturating_sub(1)], &raw[i]);
        for j in 0..N {
            s[j] += w * (0.5 * (a[j] + b[j]));
        }
    }
    s
}

/// 1.4826 x median absolute deviation from the median.
pub fn robust_std(x: &[f64]) -> f64 {
    if x.is_empty() {
        return 0.0;
    }
    let mut v = x.to_vec();
    v.sort_by(f64::total_cmp);
    let med = v[v.len() / 2];
    let mut dev: Vec<f64> = v.iter().map(|a| (a - med).abs()).collect();
    dev.sort_by(f64::total_cmp);
    1.4826 * dev[dev.len() / 2]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::effects::Effect;
    use crate::synth::{synthesize, SynthOptions};
    use crate::test_robots::Arm2;

    fn column<const N: usize>(v: &[SVector<f64, N>], j: usize) -> Vec<f64> {
        v.iter().map(|x| x[j]).collect()
    }

    /// A record of `duration` seconds generated with `effect` (seed `seed`).
    fn generated(robot: &Arm2, duration: f64, seed: u64, effect: Effect) -> Measured<2> {
        let opts = SynthOptions {
            duration,
            seed,
            ..Default::default()
        };
        synthesize(robot, &[effect], &opts).expect("a generated record")
    }

    /// The model's rate at every sample, made where asked, is the whole
    /// record's filter output to the bit (NaN where the window leaves the
    /// samples with a full window).
    #[test]
    fn the_model_rate_at_a_sample_is_the_whole_records() {
        let robot = Arm2::default();
        let m = generated(
            &robot,
            2.0,
            4,
            Effect::ViscousFriction { joint: 1, fv: 0.3 },
        );
        let sig = Signals::unfloored(&robot, &m);
        let (a, z) = sig.range;
        assert!(z > a + 2 * sig.sg.half());
        for j in 0..2 {
            let mj: Vec<f64> = (0..sig.model.len())
                .map(|k| {
                    if k >= a && k < z {
                        sig.model[k][j]
                    } else {
                        f64::NAN
                    }
                })
                .collect();
            let whole = sig.sg.apply(&mj, 1);
            let mut finite = 0;
            for (k, w) in whole.iter().enumerate() {
                let at = sig.model_rate(k)[j];
                assert_eq!(at.is_nan(), w.is_nan(), "sample {k}");
                if w.is_finite() {
                    assert_eq!(at.to_bits(), w.to_bits(), "sample {k}");
                    finite += 1;
                }
            }
            assert!(finite > 1000, "{finite}");
        }
    }

    /// The smoothed motion at every sample, made where asked (alone, at
    /// one joint, or over a stretch), is the filter's output over the
    /// whole record to the bit (NaN where its window does not fit), from
    /// the measured velocities or else the positions; and the model's
    /// efforts made from it a chunk at a time are the inverse dynamics of
    /// the whole record's filtered motion.
    #[test]
    fn the_motion_at_a_sample_is_the_whole_records() {
        let robot = Arm2::default();
        let made = generated(
            &robot,
            1.0,
            5,
            Effect::ViscousFriction { joint: 1, fv: 0.2 },
        );
        for measured in [true, false] {
            let m = Measured {
                qd_measured: measured,
                ..made.clone()
            };
            let n = m.len();
            let mut whole = [
                vec![SVector::<f64, 2>::zeros(); n],
                vec![SVector::zeros(); n],
                vec![SVector::zeros(); n],
            ];
            for j in 0..2 {
                let (q, v) = (column(&m.q, j), column(&m.qd, j));
                let cols = if measured {
                    [
                        sig_apply(&m, &q, 0),
                        sig_apply(&m, &v, 0),
                        sig_apply(&m, &v, 1),
                    ]
                } else {
                    [
                        sig_apply(&m, &q, 0),
                        sig_apply(&m, &q, 1),
                        sig_apply(&m, &q, 2),
                    ]
                };
                for (d, col) in cols.iter().enumerate() {
                    for (k, x) in col.iter().enumerate() {
                        whole[d][k][j] = *x;
                    }
                }
            }
            let same = |a: f64, b: f64| a.to_bits() == b.to_bits();
            for chunk in [7, 4096] {
                let sig = Signals::unfloored_chunked(&robot, &m, chunk);
                let mo = &sig.motion;
                let stretch = mo.stretch(13, n);
                let mut finite = 0;
                for k in 0..n {
                    let at = [sig.q(k), sig.qd(k), sig.qdd(k)];
                    for d in 0..3 {
                        for j in 0..2 {
                            let w = whole[d][k][j];
                            let one = [mo.q_at(k, j), mo.qd_at(k, j), mo.qdd_at(k, j)][d];
                            assert!(same(at[d][j], w), "measured {measured}, d {d}, sample {k}");
                            assert!(same(one, w), "measured {measured}, d {d}, sample {k}");
                            if k >= 13 {
                                assert!(same(stretch[d][k - 13][j], w), "sample {k}");
                            }
                            finite += usize::from(w.is_finite());
                        }
                    }
                }
                assert!(finite > 5000, "{finite}");
                let mut model = vec![SVector::<f64, 2>::zeros(); n];
                let (a, z) = sig.range;
                along::inverse_dynamics(
                    &robot,
                    [&whole[0], &whole[1], &whole[2]],
                    a..z,
                    chunk,
                    &mut model,
                );
                for k in 0..n {
                    for j in 0..2 {
                        assert!(same(sig.model[k][j], model[k][j]), "model at {k}");
                    }
                }
                assert!(model[a + 1].norm() > 0.0);
            }
        }
    }

    /// The analysis filter of `m` over `x`, derivative `d`.
    fn sig_apply(m: &Measured<2>, x: &[f64], d: usize) -> Vec<f64> {
        SavitzkyGolay::analysis(m.sample_interval()).apply(x, d)
    }

    /// The lightly smoothed velocity at every sample, made where asked,
    /// is the light filter's output over the whole record to the bit
    /// (NaN where its window does not fit), from the measured velocities
    /// or else the rate of the positions.
    #[test]
    fn the_light_velocity_at_a_sample_is_the_whole_records() {
        let robot = Arm2::default();
        let made = generated(
            &robot,
            1.0,
            8,
            Effect::ViscousFriction { joint: 0, fv: 0.2 },
        );
        for measured in [true, false] {
            let m = Measured {
                qd_measured: measured,
                ..made.clone()
            };
            let sig = Signals::unfloored(&robot, &m);
            let mut finite = 0;
            for j in 0..2 {
                let whole = if measured {
                    sig.light.apply(&column(&m.qd, j), 0)
                } else {
                    sig.light.apply(&column(&m.q, j), 1)
                };
                assert_eq!(whole.len(), m.len());
                for (k, w) in whole.iter().enumerate() {
                    let at = sig.qd_light_at(k, j);
                    assert_eq!(sig.qd_light(k)[j].to_bits(), at.to_bits(), "sample {k}");
                    assert_eq!(at.is_nan(), w.is_nan(), "sample {k}");
                    if w.is_finite() {
                        assert_eq!(at.to_bits(), w.to_bits(), "sample {k}");
                        finite += 1;
                    }
                }
                assert!(sig.qd_light_at(m.len() + 3, j).is_nan());
            }
            assert!(finite > 1900, "{finite}");
        }
    }

    /// Signals of a record handed over read its times and efforts from
    /// the record itself, and are the same as those of the record lent.
    #[test]
    fn signals_of_a_record_handed_over_share_it() {
        let robot = Arm2::default();
        let m = generated(
            &robot,
            1.0,
            9,
            Effect::ViscousFriction { joint: 1, fv: 0.3 },
        );
        let (lent, levels) = Signals::new(&robot, &m, None, 64);
        let handed = Arc::new(m.clone());
        let (shared, shared_levels) = Signals::shared(&robot, &handed, None, 64);
        assert!(Arc::ptr_eq(&shared.record, &handed));
        assert_eq!(shared.t.as_ptr(), handed.t.as_ptr());
        assert_eq!(shared.tau_raw().as_ptr(), handed.tau.as_ptr());
        assert!(!Arc::ptr_eq(&lent.record, &handed));
        assert_eq!(levels, shared_levels);
        assert_eq!(lent.floor, shared.floor);
        assert_eq!(&lent.t[..], &shared.t[..]);
        assert_eq!(lent.tau_raw(), shared.tau_raw());
        assert_eq!(lent.model, shared.model);
        assert_eq!(lent.residual, shared.residual);
        for k in 0..m.len() {
            for j in 0..2 {
                let (a, b) = (lent.qd_light_at(k, j), shared.qd_light_at(k, j));
                assert_eq!(a.to_bits(), b.to_bits(), "sample {k}");
            }
        }
    }

    /// The smoothed effort at every sample, made where asked, is the
    /// whole record's held and filtered effort to the bit, and the residual
    /// is it minus the model.
    #[test]
    fn the_smoothed_effort_at_a_sample_is_the_whole_records() {
        let robot = Arm2::default();
        let m = generated(
            &robot,
            2.0,
            6,
            Effect::CoulombFriction {
                joint: 0,
                fc: 0.4,
                vw: 0.01,
            },
        );
        let sig = Signals::unfloored(&robot, &m);
        let (a, z) = sig.range;
        for j in 0..2 {
            let raw: Vec<f64> = m.tau.iter().map(|x| x[j]).collect();
            let held: Vec<f64> = (0..raw.len())
                .map(|k| 0.5 * (raw[k.saturating_sub(1)] + raw[k]))
                .collect();
            let whole = sig.sg.apply(&held, 0);
            for (k, w) in whole.iter().enumerate() {
                let at = sig.tau_at(k, j);
                assert_eq!(at.is_nan(), w.is_nan(), "sample {k}");
                assert_eq!(sig.tau(k)[j].to_bits(), at.to_bits(), "sample {k}");
                if w.is_finite() {
                    assert_eq!(at.to_bits(), w.to_bits(), "sample {k}");
                }
                if k >= a && k < z {
                    let r = w - sig.model[k][j];
                    assert_eq!(sig.residual[k][j].to_bits(), r.to_bits(), "sample {k}");
                }
            }
        }
    }
}
