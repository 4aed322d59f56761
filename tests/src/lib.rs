//! Test helpers shared by the integration tests: finite differences and
//! invariant checks that work for any generated robot.

use dynamics_runtime::Robot;
use nalgebra::{SMatrix, SVector};

/// dA/dt along qd by central differences: (A(q + h qd) - A(q - h qd)) / 2h.
///
/// ```
/// use dynamics_tests::mass_matrix_rate;
/// let r = robots::Arm3r::default();
/// let z = nalgebra::Vector3::zeros();
/// assert!(mass_matrix_rate(&r, &z, &z).norm() == 0.0);
/// ```
pub fn mass_matrix_rate<R: Robot<N>, const N: usize>(
    r: &R,
    q: &SVector<f64, N>,
    qd: &SVector<f64, N>,
) -> SMatrix<f64, N, N> {
    let h = 1e-6;
    (r.mass_matrix(&(q + qd * h)) - r.mass_matrix(&(q - qd * h))) / (2.0 * h)
}

/// dA/dq_k by central differences.
pub fn mass_matrix_partial<R: Robot<N>, const N: usize>(
    r: &R,
    q: &SVector<f64, N>,
    k: usize,
) -> SMatrix<f64, N, N> {
    let h = 1e-6;
    let mut e = SVector::<f64, N>::zeros();
    e[k] = h;
    (r.mass_matrix(&(q + e)) - r.mass_matrix(&(q - e))) / (2.0 * h)
}

/// -(Qqt1 + Qqt2) in Christoffel form, from finite differences of A only:
/// `sum_jk (dA_ij/dq_k - 1/2 dA_jk/dq_i) qd_j qd_k`.
pub fn christoffel_bias<R: Robot<N>, const N: usize>(
    r: &R,
    q: &SVector<f64, N>,
    qd: &SVector<f64, N>,
) -> SVector<f64, N> {
    let da: Vec<SMatrix<f64, N, N>> = (0..N).map(|k| mass_matrix_partial(r, q, k)).collect();
    SVector::<f64, N>::from_fn(|i, _| {
        let mut s = 0.0;
        for j in 0..N {
            for k in 0..N {
                s += (da[k][(i, j)] - 0.5 * da[i][(j, k)]) * qd[j] * qd[k];
            }
        }
        s
    })
}

/// Largest |entry| of a matrix, at least `floor`.
pub fn scale<const R: usize, const C: usize>(m: &SMatrix<f64, R, C>, floor: f64) -> f64 {
    m.iter().fold(floor, |a, x| a.max(x.abs()))
}
