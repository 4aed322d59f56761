//! Each joint's friction in the calibrated model: the nominal model's own
//! Coulomb level and viscous coefficient with the explanation's
//! corrections added (`coulomb_friction` and `stribeck_friction` correct
//! the Coulomb level, `viscous_friction` the coefficient; a Stribeck
//! friction's excess raises the breakaway level above it). What a user
//! puts into a controller's friction compensation, and where the
//! explanation kept the nominal values (no correction: the data agree with
//! them, or cannot say).

use nalgebra::SVector;

use crate::diagnose::evaluate::FrictionSpread;
use crate::diagnose::explain::report::{Explained, JointFriction};
use crate::effects::EffectKind;

/// The friction of every joint (`names`) with the nominal Coulomb levels
/// `coulomb` and viscous coefficients `viscous` and the corrections of
/// `effects`; `spread`: what the data tell of each.
pub fn friction_table<const N: usize>(
    names: &[&str; N],
    coulomb: &SVector<f64, N>,
    viscous: &SVector<f64, N>,
    effects: &[Explained],
    spread: &FrictionSpread<N>,
) -> Vec<JointFriction> {
    let correction = |joint: &str, kinds: &[EffectKind], name: &str| {
        let mut found = false;
        let sum: f64 = effects
            .iter()
            .filter(|e| e.joint.as_deref() == Some(joint))
            .filter(|e| kinds.contains(&e.kind))
            .filter_map(|e| e.parameters.iter().find(|p| p.name == name))
            .map(|p| {
                found = true;
                p.value
            })
            .filter(|v| v.is_finite())
            .sum();
        (sum, found)
    };
    (0..N)
        .map(|j| {
            let joint = names[j];
            let (fc, c_named) = correction(
                joint,
                &[EffectKind::CoulombFriction, EffectKind::StribeckFriction],
                "fc",
            );
            let (excess, _) = correction(joint, &[EffectKind::StribeckFriction], "fs_minus_fc");
            let (fv, v_named) = correction(joint, &[EffectKind::ViscousFriction], "fv");
            let (c0, v0) = (finite(coulomb[j]), finite(viscous[j]));
            let level = (c0 + fc).max(0.0);
            JointFriction {
                joint: joint.to_string(),
                coulomb_nominal: c0,
                coulomb: level,
                breakaway: level + excess.max(0.0),
                viscous_nominal: v0,
                viscous: (v0 + fv).max(0.0),
                corrected: c_named || v_named,
                coulomb_std: known(spread.coulomb[j]),
                viscous_std: known(spread.viscous[j]),
            }
        })
        .collect()
}

/// `x` when finite and not negative.
fn known(x: f64) -> Option<f64> {
    (x.is_finite() && x >= 0.0).then_some(x)
}

/// `x` when finite and not negative, else 0.
fn finite(x: f64) -> f64 {
    if x.is_finite() {
        x.max(0.0)
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnose::explain::report::test_entry as entry;

    /// By hand: j1 nominal 0.8 N m s/rad, corrected by -0.8 (all taken
    /// away), Coulomb 0 + 0.3; j2 keeps its nominal 0.2 / 0.5; j3 has a
    /// Stribeck correction of +0.1 on a nominal 0.4, breaking away at 0.25
    /// above that.
    #[test]
    fn nominal_friction_plus_the_corrections() {
        let effects = vec![
            entry(EffectKind::ViscousFriction, "j1", "fv", -0.8),
            entry(EffectKind::CoulombFriction, "j1", "fc", 0.3),
            entry(EffectKind::StribeckFriction, "j3", "fc", 0.1),
            entry(EffectKind::StribeckFriction, "j3", "fs_minus_fc", 0.25),
            entry(EffectKind::EffortOffset, "j2", "offset", 0.7),
        ];
        let t = friction_table(
            &["j1", "j2", "j3"],
            &SVector::<f64, 3>::new(0.0, 0.2, 0.4),
            &SVector::<f64, 3>::new(0.8, 0.5, 0.0),
            &effects,
            &FrictionSpread {
                coulomb: SVector::<f64, 3>::new(0.01, f64::NAN, 0.02),
                viscous: SVector::<f64, 3>::new(0.003, 0.004, -1.0),
            },
        );
        assert_eq!(t[0].joint, "j1");
        assert_eq!(
            (t[0].coulomb_std, t[0].viscous_std),
            (Some(0.01), Some(0.003))
        );
        assert_eq!((t[1].coulomb_std, t[2].viscous_std), (None, None));
        assert!((t[0].viscous - 0.0).abs() < 1e-12 && (t[0].viscous_nominal - 0.8).abs() < 1e-12);
        assert!((t[0].coulomb - 0.3).abs() < 1e-12 && t[0].corrected);
        assert!((t[1].coulomb - 0.2).abs() < 1e-12 && (t[1].viscous - 0.5).abs() < 1e-12);
        assert!(!t[1].corrected);
        assert!((t[2].coulomb - 0.5).abs() < 1e-12 && t[2].corrected);
        assert!((t[2].breakaway - 0.75).abs() < 1e-12);
        assert!((t[0].breakaway - t[0].coulomb).abs() < 1e-12);
        assert!((t[1].breakaway - 0.2).abs() < 1e-12);
    }
}
