//! The effect a synthesis request asks for: drawn where the request leaves
//! kind, joint or size open (a rotor only where the controller can carry
//! it), the size set where it gives one.

use dynamics_runtime::Robot;
use dynamics_sim2real::effects::{Effect, EffectKind, Tip};
use dynamics_sim2real::synth::{draw_effect, Rng, Scales, SynthOptions};

use super::{GapError, SynthRequest};

/// Largest ratio of a joint's locked to free inertia at which a drawn
/// rotor (armature, or the motor side of elasticity and backlash: 5-30 %
/// of the locked inertia) may sit there. arm3r's joints reach 12, the rrp
/// arm's q1 and q2 about 70.
const MOTOR_RATIO: f64 = 15.0;

/// The effect a request asks for (drawn where it leaves things open).
pub(super) fn effect_for<R: Robot<N>, const N: usize>(
    robot: &R,
    req: &SynthRequest,
    opts: &SynthOptions<N>,
    rng: &mut Rng,
) -> Result<Option<Effect>, GapError> {
    let kind = match req.kind {
        Some(k) => k,
        None => EffectKind::ALL[1 + rng.below(EffectKind::ALL.len() - 1)],
    };
    let reference = opts.reference();
    let scales = Scales::of(robot, &reference, opts.duration);
    let joint = match &req.joint {
        Some(name) => R::joint_index(name).ok_or_else(|| {
            GapError::Request(format!(
                "robot `{}` has no joint `{name}` (joints: {})",
                req.robot,
                R::JOINT_NAMES.join(", ")
            ))
        })?,
        None => {
            // A rotor (armature, motor side: a share of the joint's locked
            // inertia, see `draw_effect`) only where the controller can
            // carry it: see MOTOR_RATIO. (On the rrp arm, a 10 kg point
            // load on links of a few hundredths of a kg m^2, q1 and q2 move
            // 70 times more inertia locked than free: a rotor there leaves
            // their light direction almost without stiffness under the
            // nominal computed-torque loop, and the run drifts off.)
            let motor = matches!(
                kind,
                EffectKind::Armature | EffectKind::JointElasticity | EffectKind::Backlash
            );
            let carried: Vec<usize> = (0..N)
                .filter(|&j| !motor || scales.inertia[j] <= MOTOR_RATIO * scales.free_inertia[j])
                .collect();
            let carried = if carried.is_empty() {
                (0..N).collect()
            } else {
                carried
            };
            // Angle-based magnitudes (backlash, offsets) go to revolute joints.
            let revolute: Vec<usize> = carried
                .iter()
                .copied()
                .filter(|&j| R::JOINT_KINDS[j] == dynamics_runtime::JointKind::Revolute)
                .collect();
            let pool: Vec<usize> = if revolute.is_empty() {
                carried
            } else {
                revolute
            };
            pool[rng.below(pool.len())]
        }
    };
    let tip = Tip::of::<R, N>();
    let tip_speed = (0..=200)
        .map(|k| {
            let r = reference.at(opts.duration * k as f64 / 200.0);
            (tip.position_jacobian(robot, &r.q).1 * r.qd).norm()
        })
        .fold(0.0, f64::max);
    let drawn = draw_effect(kind, joint, &scales, &R::JOINT_KINDS, tip_speed, rng);
    let Some(m) = req.magnitude else {
        return Ok(drawn);
    };
    if !m.is_finite() {
        return Err(GapError::Request(format!(
            "magnitude must be finite, got {m}"
        )));
    }
    Ok(drawn.map(|e| match e {
        Effect::CoulombFriction { joint, vw, .. } => Effect::CoulombFriction { joint, fc: m, vw },
        Effect::ViscousFriction { joint, .. } => Effect::ViscousFriction { joint, fv: m },
        Effect::StribeckFriction { joint, .. } => Effect::StribeckFriction {
            joint,
            fc: m,
            fs: 1.5 * m,
            vs: 0.05,
        },
        Effect::Armature { joint, .. } => Effect::Armature { joint, inertia: m },
        // The magnitude is the mass change (never drawn here yet).
        Effect::InertialParameters { link, mut delta } => {
            delta[0] = m;
            Effect::InertialParameters { link, delta }
        }
        Effect::PayloadMass { com, .. } => Effect::PayloadMass { mass: m, com },
        Effect::JointElasticity {
            joint,
            motor_inertia,
            ..
        } => {
            let inertia = scales.free_inertia[joint];
            let w = 2.0 * std::f64::consts::PI * m;
            let stiffness = w * w / (1.0 / motor_inertia + 1.0 / inertia);
            Effect::JointElasticity {
                joint,
                stiffness,
                damping: 0.1 * (stiffness * motor_inertia).sqrt(),
                motor_inertia,
            }
        }
        Effect::Backlash {
            joint,
            motor_inertia,
            contact_stiffness,
            contact_damping,
            ..
        } => Effect::Backlash {
            joint,
            half_width: m,
            motor_inertia,
            contact_stiffness,
            contact_damping,
        },
        Effect::EnvironmentResistance { .. } => Effect::EnvironmentResistance { mu: m, alpha: 2.0 },
        Effect::EncoderOffset { joint, .. } => Effect::EncoderOffset { joint, offset: m },
        Effect::TimeDelay { .. } => Effect::TimeDelay { delay: m },
        Effect::EffortScale { joint, .. } => Effect::EffortScale { joint, scale: m },
        Effect::EffortOffset { joint, .. } => Effect::EffortOffset { joint, offset: m },
        // The magnitude is the stiffness; the drawn rest position is kept.
        Effect::JointSpring {
            joint,
            stiffness,
            preload,
        } => Effect::JointSpring {
            joint,
            stiffness: m,
            preload: if stiffness > 0.0 {
                preload * m / stiffness
            } else {
                0.0
            },
        },
    }))
}
