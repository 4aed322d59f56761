//! A link correction made physical without changing what the data see.
//!
//! A link's ten parameters are a physical body (a nonnegative density
//! could produce them) exactly when its pseudo-inertia matrix
//! `J = [[1/2 tr(I) 1 - I, h], [h^T, m]]` (`I` about the frame origin,
//! `h = m c`) is positive semi-definite (Wensing, Kim and Slotine, RA-L
//! 2018): mass >= 0, inertia about the centre of mass positive
//! semi-definite and within the triangle inequalities. A fitted
//! correction is determined only along some combinations of the ten
//! parameters; along the others (`free`) any value fits the data equally.
//! [`complete`] moves the correction along the free combinations, by the
//! least move in the link's units (`size.rs`) that makes `J` positive
//! semi-definite (a small semi-definite program: `barrier.rs`); when no
//! such move exists, the fit's nearest physical body is taken if it keeps
//! most of the determined part, else the determined part is scaled back,
//! and the scale said.

use nalgebra::{DMatrix, Matrix3, Matrix4, SVector};

use super::barrier::nearest_move;
use super::pseudo::{margin, pseudo_inertia};
use super::size::units;

/// A correction made physical.
#[derive(Debug, Clone, PartialEq)]
pub struct Completed {
    /// The correction (the determined part times `scale`, plus a move
    /// along the free combinations).
    pub delta: SVector<f64, 10>,
    /// How much of the determined part is kept: 1 unless no move along
    /// the free combinations makes the link physical.
    pub scale: f64,
    /// Whether the free combinations were moved.
    pub moved: bool,
    /// Whether the correction is the fit's nearest physical body
    /// ([`nearest_physical`]) instead of a scaled-back one: chosen when it
    /// keeps more of what the data determine.
    pub projected: bool,
}

/// Relative tolerance of the moves' search on the pseudo-inertia's
/// smallest eigenvalue: a moved link is a body to this fraction of its
/// own pseudo-inertia.
const SLACK: f64 = 1e-7;

/// Relative tolerance on the pseudo-inertia's smallest eigenvalue.
const TOL: f64 = 1e-9;

/// The largest part of the determined change (relative, in the ten
/// parameters' norm) the nearest physical body may lose to be kept.
const NEAR: f64 = 0.5;

/// Makes `nominal + delta` physical by the least move (in the link's
/// units, `size.rs`; at most one unit more than `delta` itself) along the
/// combinations `free` (10 x f, the ones the data do not determine), or,
/// failing that,
/// by taking the fit's nearest physical body ([`nearest_physical`]) when
/// it keeps more of the determined change than scaling back and loses at
/// most half of it, else by scaling `delta` back (the largest scale in
/// [0, 1] found by bisection, 1e-3 apart). `None` when the nominal
/// parameters themselves are not physical.
///
/// ```
/// use dynamics_sim2real::inertial::{check, complete};
/// use nalgebra::{DMatrix, SVector};
/// // A 1 kg link whose fitted mass change of -1.2 kg is determined only
/// // together with its first moment along x.
/// let nominal = SVector::<f64, 10>::from([1.0, 0.1, 0.0, 0.0, 0.01, 0.0, 0.02, 0.0, 0.0, 0.02]);
/// let delta = SVector::<f64, 10>::from([-1.2, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
/// let free = DMatrix::<f64>::zeros(10, 0);
/// let c = complete(&nominal, &delta, &free).expect("a physical nominal link");
/// // No body has -0.2 kg: the nearest one keeps most of the change.
/// assert!(c.projected && check(&(nominal + c.delta), 1e-6).is_ok());
/// assert!(c.delta[0] < -0.5);
/// ```
pub fn complete(
    nominal: &SVector<f64, 10>,
    delta: &SVector<f64, 10>,
    free: &DMatrix<f64>,
) -> Option<Completed> {
    let tol = TOL * pseudo_inertia(nominal).norm().max(1e-300);
    if margin(nominal) < -tol {
        return None;
    }
    let full = nominal + delta;
    if margin(&full) >= -tol {
        return Some(Completed {
            delta: *delta,
            scale: 1.0,
            moved: false,
            projected: false,
        });
    }
    let units = units(nominal);
    let slack = SLACK * pseudo_inertia(nominal).norm();
    // (The move reaches the boundary to within the slack; the nearest body
    // to its end takes the rest, a change of the order of the slack.)
    // A move is at most as large as the link itself (one of its units)
    // plus the change the data ask for: the combinations they leave free
    // are filled in, not made into another body.
    let search = |p: &SVector<f64, 10>| {
        let asked = (p - nominal).component_div(&units).norm();
        nearest_move(p, free, &units, 1.0 + asked, slack).map(|mv| nearest_physical(&(p + mv)) - p)
    };
    if let Some(mv) = search(&full) {
        return Some(Completed {
            delta: delta + mv,
            scale: 1.0,
            moved: true,
            projected: false,
        });
    }
    // Scale the determined part back: the largest scale with a move.
    let (mut lo, mut hi) = (0.0, 1.0);
    let mut best = (SVector::<f64, 10>::zeros(), false);
    while hi - lo > 1e-3 {
        let s = 0.5 * (lo + hi);
        if let Some(mv) = search(&(nominal + delta * s)) {
            lo = s;
            best = (delta * s + mv, mv.amax() > 0.0);
        } else {
            hi = s;
        }
    }
    // The nearest physical body to the fit, when it keeps most of the
    // determined part (the scaled-back one keeps nothing at a scale of 0:
    // a fit off the boundary in a direction the scale cannot follow); a
    // fit far from every body (its nearest one would lose more than half of
    // what the data determine) stays scaled back.
    let near = nearest_physical(&full) - nominal;
    let lost = |d: &SVector<f64, 10>| -> f64 {
        let e = d - delta;
        let along_free = free.tr_mul(&e);
        (e.norm_squared() - along_free.norm_squared())
            .max(0.0)
            .sqrt()
    };
    let determined = lost(&SVector::zeros());
    if margin(&(nominal + near)) >= -tol
        && lost(&near) < lost(&best.0)
        && lost(&near) <= NEAR * determined
    {
        return Some(Completed {
            delta: near,
            scale: 1.0,
            moved: true,
            projected: true,
        });
    }
    Some(Completed {
        delta: best.0,
        scale: lo,
        moved: best.1,
        projected: false,
    })
}

/// The physical body nearest `pi` in the Frobenius norm of the
/// pseudo-inertia matrix: that matrix with its negative eigenvalues set to
/// zero, read back as ten parameters (`I = tr(S) 1 - S` from its upper
/// block `S`, `h` from its last column, `m` from its corner).
///
/// ```
/// use dynamics_sim2real::inertial::{margin, nearest_physical};
/// use nalgebra::SVector;
/// // A negative mass with a first moment: no body has it.
/// let pi = SVector::<f64, 10>::from([-0.2, 0.1, 0.0, 0.0, 0.01, 0.0, 0.02, 0.0, 0.0, 0.02]);
/// let near = nearest_physical(&pi);
/// assert!(margin(&pi) < 0.0 && margin(&near) > -1e-12);
/// ```
pub fn nearest_physical(pi: &SVector<f64, 10>) -> SVector<f64, 10> {
    let eig = pseudo_inertia(pi).symmetric_eigen();
    let clipped = eig.eigenvalues.map(|e| e.max(0.0));
    let j = eig.eigenvectors * Matrix4::from_diagonal(&clipped) * eig.eigenvectors.transpose();
    let s = j.fixed_view::<3, 3>(0, 0).into_owned();
    let i = Matrix3::identity() * s.trace() - s;
    super::parameters(j[(3, 3)], j.fixed_view::<3, 1>(0, 3).into_owned(), &i)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::inertial::check;
    use crate::inertial::tests::rod;

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
        let nominal =
            SVector::<f64, 10>::from([1.0, 0.3, 0.0, 0.0, 0.0, 0.0, 0.09, 0.0, 0.0, 0.09]);
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
        // What the data see is kept (to the search's slack).
        assert!((done.delta[2] - delta[2] * done.scale).abs() < 1e-5 * delta[2]);
    }

    /// A correction the data determine only in part: moved along the free
    /// combination it becomes physical, and its determined part is kept
    /// (what the data see is unchanged).
    #[test]
    fn a_free_combination_makes_the_correction_physical() {
        let nominal = rod();
        // Determined: I_yy - I_zz; the data ask for I_yy - I_zz = +0.2,
        // which with I_zz unchanged breaks the triangle inequality.
        let det = SVector::<f64, 10>::from([0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, -1.0])
            / 2f64.sqrt();
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
        let seen = det.dot(&delta);
        assert!((det.dot(&done.delta) - seen).abs() < 1e-5 * seen.abs());
    }

    /// A point mass on the x axis cannot lose inertia about x: a fit
    /// asking for that and for 0.5 kg more (every combination determined)
    /// is not physical at any scale but 0, which keeps nothing; the
    /// nearest physical body keeps the added mass and is a body.
    #[test]
    fn the_nearest_body_keeps_what_scaling_back_loses() {
        let nominal =
            SVector::<f64, 10>::from([1.0, 0.3, 0.0, 0.0, 0.0, 0.0, 0.09, 0.0, 0.0, 0.09]);
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
}
