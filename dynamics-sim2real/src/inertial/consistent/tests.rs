//! Tests of the pseudo-inertia, [`complete`] and [`nearest_physical`].

use super::*;
use crate::inertial::check;

/// A rod along x: 2 kg, COM at 0.3 m.
fn rod() -> SVector<f64, 10> {
    let (m, c, l) = (2.0, 0.3, 0.4);
    let iyy = m * l * l / 12.0 + m * c * c;
    SVector::from([m, m * c, 0.0, 0.0, 1e-4, 0.0, iyy, 0.0, 0.0, iyy])
}

/// The pseudo-inertia test agrees with the mass-properties check on
/// physical and unphysical parameter sets.
#[test]
fn pseudo_inertia_agrees_with_the_check() {
    let r = rod();
    assert!(margin(&r) >= 0.0 && check(&r, 1e-9).is_ok());
    let mut neg = r;
    neg[0] = -0.1;
    assert!(margin(&neg) < 0.0 && check(&neg, 1e-9).is_err());
    let mut far = r;
    far[1] = 2.0 * 0.9; // COM at 0.9 m: the inertia about it is negative
    assert!(margin(&far) < 0.0 && check(&far, 1e-9).is_err());
    let mut flat = r;
    flat[4] = 1.0; // triangle inequality broken
    assert!(margin(&flat) < 0.0 && check(&flat, 1e-9).is_err());
}

/// A point mass (a pseudo-inertia of rank one, on the boundary of the
/// physical set) whose centre of mass the data move sideways: the
/// free combinations (all but `m c_y`) take the inertia along.
#[test]
fn a_point_mass_moved_sideways_stays_physical() {
    let nominal = SVector::<f64, 10>::from([1.0, 0.3, 0.0, 0.0, 0.0, 0.0, 0.09, 0.0, 0.0, 0.09]);
    let mut delta = SVector::<f64, 10>::zeros();
    delta[2] = 0.01;
    assert!(check(&(nominal + delta), 1e-9).is_err());
    let mut free = DMatrix::<f64>::zeros(10, 9);
    for (c, e) in [0, 1, 3, 4, 5, 6, 7, 8, 9].iter().enumerate() {
        free[(*e, c)] = 1.0;
    }
    let done = complete(&nominal, &delta, &free).expect("physical nominal");
    assert!(done.scale > 0.99, "{done:?}");
    assert!(check(&(nominal + done.delta), 1e-6).is_ok(), "{done:?}");
    assert_eq!(done.delta[2], delta[2] * done.scale);
}

/// A correction the data determine only in part: moved along the free
/// combination it becomes physical, and its determined part is kept
/// (what the data see is unchanged).
#[test]
fn a_free_combination_makes_the_correction_physical() {
    let nominal = rod();
    // Determined: I_yy - I_zz; the data ask for I_yy - I_zz = +0.2,
    // which with I_zz unchanged breaks the triangle inequality.
    let det =
        SVector::<f64, 10>::from([0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, -1.0]) / 2f64.sqrt();
    let delta = det * (0.2 * 2f64.sqrt());
    assert!(check(&(nominal + delta), 1e-9).is_err());
    // Free: everything orthogonal to `det`.
    let mut free = DMatrix::<f64>::zeros(10, 9);
    let mut c = 0;
    for e in 0..10 {
        let mut v = SVector::<f64, 10>::zeros();
        v[e] = 1.0;
        v -= det * det.dot(&v);
        if v.norm() < 1e-9 || c == 9 {
            continue;
        }
        for r in 0..c {
            let u = SVector::<f64, 10>::from_fn(|i, _| free[(i, r)]);
            v -= u * u.dot(&v);
        }
        if v.norm() > 1e-9 {
            free.set_column(c, &v.normalize());
            c += 1;
        }
    }
    let done = complete(&nominal, &delta, &free).expect("physical nominal");
    assert_eq!(done.scale, 1.0);
    assert!(done.moved);
    assert!(check(&(nominal + done.delta), 1e-6).is_ok(), "{done:?}");
    assert!((det.dot(&done.delta) - det.dot(&delta)).abs() < 1e-9);
}

/// A point mass on the x axis cannot lose inertia about x: a fit
/// asking for that and for 0.5 kg more (every combination determined)
/// is not physical at any scale but 0, which keeps nothing; the
/// nearest physical body keeps the added mass and is a body.
#[test]
fn the_nearest_body_keeps_what_scaling_back_loses() {
    let nominal = SVector::<f64, 10>::from([1.0, 0.3, 0.0, 0.0, 0.0, 0.0, 0.09, 0.0, 0.0, 0.09]);
    assert!(margin(&nominal) > -1e-12);
    let mut delta = SVector::<f64, 10>::zeros();
    delta[0] = 0.5;
    delta[4] = -0.01;
    for s in [1.0, 0.1, 0.01] {
        assert!(margin(&(nominal + delta * s)) < -1e-6, "{s}");
    }
    let free = DMatrix::<f64>::zeros(10, 0);
    let done = complete(&nominal, &delta, &free).expect("physical nominal");
    assert!(done.projected, "{done:?}");
    assert!(check(&(nominal + done.delta), 1e-6).is_ok(), "{done:?}");
    assert!((done.delta[0] - 0.5).abs() < 0.05, "{done:?}");
    assert!((done.delta - delta).norm() < delta.norm());
    // A fit that a free move makes physical is not projected.
    let fine = complete(&nominal, &(delta * 0.0), &free).expect("physical");
    assert!(!fine.projected && fine.scale == 1.0);
}
