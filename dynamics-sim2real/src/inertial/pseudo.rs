//! The pseudo-inertia matrix of a link's ten parameters,
//! `J = [[1/2 tr(I) 1 - I, h], [h^T, m]]` (`I` about the frame origin,
//! `h = m c`): positive semi-definite exactly when the parameters are a
//! physical body (Wensing, Kim and Slotine, RA-L 2018).

use nalgebra::{Matrix3, Matrix4, SVector};

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
