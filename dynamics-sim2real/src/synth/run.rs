//! One synthetic experiment: the plant with the withheld effects, the
//! reference, the cascade controller built on the nominal model, and the
//! sensors (noise, encoder offsets, delay, a late position or effort
//! channel).

use nalgebra::SVector;

use super::phases::Phases;
use super::sensors::{delayed, effort_at};
use super::{Excitation, Noise, Rng, Scales, SynthError, SynthOptions};
use crate::data::Measured;
use crate::effects::{smooth_sign, Effect};
use crate::smoothing::SavitzkyGolay;
use dynamics_runtime::control::Reference;
use dynamics_runtime::ode::Tolerances;
use dynamics_runtime::Robot;

/// A velocity reverses when it reaches this fraction of its peak speed on
/// both sides of zero.
const REVERSAL: f64 = 0.05;
/// The effect's size is measured away from the record's ends by this much,
/// s: the half-width of the diagnosis's smoothing (`diagnose::signals`),
/// where no differentiating filter of that width has a full window. What
/// happens there is not in the data an analysis of the motion uses: a
/// joint started at the reference's speed and stopped by its friction
/// within 10 ms (a generated Stribeck case at 100 Hz: +0.12 rad/s at t = 0,
/// never positive again) counted as reversing, and its start-up as
/// breakaway, on one sample.
const EDGE: f64 = 0.04;

/// One experiment: the plant, the reference, the controller, the sensors.
pub(super) struct Run<'a, R, const N: usize> {
    robot: &'a R,
    /// The plants of the effects on at a time (windows), and the sensor
    /// effects on at a time.
    phases: Phases<R, N>,
    reference: Excitation<N>,
    pub(super) scales: Scales<N>,
    opts: &'a SynthOptions<N>,
    delay: f64,
    /// Joints whose drive turns a motor side (elasticity, backlash): their
    /// velocity loop reads the motor speed.
    motor: [bool; N],
    /// Joints with a Stribeck friction, which contains a Coulomb friction.
    stribeck: [bool; N],
    /// The random stream after the reference was drawn (sensor noise).
    pub(super) rng: Rng,
}

impl<'a, R: Robot<N> + Clone, const N: usize> Run<'a, R, N> {
    pub(super) fn new(
        robot: &'a R,
        effects: &[Effect],
        opts: &'a SynthOptions<N>,
    ) -> Result<Self, SynthError> {
        if !(opts.rate.is_finite()
            && opts.rate > 0.0
            && opts.duration.is_finite()
            && opts.duration > 0.0)
        {
            return Err(SynthError::Options(format!(
                "duration ({}) and rate ({}) must be positive",
                opts.duration, opts.rate
            )));
        }
        let phases = Phases::new(robot, effects, &opts.windows)?;
        let mut rng = Rng::new(opts.seed);
        let reference = opts.drawn_reference(&mut rng);
        let scales = Scales::of(robot, &reference, opts.duration);
        let mut delay = 0.0;
        let mut motor = [false; N];
        let mut stribeck = [false; N];
        for e in effects {
            if let (true, Some(j)) = (e.has_motor(), e.joint()) {
                motor[j.min(N - 1)] = true;
            }
            if let Effect::StribeckFriction { joint, .. } = *e {
                stribeck[joint.min(N - 1)] = true;
            }
            if let Effect::TimeDelay { delay: d } = *e {
                delay += d;
            }
        }
        Ok(Run {
            robot,
            phases,
            reference,
            scales,
            opts,
            delay,
            motor,
            stribeck,
            rng,
        })
    }

    /// Runs the experiment with sensor noise `noise`; returns what the
    /// sensors recorded and, per joint, the RMS of the recorded effort minus
    /// the nominal inverse dynamics of the noise-free sensor readings, and
    /// of what of it the simpler effect the withheld one contains does not
    /// explain: a rigid rotor at the motor joints, a Coulomb friction where
    /// the friction is Stribeck's.
    #[allow(clippy::type_complexity)]
    pub(super) fn record(
        &self,
        noise: Noise,
        rng: &mut Rng,
    ) -> Result<(Measured<N>, SVector<f64, N>, SVector<f64, N>), SynthError> {
        let (robot, opts) = (self.robot, self.opts);
        let times = clock(opts);
        let n = times.len();
        let r0 = self.reference.at(0.0);
        let mut sim = self.phases.first().start(r0.q, r0.qd);
        let tol = Tolerances {
            rtol: 1e-9,
            atol: 1e-11,
            ..Default::default()
        };
        let kp = opts.bandwidth * opts.bandwidth;
        let kd = 2.0 * opts.bandwidth;
        let mut truth: Vec<(SVector<f64, N>, SVector<f64, N>)> = Vec::with_capacity(n);
        // Noise-free sensor readings, applied efforts and the efforts
        // recorded, for the effect size.
        let mut seen: Vec<(SVector<f64, N>, SVector<f64, N>)> = Vec::with_capacity(n);
        let mut applied: Vec<SVector<f64, N>> = Vec::with_capacity(n);
        // What the effort sensor reported of them (noise-free).
        let mut recorded: Vec<SVector<f64, N>> = Vec::with_capacity(n);
        let mut out = Measured::<N> {
            qd_measured: true,
            ..Default::default()
        };
        for k in 0..n {
            let t = times[k];
            truth.push((sim.state.q, sim.state.qd));
            // What the sensors report: late by `delay` (the positions by
            // `q_late` more), shifted by the offsets.
            let past = &times[..=k];
            let (q_seen, qd_seen) = delayed(past, &truth, t - self.delay, &truth[0]);
            let q_seen = if opts.damage.q_late > 0.0 {
                delayed(past, &truth, t - self.delay - opts.damage.q_late, &truth[0]).0
            } else {
                q_seen
            };
            let q_seen = q_seen + self.phases.offset_at(t);
            seen.push((q_seen, qd_seen));
            let q_meas = q_seen + rng.normal_vec(&SVector::repeat(noise.q));
            let qd_meas = qd_seen + rng.normal_vec(&SVector::repeat(noise.qd));
            let r: Reference<N> = self.reference.at(t);
            // The drive's velocity loop: the motor encoder where there is
            // a motor side, else the (one) joint speed.
            let drive_qd = SVector::<f64, N>::from_fn(|j, _| {
                if self.motor[j] {
                    sim.state.qmd[j] + noise.qd * rng.normal()
                } else {
                    qd_meas[j]
                }
            });
            let v = r.qdd + (r.q - q_meas) * kp + (r.qd - drive_qd) * kd;
            let tau = robot.inverse_dynamics(&q_meas, &qd_meas, &v);
            applied.push(tau);
            // What the effort sensor reports: the applied effort, or the
            // one applied `tau_late` earlier.
            let tau_seen = if opts.damage.tau_late > 0.0 {
                effort_at(past, &applied, t - opts.damage.tau_late)
            } else {
                tau
            };
            recorded.push(tau_seen);
            let mut tau_meas = tau_seen;
            for j in 0..N {
                tau_meas[j] += noise.tau_relative * self.scales.peak_effort[j] * rng.normal();
            }
            for j in 0..N {
                let error = (sim.state.q[j] - r.q[j]).abs();
                // (NaN counts as off too.)
                if error.is_nan() || error > 5.0 * opts.amplitude[j].abs() + 1e-3 {
                    return Err(SynthError::Unstable { t, joint: j, error });
                }
            }
            out.t.push(t);
            out.q.push(q_meas);
            out.qd.push(qd_meas);
            out.tau.push(tau_meas);
            if k + 1 < n {
                let drive = Effect::applied_effort(&self.phases.sensor_at(t), &tau);
                sim.advance(self.phases.plant_at(t), times[k + 1], &drive, tol)?;
            }
        }
        // The effort is held over each sample interval: around sample k the
        // motion's mean acceleration (central difference of the velocity)
        // answers the mean of the efforts held before and after it.
        // Per joint: the gap, and x the column of the simpler effect
        // contained (the acceleration for a rigid rotor at the motor
        // joints, the friction's sign for a Coulomb friction within a
        // Stribeck one). A Stribeck friction is measured against a Coulomb
        // one only where the velocity never reverses: there the Coulomb
        // friction is a constant effort and only the low-speed rise tells
        // Stribeck's apart, if the joint ever slows to it; where it
        // reverses, the breakaway shows at every reversal, brief but clear
        // (on a generated MAR case whose rise is 0.31 of one sample's noise
        // in RMS over the record, the diagnosis named Stribeck's 25 AICc
        // ahead of Coulomb's), and the whole effect counts.
        let nan = SVector::<f64, N>::repeat(f64::NAN);
        let (mut gaps, mut xs) = (vec![nan; n], vec![nan; n]);
        for k in 1..n.saturating_sub(1) {
            let qdd = (seen[k + 1].1 - seen[k - 1].1) / (times[k + 1] - times[k - 1]);
            let held = (recorded[k - 1] + recorded[k]) * 0.5;
            gaps[k] = held - robot.inverse_dynamics(&seen[k].0, &seen[k].1, &qdd);
            xs[k] = SVector::<f64, N>::from_fn(|j, _| {
                if self.stribeck[j] && !self.motor[j] {
                    smooth_sign(seen[k].1[j])
                } else {
                    qdd[j]
                }
            });
        }
        // Both as the diagnosis sees them, through its smoothing: what
        // lies above the band it passes (a backlash's contact ringing at
        // 60 Hz and more) is in no fit of the diagnosis, and its size in
        // RMS of the smoothed signal is on the scale of one sample's noise
        // (the smoothing shrinks that noise as it shrinks the evidence per
        // row). On slow effects the same as the raw size.
        let sg = SavitzkyGolay::analysis(1.0 / opts.rate);
        let smoothed = |v: &[SVector<f64, N>]| -> Vec<SVector<f64, N>> {
            let mut out = vec![nan; n];
            for j in 0..N {
                let col: Vec<f64> = v.iter().map(|x| x[j]).collect();
                for (o, c) in out.iter_mut().zip(sg.apply(&col, 0)) {
                    o[j] = c;
                }
            }
            out
        };
        let (gaps, xs) = (smoothed(&gaps), smoothed(&xs));
        // Per joint: sum of gap^2, of gap * x and of x^2.
        let (mut sum, mut cross, mut acc) = (
            SVector::<f64, N>::zeros(),
            SVector::<f64, N>::zeros(),
            SVector::<f64, N>::zeros(),
        );
        // The samples the size is measured on.
        let (t0, t1) = (
            times.first().copied().unwrap_or(0.0) + EDGE,
            times.last().copied().unwrap_or(0.0) - EDGE,
        );
        let inner: Vec<usize> = (1..n.saturating_sub(1))
            .filter(|&k| times[k] >= t0 && times[k] <= t1)
            .collect();
        let mut count = 0usize;
        for &k in &inner {
            let (gap, x) = (gaps[k], xs[k]);
            if !(gap.iter().all(|g| g.is_finite()) && x.iter().all(|x| x.is_finite())) {
                continue;
            }
            sum += gap.component_mul(&gap);
            cross += gap.component_mul(&x);
            acc += x.component_mul(&x);
            count += 1;
        }
        // Whether each joint's velocity reverses (reaches a twentieth of
        // its peak speed on both sides of zero).
        let reverses = SVector::<bool, N>::from_fn(|j, _| {
            let (lo, hi) = inner.iter().fold((0.0f64, 0.0f64), |(lo, hi), &k| {
                (lo.min(seen[k].1[j]), hi.max(seen[k].1[j]))
            });
            let peak = hi.max(-lo);
            hi >= REVERSAL * peak && -lo >= REVERSAL * peak && peak > 0.0
        });
        let count = count.max(1) as f64;
        let effect = (sum / count).map(f64::sqrt);
        let distinct = SVector::<f64, N>::from_fn(|j, _| {
            let contains = self.motor[j] || (self.stribeck[j] && !reverses[j]);
            if contains && acc[j] > 0.0 {
                ((sum[j] - cross[j] * cross[j] / acc[j]).max(0.0) / count).sqrt()
            } else {
                effect[j]
            }
        });
        Ok((out, effect, distinct))
    }
}

/// The controller's sampling times: every `1 / rate`, or with a jittered
/// clock (`Damage::jitter`) each interval scaled by a factor uniform in
/// `1 +- jitter`, drawn from a stream of its own (the sensor noise is the
/// same with and without jitter).
fn clock<const N: usize>(opts: &SynthOptions<N>) -> Vec<f64> {
    let dt = 1.0 / opts.rate;
    let jitter = opts.damage.jitter.clamp(0.0, 0.9);
    if jitter == 0.0 {
        let n = (opts.duration * opts.rate).round() as usize + 1;
        return (0..n).map(|k| k as f64 * dt).collect();
    }
    let mut rng = Rng::new(opts.seed ^ 0x71_77E2);
    let mut times = vec![0.0];
    let mut t = 0.0;
    while t + dt * (1.0 + jitter) <= opts.duration + 1e-12 {
        t += dt * rng.uniform(1.0 - jitter, 1.0 + jitter);
        times.push(t);
    }
    times
}
