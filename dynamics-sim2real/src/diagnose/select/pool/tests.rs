use super::test_pool;
use super::test_term as term;
use super::*;
use crate::diagnose::numeric::constrained_least_squares;
use crate::effects::SIGN_SMOOTHING;

/// The Gram route against a direct least-squares fit of the same
/// columns, with a fixed column subtracted and a sign constraint that
/// becomes active.
#[test]
fn joint_fits_from_the_gram_match_direct_least_squares() {
    let n = 300;
    let c0: Vec<f64> = (0..n).map(|i| (i as f64 * 0.05).sin()).collect();
    let c1: Vec<f64> = (0..n).map(|i| (i as f64 * 0.013).cos()).collect();
    let c2: Vec<f64> = (0..n).map(|i| ((i % 7) as f64 - 3.0) * 0.1).collect();
    let fixed: Vec<f64> = (0..n).map(|i| 0.3 * (i as f64 * 0.2).sin()).collect();
    let mut rng = crate::synth::Rng::new(5);
    // y = 2 c0 - 0.7 c1 + 1.5 c2 + fixed + noise.
    let y: Vec<f64> = (0..n)
        .map(|i| 2.0 * c0[i] - 0.7 * c1[i] + 1.5 * c2[i] + fixed[i] + 0.01 * rng.normal())
        .collect();
    let cols = [c0.clone(), c1.clone(), c2.clone(), fixed.clone()];
    let x = DMatrix::from_fn(n, 4, |r, c| cols[c][r]);
    let yv = DVector::from_vec(y.clone());
    let terms = vec![
        term(
            Candidate::Coulomb(0, SIGN_SMOOTHING),
            vec![0],
            vec![true],
            None,
        ),
        term(Candidate::Viscous(0), vec![1], vec![true], None),
        term(Candidate::EffortOffset(0), vec![2], vec![false], None),
        term(Candidate::Elasticity(1), vec![], vec![], Some(3)),
    ];
    let pool = test_pool(x, yv.clone(), terms, 1);
    // All four: the viscous coefficient wants -0.7, is held at 0.
    let sol = pool.solve(&[0, 1, 2, 3]);
    let y_minus_fixed = DVector::from_fn(n, |r, _| y[r] - fixed[r]);
    let direct = constrained_least_squares(
        &DMatrix::from_fn(n, 3, |r, c| cols[c][r]),
        &y_minus_fixed,
        &[true, true, false],
    );
    assert_eq!(sol.theta[1][0], 0.0);
    for (t, d) in [(0, 0), (2, 2)] {
        assert!((sol.theta[t][0] - direct.theta[d]).abs() < 1e-9, "{t}");
        assert!((sol.std[t][0] / direct.std[d] - 1.0).abs() < 1e-6);
    }
    assert!((sol.sse / direct.sse - 1.0).abs() < 1e-9);
    // The held coefficient's spread is the one it has freed: the
    // unconstrained fit's, scaled by the two fits' residuals (the same
    // degrees of freedom), by both routes.
    let unconstrained = constrained_least_squares(
        &DMatrix::from_fn(n, 3, |r, c| cols[c][r]),
        &y_minus_fixed,
        &[false, false, false],
    );
    assert!(unconstrained.theta[1] < -0.5);
    let freed = unconstrained.std[1] * (direct.sse / unconstrained.sse).sqrt();
    assert!(
        (sol.std[1][0] / freed - 1.0).abs() < 1e-6,
        "{:?} vs {freed}",
        sol.std[1]
    );
    assert!((direct.std[1] / freed - 1.0).abs() < 1e-9);
    assert_eq!(sol.k, 1 + 1 + 1 + 3);
    // The residual it leaves is the direct one.
    let r = pool.residual(&[0, 1, 2, 3], &sol);
    assert!((r.norm_squared() / direct.sse - 1.0).abs() < 1e-9);
    // Without the fixed column the fit is worse.
    assert!(pool.solve(&[0, 1, 2]).sse > sol.sse + 1.0);
}

/// A term whose column a term before it already spans is left out of
/// the fit and of the parameter count, and a term after the pair is
/// still fitted (not dropped as the last column of a singular set).
#[test]
fn a_dependent_column_does_not_hide_the_terms_after_it() {
    let n = 200;
    let c0: Vec<f64> = (0..n).map(|i| (i as f64 * 0.05).sin()).collect();
    let c1: Vec<f64> = (0..n).map(|i| (i as f64 * 0.011).cos()).collect();
    let y: Vec<f64> = (0..n).map(|i| 2.0 * c0[i] + 0.5 * c1[i]).collect();
    // Column 1 repeats column 0 (a regrouped link parameter).
    let cols = [c0.clone(), c0.clone(), c1.clone()];
    let x = DMatrix::from_fn(n, 3, |r, c| cols[c][r]);
    let yv = DVector::from_vec(y);
    let terms = vec![
        term(Candidate::EffortOffset(0), vec![0], vec![false], None),
        term(Candidate::EffortOffset(1), vec![1], vec![false], None),
        term(Candidate::EffortOffset(2), vec![2], vec![false], None),
    ];
    let pool = test_pool(x, yv, terms, 1);
    let sol = pool.solve(&[0, 1, 2]);
    assert!((sol.theta[0][0] - 2.0).abs() < 1e-9, "{:?}", sol.theta);
    assert_eq!(sol.theta[1][0], 0.0);
    assert!((sol.theta[2][0] - 0.5).abs() < 1e-9, "{:?}", sol.theta);
    assert!(sol.sse < 1e-9);
    assert_eq!(sol.k, 2);
}

/// Reweighting two joints' rows keeps the residual in floor units,
/// leaves an exact fit's parameter where it is, and moves a fit that
/// must compromise between the joints toward the heavier one, as a
/// direct weighted least-squares fit does.
#[test]
fn reweighting_the_joints_rows_is_weighted_least_squares() {
    let rows = 200;
    // Rows interleaved: joint 0, joint 1, joint 0, ...
    let c0: Vec<f64> = (0..2 * rows)
        .map(|i| ((i / 2) as f64 * 0.07).sin())
        .collect();
    // Joint 0 wants 2, joint 1 wants 3.
    let y: Vec<f64> = (0..2 * rows)
        .map(|i| if i % 2 == 0 { 2.0 } else { 3.0 } * c0[i])
        .collect();
    let x = DMatrix::from_column_slice(2 * rows, 1, &c0);
    let yv = DVector::from_vec(y.clone());
    let terms = vec![term(Candidate::EffortScale(0), vec![0], vec![false], None)];
    let mut pool = test_pool(x, yv, terms, 2);
    let even = pool.solve(&[0]);
    assert!((even.theta[0][0] - 2.5).abs() < 1e-9, "{:?}", even.theta);
    let before = pool.floor_rms(&pool.residual(&[0], &even));
    pool.reweight(&[1.0, 0.1]);
    // The same parameters leave the same residual in floor units.
    let again = pool.floor_rms(&pool.residual(&[0], &even));
    for j in 0..2 {
        assert!((again[j] / before[j] - 1.0).abs() < 1e-12);
    }
    // Weighted least squares: (2 * 1 + 3 * 0.01) / 1.01.
    let heavy = pool.solve(&[0]);
    assert!(
        (heavy.theta[0][0] - 2.03 / 1.01).abs() < 1e-9,
        "{:?}",
        heavy.theta
    );
    // Back to even weights: the even fit again.
    pool.reweight(&[1.0, 1.0]);
    assert!((pool.solve(&[0]).theta[0][0] - 2.5).abs() < 1e-9);
}

/// A link correction the free fit takes below any body (its mass
/// determined alone, 3 kg taken from a 2 kg rod) is moved to the nearest
/// physical one: it leaves a body, it is on the boundary (a little more
/// taken leaves none), the fit is worse than the free one, and the other
/// term is fitted again with the link held. A physical fit is left alone.
#[test]
fn a_link_correction_is_held_to_a_body() {
    use crate::diagnose::candidates::{delta, LinkBasis};
    let rod = crate::inertial::tests::rod();
    let n = 400;
    let mass: Vec<f64> = (0..n).map(|i| (i as f64 * 0.05).sin()).collect();
    let other: Vec<f64> = (0..n).map(|i| (i as f64 * 0.011).cos()).collect();
    let x = DMatrix::from_fn(n, 2, |r, k| if k == 0 { mass[r] } else { other[r] });
    let fit = |dm: f64| {
        let y = DVector::from_fn(n, |r, _| dm * mass[r] + 0.5 * other[r]);
        let mut link = term(Candidate::Inertial(0), vec![0], vec![false], None);
        let mut v = DMatrix::<f64>::zeros(10, 1);
        v[(0, 0)] = 1.0;
        link.link = Some(LinkBasis {
            link: 0,
            v,
            tip: false,
            moments: false,
        });
        let offset = term(Candidate::EffortOffset(0), vec![1], vec![false], None);
        test_pool(x.clone(), y, vec![link, offset], 1)
    };
    let pool = fit(-3.0);
    let free = pool.solve(&[0, 1]);
    let held = pool.solve_physical(&[0, 1], &[rod]);
    assert!((free.theta[0][0] + 3.0).abs() < 1e-9);
    let b = pool.terms[0].link.clone().expect("a link term");
    let change = |dm: f64| delta(&b, &[dm]);
    let dm = held.theta[0][0];
    assert!(dm > -2.0 && dm < 0.0, "{dm}");
    assert!(leaves_a_body(&rod, &change(dm), &b.free_combinations()));
    assert!(!leaves_a_body(
        &rod,
        &change(dm - 0.01),
        &b.free_combinations()
    ));
    assert!(held.sse > free.sse);
    // The offset fitted again with the link held: the direct fit of what
    // the held link leaves.
    let g = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    let rest: Vec<f64> = (0..n)
        .map(|r| (-3.0 - dm) * mass[r] + 0.5 * other[r])
        .collect();
    let direct = g(&rest, &other) / g(&other, &other);
    assert!(
        (held.theta[1][0] - direct).abs() < 1e-9,
        "{} vs {direct}",
        held.theta[1][0]
    );
    // A fit that leaves a body is the free fit itself.
    let fine = fit(0.2);
    let (a, z) = (fine.solve(&[0, 1]), fine.solve_physical(&[0, 1], &[rod]));
    assert_eq!(a.theta, z.theta);
}

/// A block's Gram matrix kept by the pool is the one its rows give as they
/// are, to the bit: the same when asked again, and formed again once a
/// fixed column is replaced or the rows reweighted.
#[test]
fn a_blocks_gram_kept_is_its_rows_as_they_are() {
    let mut rng = crate::synth::Rng::new(23);
    let n = 120;
    let x = DMatrix::from_fn(n, 3, |_, _| rng.normal());
    let y = DVector::from_fn(n, |_, _| rng.normal());
    let terms = vec![
        term(Candidate::Viscous(0), vec![0], vec![false], None),
        term(Candidate::EffortOffset(1), vec![1], vec![false], None),
        term(Candidate::Elasticity(1), vec![], vec![], Some(2)),
    ];
    let mut pool = test_pool(x, y, terms, 2);
    let fresh = |pool: &Pool, a: usize, z: usize| {
        let x = pool.x.to_matrix();
        let xb = x.rows(a, z - a);
        let yb = pool.y.rows(a, z - a);
        (xb.tr_mul(&xb), xb.tr_mul(&yb), yb.norm_squared())
    };
    let same = |g: &RowsGram, f: &(DMatrix<f64>, DVector<f64>, f64)| {
        g.gram
            .iter()
            .zip(f.0.iter())
            .all(|(u, v)| u.to_bits() == v.to_bits())
            && g.xty
                .iter()
                .zip(f.1.iter())
                .all(|(u, v)| u.to_bits() == v.to_bits())
            && g.yy.to_bits() == f.2.to_bits()
    };
    let first = pool.rows_gram(30, 60);
    assert!(same(&first, &fresh(&pool, 30, 60)));
    assert!(same(&pool.rows_gram(30, 60), &fresh(&pool, 30, 60)));
    assert!(same(&pool.rows_gram(0, 30), &fresh(&pool, 0, 30)));
    // A fixed column searched again.
    let col: Vec<f64> = (0..n).map(|i| (i as f64 * 0.1).sin()).collect();
    let fit = pool.terms[2].fit.clone();
    pool.set_fixed(2, fit, col);
    let after = pool.rows_gram(30, 60);
    assert!(same(&after, &fresh(&pool, 30, 60)));
    assert_ne!(after.gram[(2, 2)].to_bits(), first.gram[(2, 2)].to_bits());
    // The joints' rows reweighted.
    pool.reweight(&[0.5, 2.0]);
    let reweighted = pool.rows_gram(30, 60);
    assert!(same(&reweighted, &fresh(&pool, 30, 60)));
    assert_ne!(reweighted.yy.to_bits(), after.yy.to_bits());
    // A clone keeps what it was given, and its own changes are its own.
    let mut other = pool.clone();
    assert!(same(&other.rows_gram(30, 60), &fresh(&pool, 30, 60)));
    other.reweight(&[1.0, 1.0]);
    assert!(same(&other.rows_gram(30, 60), &fresh(&other, 30, 60)));
    assert!(same(&pool.rows_gram(30, 60), &fresh(&pool, 30, 60)));
}

/// A pool whose columns zero off one joint are kept at that joint's rows
/// gives what the same pool with every column whole gives, to the bit:
/// its Gram matrices (all rows, blocks), fits, residuals, a fixed column
/// replaced, the rows reweighted, a term's column split; and keeps less.
#[test]
fn columns_kept_at_their_joints_rows_change_nothing() {
    let mut rng = crate::synth::Rng::new(41);
    let (rows, joints) = (203, 3);
    let n = rows * joints;
    let local = |rng: &mut crate::synth::Rng, j: usize| -> Vec<f64> {
        (0..n)
            .map(|i| {
                if i % joints == j {
                    rng.normal() * 3.0
                } else {
                    0.0
                }
            })
            .collect()
    };
    let cols = [
        local(&mut rng, 0),
        local(&mut rng, 1),
        (0..n).map(|_| rng.normal()).collect::<Vec<_>>(),
        local(&mut rng, 2),
        local(&mut rng, 1),
    ];
    let x = DMatrix::from_fn(n, cols.len(), |r, c| cols[c][r]);
    let y = DVector::from_fn(n, |r, _| {
        0.7 * cols[0][r] - 0.2 * cols[1][r] + 0.4 * cols[2][r] + cols[4][r] + rng.normal() * 0.1
    });
    let terms = vec![
        term(Candidate::Viscous(0), vec![0], vec![true], None),
        term(Candidate::EffortOffset(1), vec![1], vec![false], None),
        term(Candidate::TimeDelay(0.0), vec![2], vec![false], None),
        term(Candidate::EffortScale(2), vec![3], vec![false], None),
        term(Candidate::Elasticity(1), vec![], vec![], Some(4)),
    ];
    let mut kept = test_pool(x.clone(), y.clone(), terms.clone(), joints);
    let mut whole = test_pool(x, y, terms, joints);
    whole.x.keep_whole();
    assert_eq!(kept.x.kept(), n + 4 * rows);
    assert_eq!(whole.x.kept(), 5 * n);
    let bits = |m: &[f64]| m.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
    let all = [0, 1, 2, 3, 4];
    let check = |kept: &Pool, whole: &Pool| {
        assert_eq!(bits(kept.gram().as_slice()), bits(whole.gram().as_slice()));
        assert_eq!(bits(kept.xty().as_slice()), bits(whole.xty().as_slice()));
        for (a, z) in [(0, n), (13, 301), (600, 609), (5, 9)] {
            let (gk, gw) = (kept.rows_gram(a, z), whole.rows_gram(a, z));
            assert_eq!(bits(gk.gram.as_slice()), bits(gw.gram.as_slice()));
            assert_eq!(bits(gk.xty.as_slice()), bits(gw.xty.as_slice()));
        }
        let (sk, sw) = (kept.solve(&all), whole.solve(&all));
        assert_eq!(sk.sse.to_bits(), sw.sse.to_bits());
        let (rk, rw) = (kept.residual(&all, &sk), whole.residual(&all, &sw));
        assert_eq!(bits(rk.as_slice()), bits(rw.as_slice()));
        let part: Vec<f64> = (0..n).map(|i| (i as f64 * 0.01).sin()).collect();
        let split = |p: &Pool| p.split_off(&all, 2, &part, |q, s| q.solve(s));
        assert_eq!(split(kept), split(whole));
        assert!(split(kept).is_some());
    };
    check(&kept, &whole);
    // A fixed column searched again, at its joint.
    let col: Vec<f64> = (0..n)
        .map(|i| {
            if i % joints == 1 {
                (i as f64 * 0.1).sin()
            } else {
                0.0
            }
        })
        .collect();
    for p in [&mut kept, &mut whole] {
        let fit = p.terms[4].fit.clone();
        p.set_fixed(4, fit, col.clone());
    }
    check(&kept, &whole);
    assert_eq!(kept.x.kept(), n + 4 * rows);
    // The joints' rows reweighted.
    for p in [&mut kept, &mut whole] {
        p.reweight(&[0.5, 2.0, 1.5]);
    }
    check(&kept, &whole);
    assert_eq!(kept.x.kept(), n + 4 * rows);
}
