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
//! [`complete`] moves the correction along the free combinations until
//! `J` is positive semi-definite (a compass search on its smallest
//! eigenvalue, which is concave in the parameters); when no such move
//! exists, the fit's nearest physical body is taken if it keeps most of
//! the determined part, else the determined part is scaled back, and the
//! scale said.
//!
//! Here: the pseudo-inertia and [`complete`]; its compass search in
//! `search.rs`.

mod search;

use nalgebra::{DMatrix, Matrix3, Matrix4, SVector};

use search::search;

/// The pseudo-inertia matrix of `pi` (Pinocchio's order).
pub fn pseudo_inertia(pi: &SVector<f64, 10>) -> Matrix4<f64> {
    let i = Matrix3::new(
        pi[4], pi[5], pi[7], //
        pi[5], pi[6], pi[8], //
        pi[7], pi[8], pi[9],
    );
    let s = Matrix3::identity() * (0.5 * i.trace()) - i;
    let mut j = Matrix4::zeros();
    j.fixed_view_mut::<3, 3>(0, 0).copy_from(&s);
    for r in 0..3 {
        j[(r, 3)] = pi[1 + r];
        j[(3, r)] = pi[1 + r];
    }
    j[(3, 3)] = pi[0];
    j
}

/// The smallest eigenvalue of the pseudo-inertia matrix: >= 0 for a
/// physical body.
pub fn margin(pi: &SVector<f64, 10>) -> f64 {
    pseudo_inertia(pi).symmetric_eigenvalues().min()
}

/// The sum of the pseudo-inertia's negative eigenvalues: 0 for a physical
/// body. What the search raises: unlike the smallest eigenvalue alone it
/// moves when one of two negative eigenvalues does, and it does not stall
/// where several sit at zero (a point mass, a flat body).
fn negativity(pi: &SVector<f64, 10>) -> f64 {
    pseudo_inertia(pi)
        .symmetric_eigenvalues()
        .iter()
        .map(|e| e.min(0.0))
        .sum()
}

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

/// Relative tolerance on the pseudo-inertia's smallest eigenvalue.
const TOL: f64 = 1e-9;

/// The largest part of the determined change (relative, in the ten
/// parameters' norm) the nearest physical body may lose to be kept.
const NEAR: f64 = 0.5;

/// Evaluations of the pseudo-inertia's eigenvalues one [`complete`] may
/// spend in its searches (about half a second): the compass search creeps
/// along a curved boundary (a point mass needs some 1e5), and without a
/// budget one link of a real log took several seconds. A search that runs
/// out of it stops where it is, and `complete` goes on to scaling back and
/// the nearest body as when no move is found.
const BUDGET: usize = 400_000;

/// Makes `nominal + delta` physical by moving along the combinations
/// `free` (10 x f, the ones the data do not determine), or, failing that,
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
    let mut budget = BUDGET;
    let (mv, m) = search(&full, free, -tol, &mut budget);
    if m >= -tol {
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
        let p = nominal + delta * s;
        let (mv, m) = search(&p, free, -tol, &mut budget);
        if m >= -tol {
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
mod tests;
