//! The others' efforts made where read against a copy of the record with
//! them added along it.

use nalgebra::{DMatrix, DVector, SVector};

use super::*;
use crate::diagnose::candidates::{LinkBasis, MotorGuess};
use crate::diagnose::fit::{fit, fixed_column, Load};
use crate::diagnose::select::pool::{test_pool, test_term};
use crate::effects::{Effect, SIGN_SMOOTHING};
use crate::synth::{synthesize, SynthOptions};
use crate::test_robots::Arm2;

fn bits<const N: usize>(a: &SVector<f64, N>, b: &SVector<f64, N>) -> bool {
    a.iter()
        .zip(b.iter())
        .all(|(x, y)| x.to_bits() == y.to_bits())
}

/// A motor side searched against the others' efforts made where read
/// (at the rows, at its joint over what it simulates) finds what it finds
/// on a copy of the record with the others' efforts in its model at every
/// sample, to the bit: the model and residual at every sample and joint,
/// the model along a joint (made for the samples asked, or kept along the
/// record while motor sides read it), the residual at the rows, the fits (a stiff
/// rotor, elasticity) and their fixed columns. The others hold joint
/// terms at both joints and terms that reach every joint (a payload, an
/// encoder offset), a link term and a motor side (both left out).
#[test]
fn the_others_made_where_read_are_the_copys() {
    let robot = Arm2::default();
    let effects = [
        Effect::ViscousFriction { joint: 0, fv: 0.3 },
        Effect::CoulombFriction {
            joint: 1,
            fc: 0.4,
            vw: SIGN_SMOOTHING,
        },
        Effect::JointElasticity {
            joint: 1,
            stiffness: 5300.0,
            damping: 14.4,
            motor_inertia: 0.02,
        },
    ];
    let opts = SynthOptions {
        duration: 3.0,
        seed: 7,
        ..Default::default()
    };
    let m = synthesize(&robot, &effects, &opts).expect("a generated record");
    let p = Prepared::new(&robot, &m);
    let n = p.sig.t.len();
    let (a, z) = p.sig.range;
    let mut terms = vec![
        test_term(Candidate::Viscous(0), vec![0], vec![true], None),
        test_term(
            Candidate::Coulomb(1, SIGN_SMOOTHING),
            vec![1],
            vec![true],
            None,
        ),
        test_term(
            Candidate::Stribeck(1, 0.05),
            vec![2, 3],
            vec![true; 2],
            None,
        ),
        test_term(Candidate::Payload, vec![4], vec![false], None),
        test_term(Candidate::EncoderOffset(0), vec![5], vec![false], None),
        test_term(Candidate::EffortOffset(1), vec![6], vec![false], None),
        test_term(Candidate::Elasticity(0), vec![], vec![], Some(7)),
        test_term(Candidate::Inertial(0), vec![8], vec![false], None),
    ];
    terms[7].link = Some(LinkBasis {
        link: 0,
        v: DMatrix::zeros(10, 1),
        tip: false,
        moments: false,
    });
    let pool = test_pool(DMatrix::zeros(1, 9), DVector::zeros(1), terms, 2);
    let set: Vec<usize> = (0..8).collect();
    let sol = Solution {
        theta: vec![
            vec![0.29],
            vec![0.38],
            vec![0.01, 0.005],
            vec![0.01],
            vec![-1e-4],
            vec![0.01],
            vec![],
            vec![1e3],
        ],
        std: vec![vec![]; 8],
        sse: 0.0,
        k: 0,
    };
    let copy = without_others(&p, &pool, &set, &sol);
    let on = against_others(&p, &pool, &set, &sol);
    let mut moved = 0usize;
    for k in 0..n {
        assert!(bits(&on.residual_at(k), &copy.sig.residual[k]), "{k}");
        for j in 0..2 {
            let x = on.model_at(k, j);
            assert_eq!(x.to_bits(), copy.sig.model[k][j].to_bits(), "{k} {j}");
            moved += usize::from(x != p.sig.model[k][j]);
        }
    }
    // Not a comparison of the record with itself (inside the range only).
    assert!(moved > (z - a), "{moved}");
    // Made for the samples asked, and kept along the record for the motor
    // sides said to read the joint.
    let same_along = |j: usize| {
        for (lo, hi) in [(0, n), (a + 17, a + 900), (z - 5, n)] {
            let along = on.model_along(j, lo, hi);
            assert_eq!(along.len(), hi - lo);
            for (x, k) in along.iter().zip(lo..hi) {
                assert_eq!(x.to_bits(), copy.sig.model[k][j].to_bits(), "{k} {j}");
            }
        }
    };
    same_along(0);
    same_along(1);
    on.expect(1, 3);
    same_along(1);
    for (i, &k) in p.rows.iter().enumerate() {
        assert!(bits(&on.residual_row(i), &copy.sig.residual[k]), "row {i}");
    }
    for c in [Candidate::Armature(1), Candidate::Elasticity(1)] {
        let f = fit_against::<Arm2, 2>(c, &on);
        let g = fit::<Arm2, 2>(c, &copy);
        assert!(f.motor.is_some(), "{c:?}");
        assert_eq!(f.sse.to_bits(), g.sse.to_bits(), "{c:?}");
        let guess = |m: Option<MotorGuess>| {
            m.map(|m| [m.jm, m.stiffness, m.damping, m.half_width].map(f64::to_bits))
        };
        assert_eq!(guess(f.motor), guess(g.motor), "{c:?}");
        assert_eq!(guess(f.motor_std), guess(g.motor_std), "{c:?}");
        let theta = |f: &Fit| f.theta.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(theta(&f), theta(&g), "{c:?}");
        let (x, y) = (fixed_column_against(&f, &on), fixed_column(&f, &copy));
        assert_eq!(x.len(), y.len());
        assert!(x.iter().zip(&y).all(|(x, y)| x.to_bits() == y.to_bits()));
        assert!(x.iter().any(|x| *x != 0.0), "{c:?}");
        // Against the record's own residual the same search finds another
        // optimum.
        assert_ne!(fit::<Arm2, 2>(c, &p).sse.to_bits(), f.sse.to_bits());
        on.done(1);
    }
    on.done(1);
    same_along(1);
}

/// A candidate said to act at one joint has columns that are zero, to
/// the bit, at every other joint (the others' efforts at a joint skip
/// them).
#[test]
fn a_joint_candidates_columns_are_zero_elsewhere() {
    let robot = Arm2::default();
    let opts = SynthOptions {
        duration: 1.0,
        seed: 3,
        ..Default::default()
    };
    let m = synthesize(&robot, &[], &opts).expect("a generated record");
    let p = Prepared::new(&robot, &m);
    let (a, z) = p.sig.range;
    for j in 0..2 {
        let joint = [
            Candidate::Coulomb(j, SIGN_SMOOTHING),
            Candidate::Viscous(j),
            Candidate::Stribeck(j, 0.05),
            Candidate::Armature(j),
            Candidate::EffortScale(j),
            Candidate::EffortOffset(j),
            Candidate::Spring(j),
        ];
        for c in joint {
            assert_eq!(c.local_joint(), Some(j));
            let mut own = 0usize;
            for k in a..z {
                let cols = c.columns(&p.sig, &p.basis, k);
                for col in cols {
                    assert_eq!(col[1 - j].to_bits(), 0.0f64.to_bits(), "{c:?} {k}");
                }
                own += usize::from(cols[0][j] != 0.0);
            }
            assert!(own > 0, "{c:?}");
        }
    }
    for c in [
        Candidate::EncoderOffset(0),
        Candidate::Payload,
        Candidate::TimeDelay(0.0),
    ] {
        assert_eq!(c.local_joint(), None);
    }
}
