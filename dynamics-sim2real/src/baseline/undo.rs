//! What a calibrated baseline cannot fold into the rigid model, undone on
//! measured data before the record is compared with the calibrated model
//! ([`Calibrated`]):
//!
//! - the sensors' effects ([`undo_sensors`]);
//! - the motor sides (elasticity, backlash): they have a state of their
//!   own, so they are no term of the rigid model's mass matrix and forces;
//!   with their known parameters the motor side is simulated along the
//!   record exactly as the diagnosis fits it (driven by the measured
//!   effort, its link following the measured motion), and the joint's
//!   measured effort is replaced by the effort that reaches the link, the
//!   quantity the rigid model predicts;
//! - the effects limited to a window of the record's time: inside the
//!   window, a sensor effect is undone like an always-on one, and a force
//!   or inertia's effort along the measured motion is taken out of the
//!   measured effort.

use nalgebra::SVector;

use crate::data::Measured;
use crate::diagnose::{motor_transmitted_raw, MotorGuess, Prepared, Signals};
use crate::effects::{undo_sensors, Calibrated, Effect, Window};
use dynamics_runtime::Robot;

/// Why a baseline could not be undone on a record.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum UndoError {
    /// The motor side's simulation gave no effort along the record.
    #[error(
        "effect `{kind}` at joint {joint}: the motor side's simulation along the record {cause}"
    )]
    Motor {
        /// Its kind's name.
        kind: &'static str,
        /// The joint's name.
        joint: String,
        /// What went wrong.
        cause: &'static str,
    },
    /// A force limited to a window that cannot be evaluated on its own.
    #[error("effect `{kind}` limited to a window: {cause}")]
    Windowed {
        /// Its kind's name.
        kind: &'static str,
        /// The cause.
        cause: String,
    },
}

/// `m` with what `robot`'s baseline keeps apart from the rigid model
/// undone, in the order the effects act on the record: the sensors'
/// effects (always on, then those limited to a window, inside it), the
/// motor sides (the measured effort of their joint replaced by the effort
/// the motor side passes to the link: see below), then the forces limited
/// to a window (their effort along the measured motion subtracted inside
/// it). A record without such effects comes back as it is.
///
/// **Motor sides.** The simulation is the diagnosis's own
/// (`diagnose/fit/motor_sim`): the motor inertia driven by the measured
/// effort (held over each sample's interval) through the coupling
/// (elasticity's spring and damper, backlash's dead zone and contact), the
/// link following the measured motion plus what the transmitted effort
/// changes over the calibrated model's, pulled back to the measurement.
/// The coupling's force at each sample is the effort that reaches the
/// link; the record's effort becomes its mean over each sample's interval
/// (the record's convention: an effort is held from its sample to the
/// next). The simulation needs the smoothing's full window: the first and
/// last half-window of samples keep their measured effort (no fit row's
/// window reaches them).
///
/// **Windows** are in the record's own times (as the report writes them,
/// the training record's): on the same record, or a run of the same
/// schedule, they undo the effect where it was on. On another record, an
/// effect on at other times needs its window changed, or the entry left
/// out.
///
/// ```
/// use dynamics_runtime::Robot;
/// use dynamics_sim2real::baseline::undo;
/// use dynamics_sim2real::effects::{Calibrated, Effect, Window};
/// use dynamics_sim2real::synth::{synthesize, SynthOptions};
/// dynamics_macros::robot! {
///     pub robot Pendulum; gravity = [0.0, -9.81, 0.0];
///     link base; link rod { mass = 1.0; com = [0.5, 0.0, 0.0]; inertia = [0.01, 0.02, 0.02]; }
///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
/// }
/// let slip = Effect::EffortOffset { joint: 0, offset: 0.3 };
/// let held: Window = "1:2".parse().unwrap();
/// let options = SynthOptions::<1> { duration: 3.0, windows: vec![Some(held)], ..Default::default() };
/// let m = synthesize(&Pendulum::default(), &[slip], &options).unwrap();
/// let r = Calibrated::timed(Pendulum::default(), vec![(slip, Some(held))]).unwrap();
/// let fixed = undo(&r, &m).unwrap();
/// for k in 0..m.len() {
///     let taken = if held.contains(m.t[k]) { 0.3 } else { 0.0 };
///     assert!((m.tau[k][0] - fixed.tau[k][0] - taken).abs() < 1e-12);
/// }
/// ```
pub fn undo<R: Robot<N> + Clone + Send + Sync + 'static, const N: usize>(
    robot: &Calibrated<R, N>,
    m: &Measured<N>,
) -> Result<Measured<N>, UndoError> {
    let mut out = undo_sensors(m, robot.sensor_effects());
    for (e, w) in robot
        .windowed_effects()
        .iter()
        .filter(|(e, _)| e.is_sensor())
    {
        let fixed = undo_sensors(&out, std::slice::from_ref(e));
        for k in (0..out.len()).filter(|&k| w.contains(out.t[k])) {
            out.q[k] = fixed.q[k];
            out.qd[k] = fixed.qd[k];
            out.tau[k] = fixed.tau[k];
        }
    }
    if !robot.motor_effects().is_empty() {
        out = transmitted(robot, out)?;
    }
    let forces: Vec<(Effect, Window)> = robot
        .windowed_effects()
        .iter()
        .filter(|(e, _)| !e.is_sensor())
        .copied()
        .collect();
    if !forces.is_empty() {
        windowed_forces(robot.nominal(), &forces, &mut out)?;
    }
    Ok(out)
}

/// The motor side of `e` as the diagnosis's simulation takes it, and
/// whether it is backlash.
fn guess(e: &Effect) -> Option<(usize, MotorGuess, bool)> {
    match *e {
        Effect::JointElasticity {
            joint,
            stiffness,
            damping,
            motor_inertia,
        } => Some((
            joint,
            MotorGuess {
                jm: motor_inertia,
                stiffness,
                damping,
                half_width: 0.0,
            },
            false,
        )),
        Effect::Backlash {
            joint,
            half_width,
            motor_inertia,
            contact_stiffness,
            contact_damping,
        } => Some((
            joint,
            MotorGuess {
                jm: motor_inertia,
                stiffness: contact_stiffness,
                damping: contact_damping,
                half_width,
            },
            true,
        )),
        _ => None,
    }
}

/// `m` with the effort of every motor side's joint replaced by what its
/// motor side passes to the link (see [`undo`]).
fn transmitted<R: Robot<N> + Clone + Send + Sync + 'static, const N: usize>(
    robot: &Calibrated<R, N>,
    mut m: Measured<N>,
) -> Result<Measured<N>, UndoError> {
    let p = Prepared::new(robot, &m);
    let (a, z) = p.sig.range;
    for e in robot.motor_effects() {
        let Some((j, g, backlash)) = guess(e) else {
            continue;
        };
        let fail = |cause| UndoError::Motor {
            kind: e.kind().name(),
            joint: R::JOINT_NAMES.get(j).unwrap_or(&"?").to_string(),
            cause,
        };
        if z <= a + 1 {
            return Err(fail(
                "is too short: the record has no full smoothing window",
            ));
        }
        let t = motor_transmitted_raw(&p.sig, j, &g, backlash, &p.basis.compliance);
        if t.len() < z || t[a..z].iter().any(|x| !x.is_finite()) {
            return Err(fail("diverged"));
        }
        // The mean over each sample's interval (trapezoid) of the force
        // at the samples; the last sample's interval has no end, and the
        // sample before the first (when there is one) takes the first's.
        for k in a..z {
            let next = if k + 1 < z { t[k + 1] } else { t[k] };
            m.tau[k][j] = 0.5 * (t[k] + next);
        }
        if a > 0 {
            m.tau[a - 1][j] = t[a];
        }
    }
    Ok(m)
}

/// The efforts of `forces` (each with its window) along the smoothed
/// measured motion of `m`, taken out of its effort inside their windows:
/// each effort is what the effect alone adds to `nominal`'s inverse
/// dynamics.
fn windowed_forces<R: Robot<N> + Clone + Send + Sync + 'static, const N: usize>(
    nominal: &R,
    forces: &[(Effect, Window)],
    m: &mut Measured<N>,
) -> Result<(), UndoError> {
    let sig = Signals::unfloored(nominal, m);
    let (a, z) = sig.range;
    for (e, w) in forces {
        let with =
            Calibrated::new(nominal.clone(), vec![*e]).map_err(|err| UndoError::Windowed {
                kind: e.kind().name(),
                cause: err.to_string(),
            })?;
        for k in (0..m.len()).filter(|&k| w.contains(m.t[k])) {
            // Outside the smoothing's range (no fit row reaches it) the
            // measured position and velocity, at no acceleration.
            let (q, qd, qdd) = match (a..z).contains(&k) {
                true => (sig.q(k), sig.qd(k), sig.qdd(k)),
                false => (m.q[k], m.qd[k], SVector::zeros()),
            };
            let added =
                with.inverse_dynamics(&q, &qd, &qdd) - nominal.inverse_dynamics(&q, &qd, &qdd);
            m.tau[k] -= added;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests;
