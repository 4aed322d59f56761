//! A fitted candidate: its parameters and their spreads, the effect it
//! stands for, and the residual it leaves on a data set.

use nalgebra::SVector;

use super::against::Against;
use super::motor_sim::transmitted::motor_transmitted_raw;
use crate::diagnose::candidates::{whitened_rows, Candidate, MotorGuess, Prepared};
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
        if let (Candidate::PayloadCom(_), [(_, m, sm), moments @ ..]) = (c, out.as_slice()) {
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
        let on = Against::record(p);
        let mut r = p.sig.residual.clone();
        let (a, z) = p.sig.range;
        let motor = self
            .transmitted_raw(&on)
            .map(|(j, raw)| (j, p.sig.sg.apply(&raw, 0)));
        for (k, rk) in r.iter_mut().enumerate().take(z).skip(a) {
            let m = motor.as_ref().map(|(j, t)| (*j, t[k]));
            *rk = self.corrected_at(&on, m, k, *rk);
        }
        r
    }

    /// [`Fit::corrected`] at the rows of `p` only, one entry a row: the
    /// same values, the candidate's columns made at the rows alone (a
    /// motor side is still simulated over the whole record, its effort
    /// smoothed at the rows alone).
    pub fn corrected_rows<const N: usize>(&self, p: &Prepared<N>) -> Vec<SVector<f64, N>> {
        self.corrected_rows_against(&Against::record(p))
    }

    /// [`Fit::corrected_rows`] against `on` (its residual and model, the
    /// candidate's columns those of its record).
    pub(crate) fn corrected_rows_against<const N: usize>(
        &self,
        on: &Against<N>,
    ) -> Vec<SVector<f64, N>> {
        let p = on.p;
        let (a, z) = p.sig.range;
        let motor = self.transmitted_raw(on);
        p.rows
            .iter()
            .enumerate()
            .map(|(i, &k)| {
                let r = on.residual_row(i);
                if k >= a && k < z {
                    let m = motor.as_ref().map(|(j, raw)| (*j, p.sig.sg.at(raw, 0, k)));
                    self.corrected_at(on, m, k, r)
                } else {
                    r
                }
            })
            .collect()
    }

    /// A motor side's joint and the effort its transmission carries there
    /// along the record of `on`, before smoothing (NaN outside the range);
    /// `None` for the other fits.
    fn transmitted_raw<const N: usize>(&self, on: &Against<N>) -> Option<(usize, Vec<f64>)> {
        match (self.candidate, self.motor) {
            (Candidate::Elasticity(j), Some(g))
            | (Candidate::Backlash(j), Some(g))
            | (Candidate::Armature(j), Some(g)) => {
                let backlash = matches!(self.candidate, Candidate::Backlash(_));
                let t = motor_transmitted_raw(on, j, &g, backlash, &on.p.basis.compliance);
                Some((j, t))
            }
            _ => None,
        }
    }

    /// The residual `r` at sample `k` of the range once this effect is
    /// added: a motor side's smoothed transmitted effort at `k` and its
    /// joint, `motor` ([`Fit::transmitted_raw`]), in place of the model's
    /// at its joint where finite, else the columns times the parameters
    /// taken away.
    fn corrected_at<const N: usize>(
        &self,
        on: &Against<N>,
        motor: Option<(usize, f64)>,
        k: usize,
        mut r: SVector<f64, N>,
    ) -> SVector<f64, N> {
        match motor {
            Some((j, t)) => {
                if t.is_finite() {
                    r[j] = t - on.model_at(k, j);
                }
            }
            None => {
                let cols = self.candidate.columns(&on.p.sig, &on.p.basis, k);
                for (i, th) in self.theta.iter().enumerate() {
                    r -= cols[i] * *th;
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
    fixed_column_against(f, &Against::record(p))
}

/// [`fixed_column`] against `on` (its residual and model).
pub fn fixed_column_against<const N: usize>(f: &Fit, on: &Against<N>) -> Vec<f64> {
    let after = f.corrected_rows_against(on);
    whitened_rows(on.p, |i, _| on.residual_row(i) - after[i])
}

/// Joint `j`'s whitening weight, the whitened SSE over all joints of the
/// residual of `on` (the nominal model's, or what other effects leave),
/// and joint `j`'s share of it: what a model changing only joint `j`'s
/// effort starts from.
pub fn whitened_nominal<const N: usize>(on: &Against<N>, j: usize) -> (f64, f64, f64) {
    let p = on.p;
    let w = 1.0 / p.sig.floor[j];
    let own = (0..p.rows.len())
        .map(|i| (on.residual_row(i)[j] * w).powi(2))
        .sum();
    // (`Prepared::sse`'s sums, row by row.)
    let all = (0..p.rows.len())
        .map(|i| {
            let r = on.residual_row(i);
            (0..N).map(|j| (r[j] / p.sig.floor[j]).powi(2)).sum::<f64>()
        })
        .sum();
    (w, all, own)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::effects::{Effect, SIGN_SMOOTHING};
    use crate::synth::{synthesize, SynthOptions};
    use crate::test_robots::Arm2;

    fn fit(candidate: Candidate, theta: Vec<f64>, motor: Option<MotorGuess>) -> Fit {
        Fit {
            candidate,
            std: vec![0.0; theta.len()],
            theta,
            motor,
            motor_std: None,
            sse: 0.0,
            k: 1,
        }
    }

    /// The residual a fit leaves, made at the rows alone, is the whole
    /// record's at the rows to the bit (a linear fit, a sign-smoothed one,
    /// a motor side); the whitened sum of squares from the rows is the
    /// whole record's; and a motor side's fixed column is the difference
    /// of the whole residuals.
    #[test]
    fn the_residual_at_the_rows_is_the_whole_records() {
        let robot = Arm2::default();
        let opts = SynthOptions {
            duration: 3.0,
            seed: 12,
            ..Default::default()
        };
        let effects = [Effect::ViscousFriction { joint: 1, fv: 0.4 }];
        let m = synthesize(&robot, &effects, &opts).expect("a generated record");
        let p = Prepared::new(&robot, &m);
        assert!(p.rows.len() > 50);
        let guess = MotorGuess {
            jm: 0.05,
            stiffness: 3000.0,
            damping: 2.0,
            half_width: 0.0,
        };
        let fits = [
            fit(Candidate::Viscous(1), vec![0.35], None),
            fit(Candidate::Coulomb(0, SIGN_SMOOTHING), vec![0.2], None),
            fit(Candidate::Elasticity(1), vec![], Some(guess)),
        ];
        for f in &fits {
            let whole = f.corrected(&p);
            let rows = f.corrected_rows(&p);
            assert_eq!(rows.len(), p.rows.len());
            for (r, &k) in rows.iter().zip(&p.rows) {
                for j in 0..2 {
                    assert_eq!(r[j].to_bits(), whole[k][j].to_bits(), "{f:?} sample {k}");
                }
            }
            assert_eq!(p.sse_rows(&rows).to_bits(), p.sse(&whole).to_bits());
        }
        let whole = fits[2].corrected(&p);
        let col = fixed_column(&fits[2], &p);
        let direct = crate::diagnose::candidates::whitened(&p, |k| p.sig.residual[k] - whole[k]);
        assert_eq!(col.len(), direct.len());
        assert!(col
            .iter()
            .zip(&direct)
            .all(|(a, b)| a.to_bits() == b.to_bits()));
        assert!(col.iter().any(|x| *x != 0.0));
    }
}
