//! The motor side of elasticity and backlash candidates: the parameters
//! searched, their grid and physical box, and the highest frequency the
//! data show (the simulation of the motor side is `fit::motor`).

use std::f64::consts::PI;

use crate::effects::Effect;

/// Motor-side parameters searched for elasticity and backlash.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MotorGuess {
    /// Motor inertia.
    pub jm: f64,
    /// Spring (elasticity) or contact (backlash) stiffness.
    pub stiffness: f64,
    /// Damping.
    pub damping: f64,
    /// Backlash half-width (0 for elasticity).
    pub half_width: f64,
}

impl MotorGuess {
    /// As an effect at `joint`.
    pub fn effect(&self, backlash: bool, joint: usize) -> Effect {
        if backlash {
            Effect::Backlash {
                joint,
                half_width: self.half_width,
                motor_inertia: self.jm,
                contact_stiffness: self.stiffness,
                contact_damping: self.damping,
            }
        } else {
            Effect::JointElasticity {
                joint,
                stiffness: self.stiffness,
                damping: self.damping,
                motor_inertia: self.jm,
            }
        }
    }
}

/// Highest frequency of a signature that data sampled every `dt` show:
/// four samples a period (the motor-side simulation's two sub-steps a
/// sample keep its Runge-Kutta steps stable there, and a resonance is seen
/// as a resonance, not an alias).
pub fn signature_limit(dt: f64) -> f64 {
    0.25 / dt
}

/// Resonance (elasticity) or contact (backlash) frequency of `g`, Hz.
pub fn motor_frequency(g: &MotorGuess, inertia: f64) -> f64 {
    (g.stiffness * (1.0 / g.jm + 1.0 / inertia)).sqrt() / (2.0 * PI)
}

/// The grid of motor-side parameters searched at a joint of own inertia
/// `inertia`, at frequencies up to `limit` Hz ([`signature_limit`]).
pub fn motor_grid(backlash: bool, inertia: f64, revolute: bool, limit: f64) -> Vec<MotorGuess> {
    let mut out = all_motor_grid(backlash, inertia, revolute);
    out.retain(|g| motor_frequency(g, inertia) <= limit * (1.0 + 1e-9));
    out
}

fn all_motor_grid(backlash: bool, inertia: f64, revolute: bool) -> Vec<MotorGuess> {
    let mut out = Vec::new();
    for ratio in [0.05, 0.1, 0.2, 0.4] {
        let jm = ratio * inertia;
        if backlash {
            let widths: Vec<f64> = (0..12)
                .map(|i| {
                    let arcmin = 0.25 * (30.0f64 / 0.25).powf(i as f64 / 11.0);
                    if revolute {
                        arcmin / 60.0 * PI / 180.0
                    } else {
                        arcmin * 2e-5
                    }
                })
                .collect();
            for f in [40.0, 80.0] {
                let w = 2.0 * PI * f;
                let stiffness = w * w / (1.0 / jm + 1.0 / inertia);
                for &half_width in &widths {
                    out.push(MotorGuess {
                        jm,
                        stiffness,
                        damping: 2.0 * 0.1 * (stiffness * jm).sqrt(),
                        half_width,
                    });
                }
            }
        } else {
            for i in 0..10 {
                let f = 3.0 * (15.0f64).powf(i as f64 / 9.0);
                let w = 2.0 * PI * f;
                let stiffness = w * w / (1.0 / jm + 1.0 / inertia);
                for zeta in [0.05, 0.2] {
                    out.push(MotorGuess {
                        jm,
                        stiffness,
                        damping: 2.0 * zeta * (stiffness * jm).sqrt(),
                        half_width: 0.0,
                    });
                }
            }
        }
    }
    out
}

/// Whether `g` lies in the physical box the grid of [`motor_grid`] spans
/// (its refinement may not leave it): motor inertia 5-40 % of the joint's,
/// resonance 3-45 Hz (elasticity) or contact 20-160 Hz (backlash), damping
/// ratio 0.02-0.3 (a resonance the data can show is lightly damped; a
/// heavily damped "spring" is only a filter on the effort), half-width
/// 0.25-30 arcmin (revolute) or 5-600 um.
/// (and at most `limit` Hz, [`signature_limit`]).
pub fn motor_feasible(
    g: &MotorGuess,
    backlash: bool,
    inertia: f64,
    revolute: bool,
    limit: f64,
) -> bool {
    let ratio = g.jm / inertia;
    let f = motor_frequency(g, inertia);
    let zeta = g.damping / (2.0 * (g.stiffness * g.jm).sqrt());
    let (f_lo, f_hi): (f64, f64) = if backlash { (20.0, 160.0) } else { (3.0, 45.0) };
    let unit = if revolute { PI / 180.0 / 60.0 } else { 2e-5 };
    let width_ok = !backlash || (0.249 * unit..=30.01 * unit).contains(&g.half_width);
    (0.0499..=0.4001).contains(&ratio)
        && (f_lo..=f_hi.min(limit)).contains(&f)
        && (0.02..=0.3).contains(&zeta)
        && width_ok
}
