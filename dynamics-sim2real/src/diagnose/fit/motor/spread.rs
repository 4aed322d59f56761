//! Uncertainty of the motor-side parameters (elasticity, backlash), which
//! are searched rather than solved for: the curvature of the fit's
//! objective around its optimum. With `J` the Jacobian of the whitened
//! residual rows with respect to the logarithms of the parameters (central
//! finite differences of the motor-side simulation), the covariance of the
//! logarithms is the sandwich `(J^T J)^-1 S (J^T J)^-1`, `S` the
//! Newey-West sum of `r_k r_l J_k^T J_l` over rows less than
//! [`BANDWIDTH`] apart (weights falling linearly): the rows' residuals are
//! neither white (neighbouring rows share half of their smoothing window)
//! nor pure noise (what the model misses is correlated over a motion
//! phase), and the plain `s^2 (J^T J)^-1` took a spread four times too
//! small on an elastic joint (see the integration test). A parameter's
//! standard deviation is its value times that of its logarithm. The same
//! Jacobian gives one Gauss-Newton step from the searched optimum.

use nalgebra::DMatrix;

use crate::diagnose::candidates::MotorGuess;
use crate::diagnose::fit::motor::refine::scaled;

/// Rows over which residual correlation is summed (10 rows = 0.4 s at
/// the 40 ms row spacing: a motion phase).
pub const BANDWIDTH: usize = 10;

/// A logarithm's standard deviation beyond which the parameter counts as
/// undetermined (reported infinite): a factor e^3 = 20 either way spans
/// the whole physical range the fit searches, so a number would only
/// look like information (a backlash half-width fitted where no gap is
/// ever crossed came out at 7.6e-4 +- 5e6 rad).
pub const UNDETERMINED_LOG_STD: f64 = 3.0;

/// Relative step of the finite differences (5 %: wide enough to step over
/// the fine ripple of a backlash objective, whose contact times move in
/// whole integration steps).
pub const STEP: f64 = 0.05;

/// Standard deviations of the parameters of `g` (motor inertia,
/// stiffness, damping and, for backlash, half-width; zero for the
/// half-width of elasticity), from `residuals(gs)`: the whitened residual
/// on the fit's rows of each guess of `gs` (all of them asked for at once); and the Gauss-Newton step (factors on the parameters)
/// towards the least-squares optimum. Infinite standard deviations (and
/// no step) where the data do not determine the parameters (a singular
/// curvature, or a simulation that failed).
pub fn motor_std(
    g: &MotorGuess,
    backlash: bool,
    residuals: impl Fn(&[MotorGuess]) -> Vec<Vec<f64>>,
) -> (MotorGuess, Option<MotorGuess>) {
    let dims = if backlash { 4 } else { 3 };
    let inf = MotorGuess {
        jm: f64::INFINITY,
        stiffness: f64::INFINITY,
        damping: f64::INFINITY,
        half_width: if backlash { f64::INFINITY } else { 0.0 },
    };
    // The optimum, then each parameter up and down.
    let mut guesses = vec![*g];
    for d in 0..dims {
        guesses.push(scaled(g, d, STEP.exp()));
        guesses.push(scaled(g, d, (-STEP).exp()));
    }
    let mut rs = residuals(&guesses).into_iter();
    let r0 = rs.next().unwrap_or_default();
    let m = r0.len();
    if m <= dims || r0.iter().any(|x| !x.is_finite()) {
        return (inf, None);
    }
    let mut jac = DMatrix::zeros(m, dims);
    for d in 0..dims {
        let up = rs.next().unwrap_or_default();
        let down = rs.next().unwrap_or_default();
        if up.len() != m || down.len() != m {
            return (inf, None);
        }
        for k in 0..m {
            jac[(k, d)] = (up[k] - down[k]) / (2.0 * STEP);
        }
    }
    if jac.iter().any(|x| !x.is_finite()) {
        return (inf, None);
    }
    let Some(bread) = (jac.transpose() * &jac).try_inverse() else {
        return (inf, None);
    };
    // Scores r_k J_k, and their correlation up to BANDWIDTH rows apart.
    let score = |k: usize| jac.row(k).transpose() * r0[k];
    let mut meat = DMatrix::<f64>::zeros(dims, dims);
    for k in 0..m {
        let sk = score(k);
        meat += &sk * sk.transpose();
        for l in 1..BANDWIDTH.min(m - k) {
            let w = 1.0 - l as f64 / BANDWIDTH as f64;
            let sl = score(k + l);
            meat += (&sk * sl.transpose() + &sl * sk.transpose()) * w;
        }
    }
    let correction = m as f64 / (m - dims) as f64;
    let cov = &bread * meat * &bread * correction;
    let sd = |d: usize| -> f64 {
        let v = cov[(d, d)];
        if (0.0..=UNDETERMINED_LOG_STD * UNDETERMINED_LOG_STD).contains(&v) {
            v.sqrt()
        } else {
            f64::INFINITY
        }
    };
    let std = MotorGuess {
        jm: g.jm * sd(0),
        stiffness: g.stiffness * sd(1),
        damping: g.damping * sd(2),
        half_width: if backlash { g.half_width * sd(3) } else { 0.0 },
    };
    let rv = nalgebra::DVector::from_vec(r0);
    let step = -(&bread * (jac.transpose() * rv));
    let mut next = *g;
    for d in 0..dims {
        next = scaled(&next, d, step[d].exp());
    }
    (std, Some(next))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synth::Rng;

    /// Rows linear in the logarithms: `a_k ln(jm / 2.2) + b_k ln(k / 900)`
    /// plus a barely seen damping and white noise `e_k` of std `sigma`.
    fn rows<'a>(
        a: &'a [f64],
        b: &'a [f64],
        e: &'a [f64],
    ) -> impl Fn(&[MotorGuess]) -> Vec<Vec<f64>> + 'a {
        move |hs: &[MotorGuess]| {
            hs.iter()
                .map(|h| {
                    (0..a.len())
                        .map(|k| {
                            a[k] * (h.jm / 2.2).ln()
                                + b[k] * (h.stiffness / 900.0).ln()
                                + 1e-9 * (h.damping / 3.0).ln()
                                + e[k]
                        })
                        .collect()
                })
                .collect()
        }
    }

    #[test]
    fn white_rows_give_the_textbook_spread_and_the_step_lands_on_the_optimum() {
        let n = 2000;
        let a: Vec<f64> = (0..n).map(|k| (k as f64 * 0.1).sin()).collect();
        let b: Vec<f64> = (0..n).map(|k| (k as f64 * 0.037).cos()).collect();
        let mut rng = Rng::new(7);
        let e: Vec<f64> = (0..n).map(|_| 0.5 * rng.normal()).collect();
        let at_optimum = MotorGuess {
            jm: 2.2,
            stiffness: 900.0,
            damping: 3.0,
            half_width: 0.0,
        };
        let (sd, _) = motor_std(&at_optimum, false, rows(&a, &b, &e));
        // Textbook for white rows: sigma^2 (J^T J)^-1 over the two
        // determined logarithms (the damping column is 1e-9 of a constant).
        let (saa, sbb, sab) = (0..n).fold((0.0, 0.0, 0.0), |s, k| {
            (s.0 + a[k] * a[k], s.1 + b[k] * b[k], s.2 + a[k] * b[k])
        });
        let det = saa * sbb - sab * sab;
        let expect_jm = 2.2 * (0.25 * sbb / det).sqrt();
        let expect_k = 900.0 * (0.25 * saa / det).sqrt();
        assert!(
            (sd.jm / expect_jm - 1.0).abs() < 0.2,
            "{} vs {expect_jm}",
            sd.jm
        );
        assert!(
            (sd.stiffness / expect_k - 1.0).abs() < 0.2,
            "{} vs {expect_k}",
            sd.stiffness
        );
        // A parameter the rows barely see is barely determined.
        assert!(sd.damping > 1e3 * 3.0);
        assert_eq!(sd.half_width, 0.0);
        // From 10 % off, one step reaches the optimum (linear in the
        // logarithms), to the noise's share.
        let off = MotorGuess {
            jm: 2.0,
            stiffness: 1000.0,
            ..at_optimum
        };
        let (_, step) = motor_std(&off, false, rows(&a, &b, &e));
        let next = step.expect("a step");
        assert!(
            (next.jm / 2.2 - 1.0).abs() < 3.0 * expect_jm / 2.2,
            "{}",
            next.jm
        );
        assert!((next.stiffness / 900.0 - 1.0).abs() < 3.0 * expect_k / 900.0);
    }

    #[test]
    fn correlated_rows_widen_the_spread() {
        // The same rows with noise correlated over ~5 rows (a moving sum):
        // the textbook formula would keep the white spread; the sandwich
        // widens it by about sqrt(5) for slowly varying columns.
        let n = 2000;
        let a: Vec<f64> = (0..n).map(|k| (k as f64 * 0.01).sin()).collect();
        let b: Vec<f64> = (0..n).map(|k| (k as f64 * 0.0037).cos()).collect();
        let mut rng = Rng::new(8);
        let w: Vec<f64> = (0..n + 5).map(|_| rng.normal()).collect();
        let white: Vec<f64> = w[..n].iter().map(|x| 0.5 * x).collect();
        let red: Vec<f64> = (0..n)
            .map(|k| 0.5 * w[k..k + 5].iter().sum::<f64>() / 5f64.sqrt())
            .collect();
        let g = MotorGuess {
            jm: 2.2,
            stiffness: 900.0,
            damping: 3.0,
            half_width: 0.0,
        };
        let (s_white, _) = motor_std(&g, false, rows(&a, &b, &white));
        let (s_red, _) = motor_std(&g, false, rows(&a, &b, &red));
        let ratio = s_red.jm / s_white.jm;
        assert!(ratio > 1.6 && ratio < 2.8, "ratio {ratio}");
    }
}
