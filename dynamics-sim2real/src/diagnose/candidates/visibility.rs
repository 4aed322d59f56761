//! What these data can show, checked before anything is fitted: per joint,
//! whether it moves at all and whether its velocity reverses; whether the
//! measured effort has the sign of the model's; which effects' signatures
//! lie above what the sample rate shows. Each finding is a [`Warning`] (or
//! an error when nothing can be said), and the candidates the data cannot
//! identify are dropped rather than guessed.

use crate::diagnose::candidates::candidate::Candidate;
use crate::diagnose::candidates::motor::signature_limit;
use crate::diagnose::candidates::Prepared;
use crate::diagnose::DiagnoseError;
use crate::effects::{smooth_sign, EffectKind};
use crate::Warning;
use nalgebra::{SMatrix, SVector};

/// A joint moves when its smoothed position spans at least this many
/// position-noise deviations (and [`MIN_TRAVEL`]).
const TRAVEL_NOISE: f64 = 50.0;
/// ... and at least this far (rad or m).
const MIN_TRAVEL: f64 = 1e-3;
/// A velocity reverses when it reaches this fraction of its peak speed on
/// both sides of zero.
const REVERSAL: f64 = 0.05;
/// Correlation of the measured with the model's effort below which the
/// effort column may have the wrong sign ...
const WRONG_SIGN: f64 = -0.5;
/// ... and it has when the model's coefficient, fitted with the effects
/// that most often dwarf a joint's rigid-body effort, is below this.
const WRONG_COEFFICIENT: f64 = -0.5;
/// Lowest frequency of backlash's signature the diagnosis searches (its
/// contact frequencies), Hz.
const BACKLASH_HZ: f64 = 40.0;
/// Highest resonance of elasticity the diagnosis searches, Hz.
const ELASTICITY_HZ: f64 = 45.0;

/// Per joint: whether it moves, whether its velocity reverses.
#[derive(Debug, Clone)]
pub struct Excitation {
    /// Whether each joint moves.
    pub moves: Vec<bool>,
    /// Whether each joint's velocity reverses.
    pub reverses: Vec<bool>,
    /// Each joint's range of motion (smoothed position, lowest and
    /// highest).
    pub range: Vec<(f64, f64)>,
}

/// What the training data `p` (joint names `names`) can show; warnings
/// appended to `warnings`. Errors when no joint moves.
pub fn excitation<const N: usize>(
    p: &Prepared<N>,
    names: &[&str; N],
    warnings: &mut Vec<Warning>,
) -> Result<Excitation, DiagnoseError> {
    let mut moves = vec![false; N];
    let mut reverses = vec![false; N];
    let mut range = vec![(0.0, 0.0); N];
    for j in 0..N {
        let (mut lo, mut hi, mut vlo, mut vhi) = (f64::INFINITY, f64::NEG_INFINITY, 0.0f64, 0.0f64);
        for &k in &p.rows {
            let (q, v) = (p.sig.motion.q_at(k, j), p.sig.motion.qd_at(k, j));
            lo = lo.min(q);
            hi = hi.max(q);
            vlo = vlo.min(v);
            vhi = vhi.max(v);
        }
        let peak = vhi.max(-vlo);
        range[j] = (lo, hi);
        moves[j] = hi - lo >= (TRAVEL_NOISE * p.levels[0][j]).max(MIN_TRAVEL);
        reverses[j] = moves[j] && vhi >= REVERSAL * peak && -vlo >= REVERSAL * peak;
        if !moves[j] {
            warnings.push(Warning::NoMotion {
                joint: names[j].to_string(),
                peak_speed: peak,
            });
        } else if !reverses[j] {
            warnings.push(Warning::NoReversal {
                joint: names[j].to_string(),
            });
        }
    }
    if !moves.iter().any(|&m| m) {
        return Err(DiagnoseError::NoMotion);
    }
    Ok(Excitation {
        moves,
        reverses,
        range,
    })
}

/// Refuses an effort column whose sign is flipped: the measured effort
/// correlating negatively with the nominal model's where the model's
/// effort varies well above its noise floor, and still entering with a
/// negative coefficient when fitted together with what most often dwarfs
/// a joint's rigid-body effort: Coulomb and viscous friction, a spring and
/// an offset ([`coefficient`]).
///
/// The fit keeps joints whose effort is mostly something the model lacks.
/// FloBaRoID's KUKA LWR4+ records with its CAD URDF stripped of friction:
/// `lwr_4` measures 1.1 N m RMS, nearly all Coulomb friction, against a
/// rigid-body effort of 0.15 N m that the trajectory happens to
/// anticorrelate with it (r = -0.67; coefficient +0.20 in the fit);
/// `lwr_6` measures a spring's effort that anticorrelates with the wrist's
/// small inertial effort on periodic motion (r = -0.72; coefficient -0.15).
pub fn effort_sign<const N: usize>(
    p: &Prepared<N>,
    names: &[&str; N],
    which: &'static str,
) -> Result<(), DiagnoseError> {
    for j in 0..N {
        let n = p.rows.len().max(1) as f64;
        let mean = |f: &dyn Fn(usize) -> f64| p.rows.iter().map(|&k| f(k)).sum::<f64>() / n;
        let (mt, mm) = (mean(&|k| p.sig.tau_at(k, j)), mean(&|k| p.sig.model[k][j]));
        let (mut sxy, mut sxx, mut syy) = (0.0, 0.0, 0.0);
        for &k in &p.rows {
            let (x, y) = (p.sig.model[k][j] - mm, p.sig.tau_at(k, j) - mt);
            sxy += x * y;
            sxx += x * x;
            syy += y * y;
        }
        if (sxx / n).sqrt() < 3.0 * p.sig.floor[j] || sxx * syy <= 0.0 {
            continue;
        }
        let r = sxy / (sxx * syy).sqrt();
        if r < WRONG_SIGN && coefficient(p, j).is_some_and(|b| b < WRONG_COEFFICIENT) {
            return Err(DiagnoseError::EffortSign {
                which,
                joint: names[j].to_string(),
                correlation: r,
            });
        }
    }
    Ok(())
}

/// The nominal model's coefficient in the least-squares fit of joint `j`'s
/// measured effort by the model's, Coulomb friction (sharp), viscous
/// friction, a spring and an offset (columns the data cannot tell apart,
/// such as a still joint's spring and offset, share their part: the
/// least-norm solution); `None` when no number comes out.
fn coefficient<const N: usize>(p: &Prepared<N>, j: usize) -> Option<f64> {
    let mut xtx = SMatrix::<f64, 5, 5>::zeros();
    let mut xty = SVector::<f64, 5>::zeros();
    for &k in &p.rows {
        let (v, q) = (p.sig.motion.qd_at(k, j), p.sig.motion.q_at(k, j));
        let x = SVector::<f64, 5>::new(p.sig.model[k][j], smooth_sign(v), v, q, 1.0);
        xtx += x * x.transpose();
        xty += x * p.sig.tau_at(k, j);
    }
    let svd = xtx.svd(true, true);
    let eps = 1e-12 * svd.singular_values.max();
    let b = svd.solve(&xty, eps).ok()?;
    b[0].is_finite().then_some(b[0])
}

/// Drops the candidates these data cannot identify: every one at a joint
/// that does not move; Stribeck friction where the velocity never reverses
/// (no breakaway shows; Coulomb friction stays, named only as ambiguous
/// with an effort offset: `reversal.rs`); backlash, and
/// elasticity's resonances, above what the rate shows (interval `dt`).
pub fn identifiable(
    candidates: Vec<Candidate>,
    ex: &Excitation,
    dt: f64,
    warnings: &mut Vec<Warning>,
) -> Vec<Candidate> {
    let limit = signature_limit(dt);
    let rate = 1.0 / dt;
    let mut said = [false; 2];
    let kept = candidates
        .into_iter()
        .filter(|c| {
            if let Some(j) = c.joint() {
                if !ex.moves[j] {
                    return false;
                }
                if !ex.reverses[j] && matches!(c, Candidate::Stribeck(..)) {
                    return false;
                }
            }
            match c {
                Candidate::Backlash(_) if limit < BACKLASH_HZ => {
                    said[0] = true;
                    false
                }
                Candidate::Elasticity(_) if limit < ELASTICITY_HZ => {
                    said[1] = true;
                    true
                }
                _ => true,
            }
        })
        .collect();
    if said[0] {
        warnings.push(Warning::RateTooLow {
            effect: EffectKind::Backlash.name().into(),
            rate,
            limit,
            needs: BACKLASH_HZ,
        });
    }
    if said[1] {
        warnings.push(Warning::RateTooLow {
            effect: EffectKind::JointElasticity.name().into(),
            rate,
            limit,
            needs: ELASTICITY_HZ,
        });
    }
    kept
}
