//! A fitted candidate as the report's ranking shows it: its parameters
//! with their spreads (grid values and motor-side parameters included),
//! its share of the gap, its AICc and what it gains.

use crate::diagnose::candidates::{Candidate, MotorGuess};
use crate::diagnose::explain::report::{Parameter, Ranked};
use crate::diagnose::fit::Fit;
use dynamics_runtime::Robot;

/// The report's entry of a fit: parameters with their spreads, share of
/// the gap explained (training and held-out), AICc and its gain.
pub fn ranked_entry<R: Robot<N>, const N: usize>(
    f: &Fit,
    tip: &str,
    aicc0: f64,
    n: usize,
    share: f64,
    holdout_share: f64,
) -> Ranked {
    let c = f.candidate;
    let mut parameters: Vec<Parameter> = c
        .linear_parameters()
        .iter()
        .zip(f.theta.iter().zip(&f.std))
        .map(|((name, _), (v, s))| match *name {
            // Fitted as scale - 1, reported as the scale.
            "scale_minus_one" => Parameter {
                name: "scale".into(),
                value: 1.0 + *v,
                std: *s,
            },
            _ => Parameter {
                name: name.to_string(),
                value: *v,
                std: *s,
            },
        })
        .collect();
    match c {
        // (A grid value: its spread is the grid's step.)
        Candidate::Coulomb(_, vw) => parameters.push(Parameter {
            name: "vw".into(),
            value: vw,
            std: vw * 0.5,
        }),
        Candidate::Stribeck(_, vs) => parameters.push(Parameter {
            name: "vs".into(),
            value: vs,
            std: vs * 0.5,
        }),
        Candidate::Environment(alpha) => parameters.push(Parameter {
            name: "alpha".into(),
            value: alpha,
            std: 0.25,
        }),
        _ => {}
    }
    if let (Some(g), false) = (f.motor, matches!(c, Candidate::Armature(_))) {
        let mut push = |name: &str, value: f64, std: f64| {
            parameters.push(Parameter {
                name: name.into(),
                value,
                std,
            })
        };
        let sd = f.motor_std.unwrap_or(MotorGuess {
            jm: f64::INFINITY,
            stiffness: f64::INFINITY,
            damping: f64::INFINITY,
            half_width: f64::INFINITY,
        });
        push("motor_inertia", g.jm, sd.jm);
        if matches!(c, Candidate::Backlash(_)) {
            push("half_width", g.half_width, sd.half_width);
            push("contact_stiffness", g.stiffness, sd.stiffness);
        } else {
            push("stiffness", g.stiffness, sd.stiffness);
            push("damping", g.damping, sd.damping);
        }
    }
    let a = f.aicc(n);
    Ranked {
        channel: c.channel(),
        kind: c.kind(),
        joint: c.joint().map(|j| R::JOINT_NAMES[j].to_string()),
        point: matches!(c, Candidate::Payload | Candidate::Environment(_)).then(|| tip.to_string()),
        parameters,
        share,
        aicc: a,
        delta_aicc: aicc0 - a,
        holdout_share,
    }
}
