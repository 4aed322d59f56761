//! What changed since a calibration. A report carries, per joint, the
//! spread its data leave on the Coulomb level and the viscous coefficient
//! ([`friction_spread`]): the fit's own where the explanation corrects
//! them, else the spread they would have had, added to the explanation (a
//! calibration that did not name a small friction could not have seen it
//! below about its naming threshold times that spread). Diagnosing a later
//! record against that report as the baseline, a friction correction is a
//! change only if the calibration would have seen it ([`changed`]): where
//! the calibration corrected that friction, the correction is beyond what
//! both records' spreads allow at the held-out test's level; where it kept
//! the nominal value, the correction's lower bound at that level is above
//! what the calibration would have named (`sqrt(add_margin + 2)` times its
//! spread: the criterion's gain of a one-parameter term). Otherwise it
//! refines the calibration and is a suggestion, not a named effect.

use nalgebra::SVector;

use super::confirm::{normal_upper, Confirmed, Suggestion, Unconfirmed};
use crate::diagnose::candidates::Candidate;
use crate::diagnose::options::CalibrationSpread;
use crate::diagnose::select::{Explanation, Pool, Solution};
use crate::effects::SIGN_SMOOTHING;

/// Per joint, the standard deviation of the Coulomb level and of the
/// viscous coefficient on the data of a diagnosis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrictionSpread<const N: usize> {
    /// Coulomb level (N m or N); `NaN`: no Coulomb term at the joint.
    pub coulomb: SVector<f64, N>,
    /// Viscous coefficient (N m s/rad or N s/m); `NaN`: no viscous term.
    pub viscous: SVector<f64, N>,
}

/// Which friction law a term is, and its level's parameter position.
fn law(c: Candidate) -> Option<(usize, Law)> {
    match c {
        Candidate::Coulomb(j, _) | Candidate::Stribeck(j, _) => Some((j, Law::Coulomb)),
        Candidate::Viscous(j) => Some((j, Law::Viscous)),
        _ => None,
    }
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Law {
    Coulomb,
    Viscous,
}

/// The spread of each joint's friction in the fit of explanation `e`
/// over `pool`: of the term in the set, or of the sharp Coulomb law and
/// the viscous term added to the set.
pub fn friction_spread<const N: usize>(pool: &Pool, e: &Explanation) -> FrictionSpread<N> {
    let mut out = FrictionSpread {
        coulomb: SVector::repeat(f64::NAN),
        viscous: SVector::repeat(f64::NAN),
    };
    let mut put = |j: usize, l: Law, s: f64| {
        if j < N && s.is_finite() && s >= 0.0 {
            match l {
                Law::Coulomb => out.coulomb[j] = s,
                Law::Viscous => out.viscous[j] = s,
            }
        }
    };
    let mut seen: Vec<(usize, Law)> = Vec::new();
    for (i, &t) in e.set.iter().enumerate() {
        if let Some((j, l)) = law(pool.terms[t].fit.candidate) {
            if let Some(&s) = e.sol.std[i].first() {
                put(j, l, s);
                seen.push((j, l));
            }
        }
    }
    for (t, term) in pool.terms.iter().enumerate() {
        let c = term.fit.candidate;
        let sharp = match c {
            Candidate::Coulomb(_, w) => w <= SIGN_SMOOTHING,
            Candidate::Viscous(_) => true,
            _ => false,
        };
        let Some((j, l)) = law(c).filter(|_| sharp && term.fixed.is_none()) else {
            continue;
        };
        if seen.contains(&(j, l)) {
            continue;
        }
        let mut set = e.set.clone();
        set.push(t);
        let sol = pool.solve(&set);
        if let Some(&s) = sol.std.last().and_then(|s| s.first()) {
            put(j, l, s);
            seen.push((j, l));
        }
    }
    out
}

/// The calibration's spread on the friction term `c` corrects, and whether
/// it corrected that friction (`None`: not friction, or no spread known).
fn calibrated(c: Candidate, calibration: &CalibrationSpread) -> Option<(f64, bool)> {
    let (j, l) = law(c)?;
    let (spread, corrected) = match l {
        Law::Coulomb => (&calibration.coulomb, &calibration.coulomb_corrected),
        Law::Viscous => (&calibration.viscous, &calibration.viscous_corrected),
    };
    let s = spread
        .get(j)
        .copied()
        .filter(|s| s.is_finite() && *s >= 0.0)?;
    Some((s, corrected.get(j).copied().unwrap_or(true)))
}

/// Whether a friction correction `value` (spread `std`) of term `c` is a
/// change since a calibration of spread `calibration`, at the held-out
/// test's per-effect chance `level` (`z` the normal quantile at
/// `level / 2`): where the calibration corrected that friction, `|value|`
/// above `z` times the spread of the difference of the two estimates;
/// where it did not, `|value| - z std` above `naming` times its spread
/// (what it would have named). Terms other than joint friction, and joints
/// the calibration gives no spread for, always are.
pub fn changed(
    c: Candidate,
    (value, std): (f64, f64),
    calibration: &CalibrationSpread,
    level: f64,
    naming: f64,
) -> bool {
    let Some((s_cal, corrected)) = calibrated(c, calibration) else {
        return true;
    };
    let z = normal_upper(0.5 * level);
    if corrected {
        value.abs() > z * (s_cal * s_cal + std * std).sqrt()
    } else {
        value.abs() - z * std > naming * s_cal
    }
}

/// The friction corrections of `confirmed` that are no change since
/// `calibration` ([`changed`], at each effect's held-out test level) moved
/// to its suggestions (`Unconfirmed::WithinCalibration`), the others
/// refitted without them by `solve`; again on the refitted values until
/// none moves (two corrections of one joint's friction share what they
/// explain: with the one gone, the other's value is what is reported,
/// and it is that value which must be a change).
pub fn keep_changes(
    confirmed: &mut Confirmed,
    pool: &Pool,
    calibration: &CalibrationSpread,
    add_margin: f64,
    solve: impl Fn(&[usize]) -> Solution,
) {
    let naming = (add_margin.max(0.0) + 2.0).sqrt();
    loop {
        let e = &confirmed.explanation;
        let mut keep = Vec::new();
        let mut moved = Vec::new();
        for (i, &t) in e.set.iter().enumerate() {
            let c = pool.terms[t].fit.candidate;
            let (value, std) = (
                e.sol.theta[i].first().copied().unwrap_or(0.0),
                e.sol.std[i].first().copied().unwrap_or(0.0),
            );
            let level = confirmed.confidence.get(i).map_or(1e-3, |c| c.level);
            if changed(c, (value, std), calibration, level, naming) {
                keep.push(i);
                continue;
            }
            moved.push(Suggestion {
                term: t,
                theta: e.sol.theta[i].clone(),
                std: e.sol.std[i].clone(),
                why: Unconfirmed::WithinCalibration(
                    calibrated(c, calibration).map_or(f64::NAN, |(s, _)| s),
                ),
            });
        }
        if moved.is_empty() {
            return;
        }
        let set: Vec<usize> = keep.iter().map(|&i| e.set[i]).collect();
        let rivals = keep.iter().map(|&i| e.rivals[i]).collect();
        let confidence = keep
            .iter()
            .filter_map(|&i| confirmed.confidence.get(i).copied())
            .collect();
        let sol = solve(&set);
        confirmed.suggested.extend(moved);
        let left_out = std::mem::take(&mut confirmed.explanation.left_out);
        confirmed.explanation = Explanation {
            set,
            sol,
            rivals,
            left_out,
        };
        confirmed.confidence = confidence;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_change_is_what_the_calibration_would_have_seen() {
        let cal = CalibrationSpread {
            coulomb: vec![0.01, f64::NAN, 0.01],
            viscous: vec![0.004, 0.004, 0.002],
            coulomb_corrected: vec![true, true, false],
            viscous_corrected: vec![true, true, false],
        };
        let naming = (40.0f64 + 2.0).sqrt();
        // Corrected by the calibration: at level 1e-3 the quantile is 3.29
        // (tables); the spread of the difference sqrt(0.004^2 + 0.003^2) =
        // 0.005: 0.0164 the limit, either sign.
        let v = Candidate::Viscous(0);
        assert!(!changed(v, (0.016, 0.003), &cal, 1e-3, naming));
        assert!(!changed(v, (-0.016, 0.003), &cal, 1e-3, naming));
        assert!(changed(v, (0.017, 0.003), &cal, 1e-3, naming));
        // Kept nominal by the calibration: it would have named 6.48 x 0.002
        // = 0.01296; 0.013 - 3.29 x 0.001 = 0.0097 is below, 0.017 - 0.0033
        // above.
        let w = Candidate::Viscous(2);
        assert!(!changed(w, (0.013, 0.001), &cal, 1e-3, naming));
        assert!(changed(w, (0.017, 0.001), &cal, 1e-3, naming));
        // No spread for joint 1's Coulomb level, none for joint 3 at all.
        assert!(changed(
            Candidate::Coulomb(1, SIGN_SMOOTHING),
            (1e-6, 1.0),
            &cal,
            1e-3,
            naming
        ));
        assert!(changed(
            Candidate::Viscous(3),
            (1e-6, 1.0),
            &cal,
            1e-3,
            naming
        ));
        // Not friction: a change whatever its size.
        assert!(changed(
            Candidate::Armature(0),
            (1e-9, 1.0),
            &cal,
            1e-3,
            naming
        ));
        // A Stribeck correction's level is judged as the Coulomb level.
        assert!(!changed(
            Candidate::Stribeck(0, 0.05),
            (0.03, 0.001),
            &cal,
            1e-3,
            naming
        ));
    }

    /// Coulomb and viscous friction of one joint whose columns share most
    /// of what they explain: fitted together, the viscous correction is 5
    /// (beyond the calibration's 0.5) and the Coulomb one -4 (within its
    /// 10); with the Coulomb correction left to the calibration, the
    /// viscous one alone is about 1, within what the calibration could
    /// tell: it too is a suggestion, not a change.
    #[test]
    fn a_correction_is_judged_at_the_value_reported() {
        use crate::diagnose::evaluate::confirm::Confidence;
        use crate::diagnose::select::{test_pool, test_term};
        use nalgebra::{DMatrix, DVector};
        let n = 200;
        // a: a sign-like column; c: small and orthogonal to it.
        let a = |r: usize| if r.is_multiple_of(2) { 1.0 } else { -1.0 };
        let c = |r: usize| if (r / 2).is_multiple_of(2) { 0.1 } else { -0.1 };
        let x = DMatrix::from_fn(n, 2, |r, k| if k == 0 { a(r) } else { a(r) + c(r) });
        let y = DVector::from_fn(n, |r, _| -4.0 * a(r) + 5.0 * (a(r) + c(r)));
        let coulomb = Candidate::Coulomb(0, SIGN_SMOOTHING);
        let viscous = Candidate::Viscous(0);
        let pool = test_pool(
            x,
            y,
            vec![
                test_term(coulomb, vec![0], vec![false], None),
                test_term(viscous, vec![1], vec![false], None),
            ],
            1,
        );
        let sol = pool.solve(&[0, 1]);
        assert!((sol.theta[0][0] + 4.0).abs() < 1e-9 && (sol.theta[1][0] - 5.0).abs() < 1e-9);
        let confidence = Confidence {
            held_out: 1.0,
            threshold: 0.0,
            effective_rows: n as f64,
            gain_share: 0.5,
            chance_share: 0.0,
            size: 1.0,
            joint_share: 1.0,
            level: 1e-3,
        };
        let mut confirmed = Confirmed {
            explanation: Explanation {
                set: vec![0, 1],
                sol,
                rivals: vec![None, None],
                left_out: vec![],
            },
            confidence: vec![confidence, confidence],
            suggested: vec![],
            within_sample: None,
        };
        let cal = CalibrationSpread {
            coulomb: vec![10.0],
            viscous: vec![0.5],
            coulomb_corrected: vec![true],
            viscous_corrected: vec![true],
        };
        // The viscous correction alone: (a + c) . (a + 5 c) / |a + c|^2 =
        // 210 / 202.
        let alone = pool.solve(&[1]).theta[0][0];
        assert!((alone - 210.0 / 202.0).abs() < 1e-9, "{alone}");
        keep_changes(&mut confirmed, &pool, &cal, 0.0, |set| pool.solve(set));
        assert!(confirmed.explanation.set.is_empty());
        let moved: Vec<usize> = confirmed.suggested.iter().map(|s| s.term).collect();
        assert_eq!(moved, vec![0, 1]);
        assert!((confirmed.suggested[1].theta[0] - alone).abs() < 1e-12);
        assert!(matches!(
            confirmed.suggested[1].why,
            Unconfirmed::WithinCalibration(s) if s == 0.5
        ));
    }
}
