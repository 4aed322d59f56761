//! Compound cases: several effects withheld at once, as a real robot has
//! them (friction on every joint and more), drawn from the realistic
//! magnitude ranges of [`draw_effect`](super::draw_effect).

use std::str::FromStr;

use super::{draw_effect, Rng, Scales, SynthOptions};
use crate::effects::{Effect, EffectKind, PlaceKind, Tip};
use dynamics_runtime::{JointKind, Robot};

/// What a compound case withholds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CompoundCase {
    /// A realistic arm: Coulomb and viscous friction on every joint (each
    /// 2-8 % of the joint's peak effort) and one further effect.
    RealisticArm,
    /// Two or three effects of different kinds on different joints.
    Mixed,
    /// Nothing (a control).
    Control,
}

impl FromStr for CompoundCase {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "realistic" => Ok(CompoundCase::RealisticArm),
            "mixed" => Ok(CompoundCase::Mixed),
            "control" => Ok(CompoundCase::Control),
            _ => Err(format!(
                "unknown compound case `{s}`; known: realistic, mixed, control"
            )),
        }
    }
}

/// Largest ratio of a joint's locked to free inertia at which a drawn
/// rotor (armature, the motor side of elasticity and backlash) may sit
/// there: beyond it the nominal computed-torque loop loses the joint's
/// light direction of motion and the run drifts off.
pub const MOTOR_RATIO: f64 = 15.0;

/// The kinds a further effect is drawn from: every kind but `none` and
/// the friction laws (a realistic arm has those already).
const FURTHER: [EffectKind; 10] = [
    EffectKind::Armature,
    EffectKind::PayloadMass,
    EffectKind::JointElasticity,
    EffectKind::Backlash,
    EffectKind::EnvironmentResistance,
    EffectKind::EncoderOffset,
    EffectKind::TimeDelay,
    EffectKind::EffortScale,
    EffectKind::EffortOffset,
    EffectKind::StribeckFriction,
];

/// Draws the effects of a compound case for `robot` moving as `opts`
/// says (the magnitudes are measured against its reference motion).
///
/// ```
/// use dynamics_sim2real::synth::{draw_compound, CompoundCase, Rng, SynthOptions};
/// dynamics_macros::robot! {
///     pub robot Pendulum;
///     gravity = [0.0, -9.81, 0.0];
///     link base;
///     link rod { mass = 1.0; com = [0.5, 0.0, 0.0]; inertia = [1e-4, 0.02, 0.02]; }
///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
/// }
/// let opts = SynthOptions::<1> { duration: 1.0, ..Default::default() };
/// let e = draw_compound(&Pendulum::default(), CompoundCase::RealisticArm, &opts, &mut Rng::new(3));
/// assert!(e.len() >= 2); // Coulomb and viscous friction at the joint (and maybe more)
/// ```
pub fn draw_compound<R: Robot<N>, const N: usize>(
    robot: &R,
    case: CompoundCase,
    opts: &SynthOptions<N>,
    rng: &mut Rng,
) -> Vec<Effect> {
    let reference = opts.reference();
    let scales = Scales::of(robot, &reference, opts.duration);
    let tip = Tip::of::<R, N>();
    let tip_speed = (0..=200)
        .map(|k| {
            let r = reference.at(opts.duration * k as f64 / 200.0);
            (tip.position_jacobian(robot, &r.q).1 * r.qd).norm()
        })
        .fold(0.0, f64::max);
    let mut out = Vec::new();
    let mut used_joints: Vec<usize> = Vec::new();
    let (extra, kinds): (usize, Vec<EffectKind>) = match case {
        CompoundCase::Control => return out,
        CompoundCase::RealisticArm => {
            for j in 0..N {
                let peak = scales.peak_effort[j].max(1e-6);
                out.push(Effect::coulomb(j, peak * rng.uniform(0.02, 0.08)));
                out.push(Effect::ViscousFriction {
                    joint: j,
                    fv: peak * rng.uniform(0.02, 0.08) / scales.peak_speed[j].max(1e-3),
                });
            }
            (1, FURTHER.to_vec())
        }
        CompoundCase::Mixed => (2 + rng.below(2), EffectKind::ALL[1..].to_vec()),
    };
    let mut kinds = kinds;
    for _ in 0..extra {
        // A kind not drawn yet, at a joint not used yet where it can sit.
        for _try in 0..20 {
            if kinds.is_empty() {
                break;
            }
            let kind = kinds.remove(rng.below(kinds.len()));
            if kind.place() != PlaceKind::Joint {
                if let Some(e) = draw_effect(kind, 0, &scales, &R::JOINT_KINDS, tip_speed, rng) {
                    out.push(e);
                }
                break;
            }
            let motor = matches!(
                kind,
                EffectKind::Armature | EffectKind::JointElasticity | EffectKind::Backlash
            );
            let angle = matches!(kind, EffectKind::Backlash | EffectKind::EncoderOffset);
            let pool: Vec<usize> = (0..N)
                .filter(|j| case == CompoundCase::RealisticArm || !used_joints.contains(j))
                .filter(|&j| !motor || scales.inertia[j] <= MOTOR_RATIO * scales.free_inertia[j])
                .filter(|&j| !angle || R::JOINT_KINDS[j] == JointKind::Revolute)
                .collect();
            if pool.is_empty() {
                continue;
            }
            let j = pool[rng.below(pool.len())];
            if let Some(e) = draw_effect(kind, j, &scales, &R::JOINT_KINDS, tip_speed, rng) {
                if case == CompoundCase::RealisticArm {
                    if let Effect::StribeckFriction { .. } = e {
                        // Stribeck replaces the joint's Coulomb law.
                        out.retain(
                            |o| !matches!(o, Effect::CoulombFriction { joint, .. } if *joint == j),
                        );
                    }
                }
                used_joints.push(j);
                out.push(e);
                break;
            }
        }
    }
    out
}
