//! The equations of the three contact modes of the clearance scenario and
//! the changes of coordinates between them (see [`super::clearance`]).
//!
//! Roll uses the dissertation's coordinates `(phi1, psi, u, phi2)` of
//! [`ClearanceArm`]; slide and flight the Cartesian pin coordinates
//! `(phi1, x, y, phi)` of [`ClearanceArmFree`], regular everywhere inside
//! the ring (the polar pair psi, u is singular at its centre, and in slide
//! the inertia of psi alone is only m2 u^2 ~ 1e-9 kg m^2).

use std::f64::consts::PI;

use dynamics_runtime::{DynamicsError, Robot, SimError};
use nalgebra::{Matrix2x4, Matrix4, Matrix4x2, SMatrix, SVector, Vector2, Vector4};

use super::clearance::{drives, BAUMGARTE, GAP, R1, R2};
use crate::{ClearanceArm, ClearanceArmFree};

fn singular(t: f64, what: &'static str) -> SimError {
    SimError::Dynamics {
        t,
        source: DynamicsError::Diverged {
            quantity: what,
            index: 0,
        },
    }
}

/// D^T: the motions (3.25) allows, `(phi1, Phi)` -> `(phi1, psi, u, phi2)`.
fn allowed() -> Matrix4x2<f64> {
    Matrix4x2::new(1.0, 0.0, 0.0, -R2 / R1, 0.0, 0.0, 0.0, 1.0)
}

/// Residuals of (3.25) in m: `u - (r1 - r2)`, `r1 psi + r2 phi2 - c0`.
pub fn residual(q: &Vector4<f64>, c0: f64) -> Vector2<f64> {
    Vector2::new(q[2] - GAP, R1 * q[1] + R2 * q[3] - c0)
}

/// Rolling contact (dissertation, eqs. 3.25, 3.37): accelerations and the reaction
/// `R = A qdd - Q - Qqt - U`; `R[2]` is the dissertation's Ru, `R[3] / r2` the
/// tangential force that keeps the pin from slipping.
///
/// ```
/// use robots::scenarios::clearance::{start, R1, R2};
/// use robots::scenarios::clearance_modes::roll;
/// let (q, qd) = start();
/// let (_, r) = roll(0.0, &q, &qd, R1 * q[1] + R2 * q[3]).unwrap();
/// assert!(r[2] < 0.0); // the ring pushes the pin inward
/// ```
pub fn roll(
    t: f64,
    q: &Vector4<f64>,
    qd: &Vector4<f64>,
    c0: f64,
) -> Result<(Vector4<f64>, Vector4<f64>), SimError> {
    let terms = ClearanceArm::default().motion_terms(q, qd);
    let (m1, m2) = drives(t);
    let f = terms.bias() + Vector4::new(m1, m2, 0.0, m2);
    let s = allowed();
    // (3.25) differentiated twice, the rolling row divided by r2.
    let j = Matrix2x4::new(0.0, 0.0, 1.0, 0.0, 0.0, R1 / R2, 0.0, 1.0);
    let mut res = residual(q, c0);
    res[1] /= R2;
    let target = -(j * qd) * (2.0 * BAUMGARTE) - res * (BAUMGARTE * BAUMGARTE);
    let sa = s.transpose() * terms.a;
    let mut m = Matrix4::zeros();
    for c in 0..4 {
        m[(0, c)] = sa[(0, c)];
        m[(1, c)] = sa[(1, c)];
        m[(2, c)] = j[(0, c)];
        m[(3, c)] = j[(1, c)];
    }
    let sf = s.transpose() * f;
    let rhs = Vector4::new(sf[0], sf[1], target[0], target[1]);
    let qdd = m
        .lu()
        .solve(&rhs)
        .filter(|v| v.iter().all(|x| x.is_finite()))
        .ok_or_else(|| singular(t, "qdd (rolling equations singular)"))?;
    Ok((qdd, terms.a * qdd - f))
}

/// Normal direction and slip-rate Jacobian at a Cartesian pin state.
fn contact_rows(q: &Vector4<f64>) -> (SVector<f64, 4>, SVector<f64, 4>, f64) {
    let u = q[1].hypot(q[2]);
    let jn = Vector4::new(0.0, q[1] / u, q[2] / u, 0.0);
    let jt = Vector4::new(0.0, -GAP * q[2] / (u * u), GAP * q[1] / (u * u), R2);
    (jn, jt, u)
}

/// Slip rate `r1 psi' + r2 phi2'` of the pin on the ring, m/s.
pub fn slip_rate(q: &Vector4<f64>, qd: &Vector4<f64>) -> f64 {
    contact_rows(q).1.dot(qd)
}

/// Sliding contact with Coulomb friction `mu` against slip direction
/// `sigma`: accelerations and the normal multiplier lambda (the force on the
/// pin along u, the dissertation's Ru; the ring pushes while it is negative).
pub fn slide(
    t: f64,
    q: &Vector4<f64>,
    qd: &Vector4<f64>,
    mu: f64,
    sigma: f64,
) -> Result<(Vector4<f64>, f64), SimError> {
    let terms = ClearanceArmFree::default().motion_terms(q, qd);
    let (m1, m2) = drives(t);
    let f = terms.bias() + Vector4::new(m1, 0.0, 0.0, m2);
    let (jn, jt, u) = contact_rows(q);
    let vn = jn.dot(qd);
    let v2 = qd[1] * qd[1] + qd[2] * qd[2];
    // u'' = jn . qdd + (|v|^2 - vn^2) / u; Baumgarte on u - (r1 - r2).
    let target = -(v2 - vn * vn) / u - 2.0 * BAUMGARTE * vn - BAUMGARTE * BAUMGARTE * (u - GAP);
    // A qdd = f + (jn + mu sigma jt) lambda: friction -mu N sigma, N = -lambda.
    let w = jn + jt * (mu * sigma);
    let mut m = SMatrix::<f64, 5, 5>::zeros();
    let mut rhs = SVector::<f64, 5>::zeros();
    for r in 0..4 {
        for c in 0..4 {
            m[(r, c)] = terms.a[(r, c)];
        }
        m[(r, 4)] = -w[r];
        m[(4, r)] = jn[r];
        rhs[r] = f[r];
    }
    rhs[4] = target;
    let x = m
        .lu()
        .solve(&rhs)
        .filter(|v| v.iter().all(|x| x.is_finite()))
        .ok_or_else(|| singular(t, "qdd (sliding equations singular)"))?;
    Ok((x.fixed_rows::<4>(0).into_owned(), x[4]))
}

/// Free flight inside the clearance.
pub fn flight(t: f64, q: &Vector4<f64>, qd: &Vector4<f64>) -> Result<Vector4<f64>, SimError> {
    let (m1, m2) = drives(t);
    ClearanceArmFree::default()
        .forward_dynamics(q, qd, &Vector4::new(m1, 0.0, 0.0, m2))
        .map_err(|source| SimError::Dynamics { t, source })
}

/// Plastic impact on the ring, frictionless: the normal velocity removed
/// in the metric of A; returns the new velocities and the energy lost.
pub fn impact(q: &Vector4<f64>, qd: &Vector4<f64>) -> Result<(Vector4<f64>, f64), SimError> {
    let a = ClearanceArmFree::default().mass_matrix(q);
    let (jn, _, _) = contact_rows(q);
    let ainv_jn = a
        .cholesky()
        .map(|c| c.solve(&jn))
        .ok_or_else(|| singular(f64::NAN, "mass matrix at impact"))?;
    let vn = jn.dot(qd);
    let m_inv = jn.dot(&ainv_jn);
    let after = qd - ainv_jn * (vn / m_inv);
    Ok((after, 0.5 * vn * vn / m_inv))
}

/// Seed coordinates -> Cartesian pin.
pub fn to_free(q: &Vector4<f64>, qd: &Vector4<f64>) -> (Vector4<f64>, Vector4<f64>) {
    let (s, c) = q[1].sin_cos();
    let u = q[2];
    (
        Vector4::new(q[0], u * c, u * s, q[1] + q[3]),
        Vector4::new(
            qd[0],
            qd[2] * c - u * qd[1] * s,
            qd[2] * s + u * qd[1] * c,
            qd[1] + qd[3],
        ),
    )
}

/// Cartesian pin -> the dissertation's coordinates, psi taken nearest `psi_near`.
pub fn to_seed(q: &Vector4<f64>, qd: &Vector4<f64>, psi_near: f64) -> (Vector4<f64>, Vector4<f64>) {
    let (x, y) = (q[1], q[2]);
    let u = x.hypot(y).max(1e-300);
    let a = y.atan2(x);
    let psi = a + 2.0 * PI * ((psi_near - a) / (2.0 * PI)).round();
    let ud = (x * qd[1] + y * qd[2]) / u;
    let psid = (x * qd[2] - y * qd[1]) / (u * u);
    (
        Vector4::new(q[0], psi, u, q[3] - psi),
        Vector4::new(qd[0], psid, ud, qd[3] - psid),
    )
}
