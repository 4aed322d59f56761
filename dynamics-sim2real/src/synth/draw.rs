//! Drawing an effect at random from realistic magnitude ranges.

use std::f64::consts::PI;

use nalgebra::{SVector, Vector3};

use super::{Excitation, Rng};
use crate::effects::{Effect, EffectKind, Tip};
use dynamics_runtime::{JointKind, Robot};

/// What a robot's nominal motion looks like per joint: the yardsticks of
/// realistic effect magnitudes.
#[derive(Debug, Clone, PartialEq)]
pub struct Scales<const N: usize> {
    /// Peak nominal effort along the reference.
    pub peak_effort: SVector<f64, N>,
    /// Peak reference speed.
    pub peak_speed: SVector<f64, N>,
    /// Mean of the joint's own inertia `A[j][j]` along the reference (the
    /// inertia it moves with every other joint locked).
    pub inertia: SVector<f64, N>,
    /// Mean of `1 / (A^-1)[j][j]` along the reference: the inertia joint j
    /// moves when the other joints give way (never above `inertia`): the
    /// link side of a motor-side resonance. A rotor large against it is
    /// what makes a controller built on the nominal model lose the joint's
    /// lightest direction of motion.
    pub free_inertia: SVector<f64, N>,
    /// Effective mass at the tip along gravity at the start pose,
    /// `1 / (g^T J A^-1 J^T g)` for unit g: the "tip mass" payloads are
    /// measured against.
    pub tip_mass: f64,
}

impl<const N: usize> Scales<N> {
    /// Measures the scales on `reference` over `[0, duration]`.
    pub fn of<R: Robot<N>>(robot: &R, reference: &Excitation<N>, duration: f64) -> Self {
        let mut s = Scales {
            peak_effort: SVector::zeros(),
            peak_speed: SVector::zeros(),
            inertia: SVector::zeros(),
            free_inertia: SVector::zeros(),
            tip_mass: 0.0,
        };
        let steps = 400;
        for k in 0..=steps {
            let r = reference.at(duration * k as f64 / steps as f64);
            let tau = robot.inverse_dynamics(&r.q, &r.qd, &r.qdd);
            let a = robot.mass_matrix(&r.q);
            let a_inv = a.try_inverse();
            for j in 0..N {
                s.peak_effort[j] = s.peak_effort[j].max(tau[j].abs());
                s.peak_speed[j] = s.peak_speed[j].max(r.qd[j].abs());
                s.inertia[j] += a[(j, j)] / (steps + 1) as f64;
                let free = match &a_inv {
                    Some(inv) if inv[(j, j)] > 0.0 => (1.0 / inv[(j, j)]).min(a[(j, j)]),
                    _ => a[(j, j)],
                };
                s.free_inertia[j] += free / (steps + 1) as f64;
            }
        }
        let q0 = reference.at(0.0).q;
        let (_, jac) = Tip::of::<R, N>().position_jacobian(robot, &q0);
        let g = Vector3::from(R::GRAVITY);
        let g = if g.norm() > 0.0 {
            g / g.norm()
        } else {
            Vector3::y()
        };
        let a = robot.mass_matrix(&q0);
        let jt_g = jac.transpose() * g;
        s.tip_mass = match a.cholesky() {
            Some(c) => 1.0 / jt_g.dot(&c.solve(&jt_g)).max(1e-12),
            None => 1.0,
        };
        s
    }
}

/// Draws an effect of `kind` at joint `joint` with a magnitude from the
/// realistic ranges (given in the rustdoc of each arm), scaled by `scales`.
///
/// | kind | magnitude drawn |
/// |---|---|
/// | coulomb_friction | Fc = 0.5-3 % of the joint's peak effort |
/// | viscous_friction | Fv * peak speed = 0.5-3 % of peak effort |
/// | stribeck_friction | Fc as Coulomb, Fs = 1.3-2 Fc, vs = 0.02-0.1 |
/// | armature | 5-30 % of the joint's own (locked) inertia |
/// | payload_mass | 5-50 % of the tip mass |
/// | joint_elasticity | motor inertia 20 % of the joint's own inertia, resonance against the free inertia 5-30 Hz, 5 % damping |
/// | backlash | half-width 0.5-15 arcmin (revolute) or 10-300 um, motor as above, contact at ~60 Hz |
/// | environment_resistance | mu so that the force at peak tip speed is 1-5 % of m_tip g, alpha 1-2.5 |
/// | encoder_offset | 0.1-1 deg (revolute) or 0.1-1 mm, either sign |
/// | time_delay | 1-10 ms |
/// | effort_scale | 0.85-0.95 or 1.05-1.15 |
/// | effort_offset | 0.5-3 % of the joint's peak effort, either sign |
/// | joint_spring | over 1 rad (0.1 m) of travel 1-5 % of the peak effort, at rest within 0.5 rad (5 cm) of the zero |
///
/// ```
/// use dynamics_sim2real::effects::EffectKind;
/// use dynamics_sim2real::synth::{draw_effect, Rng, Scales};
/// let s = Scales::<2> { peak_effort: [10.0, 5.0].into(), peak_speed: [1.0, 1.0].into(), inertia: [1.0, 0.5].into(), free_inertia: [0.8, 0.4].into(), tip_mass: 2.0 };
/// let kinds = [dynamics_runtime::JointKind::Revolute; 2];
/// let e = draw_effect(EffectKind::CoulombFriction, 1, &s, &kinds, 1.0, &mut Rng::new(1)).unwrap();
/// let dynamics_sim2real::effects::Effect::CoulombFriction { fc, .. } = e else { panic!() };
/// assert!((0.025..=0.15).contains(&fc));
/// ```
pub fn draw_effect<const N: usize>(
    kind: EffectKind,
    joint: usize,
    scales: &Scales<N>,
    kinds: &[JointKind; N],
    tip_speed: f64,
    rng: &mut Rng,
) -> Option<Effect> {
    let j = joint.min(N - 1);
    let revolute = kinds[j] != JointKind::Prismatic;
    let peak = scales.peak_effort[j].max(1e-6);
    let free = scales.free_inertia[j].max(1e-9);
    let locked = scales.inertia[j].max(free);
    Some(match kind {
        // Drawn by the compound generator, which knows the robot's links.
        EffectKind::None | EffectKind::InertialParameters => return None,
        EffectKind::CoulombFriction => Effect::coulomb(j, peak * rng.uniform(0.005, 0.03)),
        EffectKind::ViscousFriction => Effect::ViscousFriction {
            joint: j,
            fv: peak * rng.uniform(0.005, 0.03) / scales.peak_speed[j].max(1e-3),
        },
        EffectKind::StribeckFriction => {
            let fc = peak * rng.uniform(0.005, 0.03);
            Effect::StribeckFriction {
                joint: j,
                fc,
                fs: fc * rng.uniform(1.3, 2.0),
                vs: rng.uniform(0.02, 0.1),
            }
        }
        EffectKind::Armature => Effect::Armature {
            joint: j,
            inertia: locked * rng.uniform(0.05, 0.3),
        },
        EffectKind::PayloadMass => Effect::PayloadMass {
            mass: scales.tip_mass * rng.uniform(0.05, 0.5),
            com: [0.0; 3],
        },
        EffectKind::JointElasticity => {
            let jm = 0.2 * locked;
            let w = 2.0 * PI * rng.uniform(5.0, 30.0);
            let stiffness = w * w / (1.0 / jm + 1.0 / free);
            Effect::JointElasticity {
                joint: j,
                stiffness,
                damping: 2.0 * 0.05 * (stiffness * jm).sqrt(),
                motor_inertia: jm,
            }
        }
        EffectKind::Backlash => {
            let jm = 0.2 * locked;
            let w = 2.0 * PI * 60.0;
            let contact_stiffness = w * w / (1.0 / jm + 1.0 / free);
            Effect::Backlash {
                joint: j,
                half_width: if revolute {
                    rng.uniform(0.5, 15.0) / 60.0 * PI / 180.0
                } else {
                    rng.uniform(10e-6, 300e-6)
                },
                motor_inertia: jm,
                contact_stiffness,
                contact_damping: 2.0 * 0.1 * (contact_stiffness * jm).sqrt(),
            }
        }
        EffectKind::EnvironmentResistance => {
            let alpha = rng.uniform(1.0, 2.5);
            let v = tip_speed.max(1e-3);
            let force = scales.tip_mass * 9.81 * rng.uniform(0.01, 0.05);
            Effect::EnvironmentResistance {
                mu: force / v.powf(alpha),
                alpha,
            }
        }
        EffectKind::EncoderOffset => {
            let sign = if rng.uniform(0.0, 1.0) < 0.5 {
                -1.0
            } else {
                1.0
            };
            let size = rng.uniform(0.1, 1.0);
            Effect::EncoderOffset {
                joint: j,
                offset: sign
                    * if revolute {
                        size * PI / 180.0
                    } else {
                        size * 1e-3
                    },
            }
        }
        // Over a radian (or 0.1 m) of travel, 1-5 % of the peak effort; at
        // rest within half a radian (5 cm) of the zero.
        EffectKind::JointSpring => {
            let travel = if revolute { 1.0 } else { 0.1 };
            let stiffness = peak * rng.uniform(0.01, 0.05) / travel;
            Effect::JointSpring {
                joint: j,
                stiffness,
                preload: -stiffness * travel * rng.uniform(-0.5, 0.5),
            }
        }
        EffectKind::TimeDelay => Effect::TimeDelay {
            delay: rng.uniform(1e-3, 10e-3),
        },
        EffectKind::EffortScale => {
            let off = rng.uniform(0.05, 0.15);
            Effect::EffortScale {
                joint: j,
                scale: if rng.uniform(0.0, 1.0) < 0.5 {
                    1.0 - off
                } else {
                    1.0 + off
                },
            }
        }
        EffectKind::EffortOffset => {
            let size = peak * rng.uniform(0.005, 0.03);
            Effect::EffortOffset {
                joint: j,
                offset: if rng.uniform(0.0, 1.0) < 0.5 {
                    -size
                } else {
                    size
                },
            }
        }
    })
}
