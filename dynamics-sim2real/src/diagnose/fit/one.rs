//! A fitted candidate: its parameters and their spreads, the effect it
//! stands for, and the residual it leaves on a data set.

use nalgebra::SVector;

use super::motor_sim::transmitted::motor_transmitted;
use crate::diagnose::candidates::{whitened, Candidate, MotorGuess, Prepared};
use crate::diagnose::numeric::aicc;
use crate::effects::Effect;

/// A fitted candidate.
#[derive(Debug, Clone)]
pub struct Fit {
    /// The candidate.
    pub candidate: Candidate,
    /// Linear parameters (empty for motor-side candidates).
    pub theta: Vec<f64>,
    /// Their standard deviations.
    pub std: Vec<f64>,
    /// Motor-side parameters of elasticity and backlash.
    pub motor: Option<MotorGuess>,
    /// Their standard deviations (elasticity and backlash).
    pub motor_std: Option<MotorGuess>,
    /// Whitened residual sum of squares on the training rows.
    pub sse: f64,
    /// Number of parameters.
    pub k: usize,
}

impl Fit {
    /// Every parameter as the report names it, with its value and standard
    /// deviation: the linear ones (an effort scale as the scale, fitted as
    /// scale - 1), a grid value with half its step as the spread, and a
    /// motor side's (infinite spreads where its search gave none).
    pub fn parameters(&self) -> Vec<(&'static str, f64, f64)> {
        let c = self.candidate;
        let mut out: Vec<(&'static str, f64, f64)> = c
            .linear_parameters()
            .iter()
            .zip(self.theta.iter().zip(&self.std))
            .map(|((name, _), (&v, &s))| match *name {
                "scale_minus_one" => ("scale", 1.0 + v, s),
                _ => (*name, v, s),
            })
            .collect();
        // A payload's first moments as its centre of mass, c = (m c) / m,
        // its spread by the first-order propagation of both spreads.
        if let (Candidate::PayloadCom, [(_, m, sm), moments @ ..]) = (c, out.as_slice()) {
            let (m, sm) = (*m, *sm);
            let com = ["com_x", "com_y", "com_z"];
            let centre: Vec<(&'static str, f64, f64)> = com
                .iter()
                .zip(moments)
                .map(|(name, &(_, h, sh))| match m != 0.0 {
                    true => (
                        *name,
                        h / m,
                        ((sh / m).powi(2) + (h * sm / (m * m)).powi(2)).sqrt(),
                    ),
                    false => (*name, 0.0, f64::INFINITY),
                })
                .collect();
            out.truncate(1);
            out.extend(centre);
        }
        match c {
            Candidate::Coulomb(_, vw) => out.push(("vw", vw, vw * 0.5)),
            Candidate::Stribeck(_, vs) => out.push(("vs", vs, vs * 0.5)),
            Candidate::Environment(alpha) => out.push(("alpha", alpha, 0.25)),
            _ => {}
        }
        if let (Some(g), false) = (self.motor, matches!(c, Candidate::Armature(_))) {
            let inf = f64::INFINITY;
            let sd = self.motor_std.unwrap_or(MotorGuess {
                jm: inf,
                stiffness: inf,
                damping: inf,
                half_width: inf,
            });
            out.push(("motor_inertia", g.jm, sd.jm));
            if matches!(c, Candidate::Backlash(_)) {
                out.push(("half_width", g.half_width, sd.half_width));
                out.push(("contact_stiffness", g.stiffness, sd.stiffness));
                out.push(("contact_damping", g.damping, sd.damping));
            } else {
                out.push(("stiffness", g.stiffness, sd.stiffness));
                out.push(("damping", g.damping, sd.damping));
            }
        }
        out
    }

    /// The fitted effect.
    pub fn effect(&self) -> Option<Effect> {
        match (self.candidate, self.motor) {
            (Candidate::Elasticity(j), Some(g)) => Some(g.effect(false, j)),
            (Candidate::Backlash(j), Some(g)) => Some(g.effect(true, j)),
            (c, _) => c.effect(&self.theta),
        }
    }

    /// The smoothed residual of `p` once this effect is added to the model.
    pub fn corrected<const N: usize>(&self, p: &Prepared<N>) -> Vec<SVector<f64, N>> {
        let mut r = p.sig.residual.clone();
        let (a, z) = p.sig.range;
        match (self.candidate, self.motor) {
            (Candidate::Elasticity(j), Some(g))
            | (Candidate::Backlash(j), Some(g))
            | (Candidate::Armature(j), Some(g)) => {
                let backlash = matches!(self.candidate, Candidate::Backlash(_));
                let t = motor_transmitted(&p.sig, j, &g, backlash, &p.basis.compliance);
                for k in a..z {
                    if t[k].is_finite() {
                        r[k][j] = t[k] - p.sig.model[k][j];
                    }
                }
            }
            (c, _) => {
                for (k, rk) in r.iter_mut().enumerate().take(z).skip(a) {
                    let cols = c.columns(&p.sig, &p.basis, k);
                    for (i, th) in self.theta.iter().enumerate() {
                        *rk -= cols[i] * *th;
                    }
                }
            }
        }
        r
    }

    /// AICc on `n` rows.
    pub fn aicc(&self, n: usize) -> f64 {
        aicc(self.sse, n, self.k)
    }
}

/// The fixed column of a motor-side fit on the rows of `p`: the residual
/// minus the residual it leaves.
pub fn fixed_column<const N: usize>(f: &Fit, p: &Prepared<N>) -> Vec<f64> {
    let after = f.corrected(p);
    whitened(p, |k| p.sig.residual[k] - after[k])
}

/// Joint `j`'s whitening weight, the nominal model's whitened SSE over all
/// joints, and joint `j`'s share of it: what a model changing only joint
/// `j`'s effort starts from.
pub fn whitened_nominal<const N: usize>(p: &Prepared<N>, j: usize) -> (f64, f64, f64) {
    let w = 1.0 / p.sig.floor[j];
    let own = p
        .rows
        .iter()
        .map(|&k| (p.sig.residual[k][j] * w).powi(2))
        .sum();
    (w, p.sse(&p.sig.residual), own)
}
