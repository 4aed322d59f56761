//! A link whose inertial parameters differ from the nominal model's by
//! `delta` (Pinocchio's order, see [`crate::inertial`]): the extra effort
//! the real robot needs is `Y_l(q, qd, qdd) delta`, affine in the
//! accelerations, so the plant's inertia gains the columns
//! `Y_l(q, 0, e_k) delta - Y_l(q, 0, 0) delta` and its forces lose
//! `Y_l(q, qd, 0) delta` (gravity and velocity terms).

use nalgebra::{SMatrix, SVector, Vector3};

use dynamics_runtime::Robot;

/// `(dA, df)`: what the changed link adds to the plant's inertia matrix
/// and to its forces (`A qdd = f + u`) at (q, qd).
pub(crate) fn terms<R: Robot<N>, const N: usize>(
    robot: &R,
    link: usize,
    delta: &[f64; 10],
    q: &SVector<f64, N>,
    qd: &SVector<f64, N>,
) -> (SMatrix<f64, N, N>, SVector<f64, N>) {
    let d = SVector::<f64, 10>::from(*delta);
    let mut y = vec![SMatrix::<f64, N, 10>::zeros(); R::LINK_NAMES.len()];
    let mut effort = |qd: &SVector<f64, N>, qdd: &SVector<f64, N>| -> SVector<f64, N> {
        match robot.inertial_regressor(q, qd, qdd, &mut y) {
            Ok(()) if link < y.len() => y[link] * d,
            _ => SVector::zeros(),
        }
    };
    let zero = SVector::<f64, N>::zeros();
    let at_rest = effort(&zero, &zero);
    let mut da = SMatrix::<f64, N, N>::zeros();
    for k in 0..N {
        let mut e = zero;
        e[k] = 1.0;
        let col = effort(&zero, &e) - at_rest;
        da.set_column(k, &col);
    }
    // Symmetric to rounding; made exactly so for the Cholesky factor.
    let da = (da + da.transpose()) * 0.5;
    (da, -effort(qd, &zero))
}

/// The changed link's share of the mechanical energy: kinetic
/// `1/2 qd^T dA qd` and potential `-gravity . (dm p + R dh)` (p, R the link
/// frame's world pose).
pub(crate) fn energy<R: Robot<N>, const N: usize>(
    robot: &R,
    link: usize,
    delta: &[f64; 10],
    q: &SVector<f64, N>,
    qd: &SVector<f64, N>,
) -> f64 {
    let (da, _) = terms(robot, link, delta, q, qd);
    let kinetic = 0.5 * qd.dot(&(da * qd));
    let pose = R::LINK_NAMES
        .get(link)
        .and_then(|name| R::frame_index(name))
        .and_then(|f| robot.frame_pose(f, q));
    let potential = match pose {
        Some(t) => {
            let r = t.fixed_view::<3, 3>(0, 0);
            let p = Vector3::new(t[(0, 3)], t[(1, 3)], t[(2, 3)]);
            let h = Vector3::new(delta[1], delta[2], delta[3]);
            -Vector3::from(R::GRAVITY).dot(&(p * delta[0] + r * h))
        }
        None => 0.0,
    };
    kinetic + potential
}

/// Checks that link `link` exists and that its nominal parameters plus
/// `delta` are a physical body: `Err(None)` for no such link,
/// `Err(Some(reason))` for an unphysical one.
pub(crate) fn physical<R: Robot<N>, const N: usize>(
    robot: &R,
    link: usize,
    delta: &[f64; 10],
) -> Result<(), Option<String>> {
    let mut pi = vec![SVector::<f64, 10>::zeros(); R::LINK_NAMES.len()];
    robot
        .inertial_parameters(&mut pi)
        .map_err(|e| Some(e.to_string()))?;
    let nominal = pi.get(link).ok_or(None)?;
    let changed = nominal + SVector::<f64, 10>::from(*delta);
    crate::inertial::check(&changed, 1e-9).map_err(|e| {
        Some(format!(
            "inertial_parameters: link {} would not be a physical body: {e}",
            R::LINK_NAMES[link]
        ))
    })
}
