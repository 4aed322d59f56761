use super::*;
use crate::synth::Rng;

/// A value whose magnitude spans many orders (so that the order of a sum
/// shows in its last bits).
fn value(rng: &mut Rng) -> f64 {
    rng.normal() * 10f64.powi(rng.below(9) as i32 - 4)
}

/// Columns over `rows` rows of `joints` joints: whole ones, ones zero off
/// one joint (some with zeros at their joint too), one zero everywhere.
fn columns(rng: &mut Rng, rows: usize, joints: usize) -> DMatrix<f64> {
    let n = rows * joints;
    let m = 11;
    let kinds: Vec<(Option<usize>, bool)> = (0..m)
        .map(|c| match c % 4 {
            0 => (None, false),
            1 | 2 => (Some(rng.below(joints)), c % 8 == 1),
            _ if c == m - 1 => (Some(0), true),
            _ => (Some(joints - 1), false),
        })
        .collect();
    DMatrix::from_fn(n, m, |i, c| match kinds[c] {
        (None, _) => value(rng),
        (Some(j), gaps) if i % joints == j => {
            if c == m - 1 || (gaps && rng.below(3) == 0) {
                0.0
            } else {
                value(rng)
            }
        }
        (Some(_), _) => 0.0,
    })
}

fn same(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(u, v)| u.to_bits() == v.to_bits())
}

/// Every product of columns kept at one joint's rows is nalgebra's of the
/// whole columns, to the bit: the Gram matrix of all rows and of blocks
/// (row counts and block starts that are not multiples of eight, blocks
/// shorter than eight), `X^T y`, a column against the others, `axpy`
/// and subtraction, and again after the rows are reweighted.
#[test]
fn every_product_is_the_whole_columns_to_the_bit() {
    let mut rng = Rng::new(31);
    let mut order_shows = false;
    for (rows, joints) in [(1, 7), (5, 7), (13, 3), (37, 7), (100, 2), (61, 7)] {
        let x = columns(&mut rng, rows, joints);
        let n = x.nrows();
        let y = DVector::from_fn(n, |_, _| value(&mut rng));
        let mut cols = Cols::from_matrix(&x, joints);
        let locals = cols.cols.iter().filter(|c| c.joint.is_some()).count();
        assert_eq!(locals, 8, "{rows} x {joints}");
        assert_eq!(cols.kept(), 3 * n + 8 * rows);
        for s in [
            None,
            Some((0..joints).map(|j| 0.5 + j as f64).collect::<Vec<_>>()),
        ] {
            if let Some(s) = &s {
                cols.scale(s);
            }
            let x = match &s {
                None => x.clone(),
                Some(s) => DMatrix::from_fn(n, x.ncols(), |i, c| x[(i, c)] * s[i % joints]),
            };
            assert!(same(cols.to_matrix().as_slice(), x.as_slice()));
            let mut blocks = vec![(0, n), (0, n.min(7)), (n / 3, n)];
            for _ in 0..6 {
                let a = rng.below(n + 1);
                blocks.push((a, a + rng.below(n - a + 1)));
            }
            for (a, z) in blocks {
                let xb = x.rows(a, z - a);
                let yb = y.rows(a, z - a);
                let g = xb.tr_mul(&xb);
                assert!(
                    same(cols.gram(a, z).as_slice(), g.as_slice()),
                    "{rows} x {joints}, {a}..{z}"
                );
                let t = xb.tr_mul(&yb);
                assert!(same(
                    cols.tr_mul(y.as_slice(), a, z).as_slice(),
                    t.as_slice()
                ));
                // The order of the sums matters to the bit: one in order
                // differs somewhere.
                for u in 0..x.ncols() {
                    let plain: f64 = (0..z - a).map(|i| xb[(i, u)] * yb[i]).sum();
                    order_shows |= plain.to_bits() != t[u].to_bits();
                }
            }
            for c in 0..x.ncols() {
                let v = x.tr_mul(&x.column(c));
                assert!(same(cols.against(c).as_slice(), v.as_slice()));
                assert_eq!(
                    cols.column(c),
                    x.column(c).iter().copied().collect::<Vec<_>>()
                );
                let th = value(&mut rng);
                let (mut r, mut d) = (y.clone(), y.clone());
                cols.axpy(c, -th, &mut r);
                d.axpy(-th, &x.column(c), 1.0);
                assert!(same(r.as_slice(), d.as_slice()));
                cols.sub_from(c, &mut r);
                d -= x.column(c);
                assert!(same(r.as_slice(), d.as_slice()));
            }
        }
    }
    assert!(order_shows);
}

/// A column is kept at one joint's rows only when it is `+0.0` at every
/// other joint's rows and the pool's columns are finite; a value that is
/// not finite keeps every column whole, and a weight that would make a
/// zero other than `+0.0` too.
#[test]
fn a_column_is_kept_at_its_joints_rows_only_when_exact() {
    let (rows, joints) = (9, 3);
    let n = rows * joints;
    let at = |j: usize, off: f64| -> Vec<f64> {
        (0..n)
            .map(|i| if i % joints == j { 1.0 + i as f64 } else { off })
            .collect()
    };
    let mut cols = Cols::new(n, joints);
    cols.push(at(1, 0.0));
    cols.push(vec![0.0; n]);
    cols.push(at(2, -0.0));
    cols.push(at(0, 0.5));
    assert_eq!(
        cols.cols.iter().map(|c| c.joint).collect::<Vec<_>>(),
        [Some(1), Some(0), None, None]
    );
    assert_eq!(cols.kept(), 2 * rows + 2 * n);
    // A subset keeps each column as it is.
    let sub = cols.subset(&[1, 3]);
    assert_eq!(sub.kept(), rows + n);
    assert_eq!(sub.column(0), vec![0.0; n]);
    // A negative weight: every column whole, the same values.
    let mut neg = cols.clone();
    neg.scale(&[1.0, -2.0, 1.0]);
    assert!(neg.cols.iter().all(|c| c.joint.is_none()));
    assert!(neg.column(0).iter().all(|x| x.is_finite()));
    assert!(neg.column(1)[1].is_sign_negative());
    // A column that is not finite: every column whole, from then on.
    let mut bad = at(1, 0.0);
    bad[1] = f64::NAN;
    cols.set(3, bad);
    assert!(cols.whole);
    assert_eq!(cols.kept(), 4 * n);
    cols.push(at(2, 0.0));
    assert_eq!(cols.kept(), 5 * n);
    // One joint, or rows that are not whole rows of the joints: whole.
    assert!(Cols::new(10, 1).whole && Cols::new(10, 3).whole);
}
