//! The ranking's decisions on hand-made fits: parsimony, the rotor that
//! leaves only noise, the held-out record's evidence.

use super::*;
use crate::effects::SIGN_SMOOTHING;

fn fit(candidate: Candidate, sse: f64, k: usize) -> Fit {
    Fit {
        candidate,
        theta: vec![],
        std: vec![],
        motor: None,
        motor_std: None,
        sse,
        k,
    }
}

/// An elastic joint 30 AICc ahead of the rotor it contains goes first
/// unless the rotor leaves its joint within the noise floor; Stribeck
/// over Coulomb is left to the margin alone.
#[test]
fn a_motor_side_goes_behind_a_rotor_that_leaves_only_noise() {
    let n = 900;
    // AICc n ln(sse / n) + 2k + ...: sse 1000 against 1034 is 30 ahead
    // after the 2 extra parameters' 4.
    let fits = || {
        vec![
            fit(Candidate::Armature(1), 1034.0, 1),
            fit(Candidate::Elasticity(1), 1000.0, 3),
            fit(Candidate::Viscous(0), 1100.0, 1),
        ]
    };
    let gain = aicc_of(1034.0, n, 1) - aicc_of(1000.0, n, 3);
    assert!(gain > 25.0 && gain < 35.0, "{gain}");
    let none = |_: &Fit| 0.0;
    let judge = |quiet: &dyn Fn(&Fit) -> bool| -> Vec<Fit> {
        best_per_place(
            fits(),
            n,
            10.0,
            &Judge {
                quiet,
                held_out: &none,
            },
        )
    };
    let loud = judge(&|_| false);
    assert_eq!(loud[0].candidate, Candidate::Elasticity(1));
    let quiet = judge(&|f| {
        assert_eq!(f.candidate, Candidate::Armature(1));
        true
    });
    assert_eq!(quiet[0].candidate, Candidate::Armature(1));
    assert_eq!(quiet[1].candidate, Candidate::Elasticity(1));
    // Stribeck 30 ahead of Coulomb stays first whatever `quiet` says.
    let friction = vec![
        fit(Candidate::Coulomb(0, SIGN_SMOOTHING), 1034.0, 1),
        fit(Candidate::Stribeck(0, 0.03), 1000.0, 3),
    ];
    let s = best_per_place(
        friction,
        n,
        10.0,
        &Judge {
            quiet: &|_| true,
            held_out: &none,
        },
    );
    assert_eq!(s[0].candidate, Candidate::Stribeck(0, 0.03));
}

/// The held-out deviance adds to the training AICc: an elastic joint
/// 30 AICc ahead of a backlash at its joint goes behind it when the
/// backlash predicts the held-out record 40 better (and stays first at
/// 20), and a Stribeck friction 8 ahead of Coulomb (under the margin
/// of 10) goes first when it predicts the held-out record 5 better; a
/// motor side ahead of its rotor by less than the margin does not, and
/// one ahead by more goes behind its rotor when it predicts the held-out
/// record worse by more than its lead less the margin.
#[test]
fn the_held_out_record_adds_its_evidence() {
    let n = 900;
    let fits = || {
        vec![
            fit(Candidate::Armature(1), 1300.0, 1),
            fit(Candidate::Backlash(1), 1034.0, 4),
            fit(Candidate::Elasticity(1), 1000.0, 3),
        ]
    };
    let lead = aicc_of(1034.0, n, 4) - aicc_of(1000.0, n, 3);
    assert!(lead > 25.0 && lead < 35.0, "{lead}");
    let rank = |fits: Vec<Fit>, backlash: f64, stribeck: f64| -> Candidate {
        let held_out = |f: &Fit| match f.candidate {
            Candidate::Backlash(_) => -backlash,
            Candidate::Stribeck(..) => -stribeck,
            _ => 0.0,
        };
        best_per_place(
            fits,
            n,
            10.0,
            &Judge {
                quiet: &|_| false,
                held_out: &held_out,
            },
        )[0]
        .candidate
    };
    assert_eq!(rank(fits(), 40.0, 0.0), Candidate::Backlash(1));
    assert_eq!(rank(fits(), 20.0, 0.0), Candidate::Elasticity(1));
    let friction = || {
        vec![
            fit(Candidate::Coulomb(0, SIGN_SMOOTHING), 1000.0, 1),
            fit(Candidate::Stribeck(0, 0.03), 986.0, 3),
        ]
    };
    let gain = aicc_of(1000.0, n, 1) - aicc_of(986.0, n, 3);
    assert!(gain > 5.0 && gain < 10.0, "{gain}");
    assert_eq!(
        rank(friction(), 0.0, 0.0),
        Candidate::Coulomb(0, SIGN_SMOOTHING)
    );
    assert_eq!(rank(friction(), 0.0, 5.0), Candidate::Stribeck(0, 0.03));
    // A motor side 5 ahead of its rotor stays behind it, however well
    // it predicts the held-out record.
    let motor = vec![
        fit(Candidate::Armature(1), 1000.0, 1),
        fit(Candidate::Backlash(1), 986.0, 4),
    ];
    assert!(aicc_of(1000.0, n, 1) - aicc_of(986.0, n, 4) > 0.0);
    assert_eq!(rank(motor, 100.0, 0.0), Candidate::Armature(1));
    // A motor side 25 ahead of its rotor on training goes behind it when
    // it predicts the held-out record 40 worse, and stays first at 10.
    let motor = || {
        vec![
            fit(Candidate::Armature(1), 1030.0, 1),
            fit(Candidate::Backlash(1), 1000.0, 4),
        ]
    };
    let lead = aicc_of(1030.0, n, 1) - aicc_of(1000.0, n, 4);
    assert!(lead > 20.0 && lead < 30.0, "{lead}");
    assert_eq!(rank(motor(), -40.0, 0.0), Candidate::Armature(1));
    assert_eq!(rank(motor(), -10.0, 0.0), Candidate::Backlash(1));
}

fn aicc_of(sse: f64, n: usize, k: usize) -> f64 {
    crate::diagnose::numeric::aicc(sse, n, k)
}
