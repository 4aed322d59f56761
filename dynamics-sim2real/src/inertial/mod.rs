//! A link's inertial parameters in Pinocchio's order (the order of
//! `Robot::inertial_regressor`): `pi = [m, m c_x, m c_y, m c_z, I_xx, I_xy,
//! I_yy, I_xz, I_yz, I_zz]`, in the link frame, `I` about the frame's
//! origin. Mass, centre of mass and inertia about the centre of mass from
//! them; a correction in words; the physical-consistency check (mass >= 0,
//! inertia about the centre of mass positive semi-definite, its principal
//! moments obeying the triangle inequalities).

use nalgebra::{Matrix3, SVector, Vector3};
use thiserror::Error;

mod barrier;
mod consistent;
mod metric;
mod pseudo;
mod size;

pub use consistent::{complete, nearest_physical, Completed};
pub use metric::{nearest_in_metric, Link as MetricLink};
pub use pseudo::{margin, pseudo_inertia};
pub use size::{units, LIGHTEST, SMALLEST};

/// Names of the ten parameters, in order.
pub const PARAMETER_NAMES: [&str; 10] = [
    "m", "m c_x", "m c_y", "m c_z", "I_xx", "I_xy", "I_yy", "I_xz", "I_yz", "I_zz",
];

/// The names of a change of the ten parameters, as a diagnosis report
/// writes a link correction (`d_` and [`PARAMETER_NAMES`] without the
/// products' signs: `d_m`, `d_mcx`, ...).
pub const PARAMETER_NAMES_DELTA: [&str; 10] = [
    "d_m", "d_mcx", "d_mcy", "d_mcz", "d_ixx", "d_ixy", "d_iyy", "d_ixz", "d_iyz", "d_izz",
];

/// Mass, centre of mass and inertia about it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MassProperties {
    /// Mass, kg.
    pub mass: f64,
    /// Centre of mass in the link frame, m (zero when the mass is zero).
    pub com: Vector3<f64>,
    /// Inertia about the centre of mass, link axes, kg m^2.
    pub inertia_com: Matrix3<f64>,
}

/// The inertia about the frame origin as a symmetric matrix.
fn origin_inertia(pi: &SVector<f64, 10>) -> Matrix3<f64> {
    Matrix3::new(
        pi[4], pi[5], pi[7], //
        pi[5], pi[6], pi[8], //
        pi[7], pi[8], pi[9],
    )
}

/// The ten parameters of a point mass `m` at `at` in the frame (`m` may be
/// negative: a point mass taken away).
pub(crate) fn point_mass(m: f64, at: &Vector3<f64>) -> SVector<f64, 10> {
    let i = (Matrix3::identity() * at.norm_squared() - at * at.transpose()) * m;
    parameters(m, at * m, &i)
}

/// The ten parameters of mass `m`, first moments `h` (`m c`) and the
/// inertia `i` about the frame origin: the inverse of [`origin_inertia`]
/// and the first four entries.
fn parameters(m: f64, h: Vector3<f64>, i: &Matrix3<f64>) -> SVector<f64, 10> {
    SVector::from([
        m,
        h.x,
        h.y,
        h.z,
        i[(0, 0)],
        i[(0, 1)],
        i[(1, 1)],
        i[(0, 2)],
        i[(1, 2)],
        i[(2, 2)],
    ])
}

/// Mass properties of `pi` (the centre of mass at the origin and the
/// inertia about the origin when the mass is not positive).
///
/// ```
/// use dynamics_sim2real::inertial::mass_properties;
/// // 2 kg at x = 0.5 m with no rotational inertia of its own.
/// let pi = nalgebra::SVector::<f64, 10>::from([2.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.5, 0.0, 0.0, 0.5]);
/// let p = mass_properties(&pi);
/// assert_eq!(p.com.x, 0.5);
/// assert!(p.inertia_com.norm() < 1e-15);
/// ```
pub fn mass_properties(pi: &SVector<f64, 10>) -> MassProperties {
    let mass = pi[0];
    let i = origin_inertia(pi);
    if mass <= 0.0 {
        return MassProperties {
            mass,
            com: Vector3::zeros(),
            inertia_com: i,
        };
    }
    let com = Vector3::new(pi[1], pi[2], pi[3]) / mass;
    let shift = (Matrix3::identity() * com.norm_squared() - com * com.transpose()) * mass;
    MassProperties {
        mass,
        com,
        inertia_com: i - shift,
    }
}

/// Why a parameter set is not a physical body.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum Inconsistency {
    /// A parameter is NaN or infinite.
    #[error("parameter {name} is not finite")]
    NotFinite {
        /// Its name ([`PARAMETER_NAMES`]).
        name: &'static str,
    },
    /// Negative mass.
    #[error("mass {mass:.6} kg is negative")]
    NegativeMass {
        /// The mass.
        mass: f64,
    },
    /// First moments without mass.
    #[error("first moments {first_moment:.3e} kg m without mass")]
    MomentWithoutMass {
        /// Their norm.
        first_moment: f64,
    },
    /// The inertia about the centre of mass has a negative principal moment.
    #[error(
        "the inertia about the centre of mass has a negative principal moment {moment:.3e} kg m^2"
    )]
    NotPositive {
        /// The smallest principal moment.
        moment: f64,
    },
    /// A principal moment exceeds the sum of the other two.
    #[error("principal moments {moments:?} kg m^2 break the triangle inequality")]
    Triangle {
        /// The principal moments.
        moments: [f64; 3],
    },
}

/// Checks that `pi` is a physical body: finite, mass >= 0, no first moment
/// without mass, inertia about the centre of mass positive semi-definite
/// and its principal moments within the triangle inequalities, each to a
/// relative tolerance `tol` of the largest principal moment.
///
/// ```
/// use dynamics_sim2real::inertial::{check, Inconsistency};
/// let rod = nalgebra::SVector::<f64, 10>::from([1.0, 0.5, 0.0, 0.0, 1e-4, 0.0, 0.33, 0.0, 0.0, 0.33]);
/// assert!(check(&rod, 1e-9).is_ok());
/// let mut flat = rod;
/// flat[4] = 1.0; // I_xx larger than I_yy + I_zz about the COM
/// assert!(matches!(check(&flat, 1e-9), Err(Inconsistency::Triangle { .. })));
/// ```
pub fn check(pi: &SVector<f64, 10>, tol: f64) -> Result<(), Inconsistency> {
    if let Some(k) = pi.iter().position(|v| !v.is_finite()) {
        return Err(Inconsistency::NotFinite {
            name: PARAMETER_NAMES[k],
        });
    }
    let p = mass_properties(pi);
    if p.mass < 0.0 {
        return Err(Inconsistency::NegativeMass { mass: p.mass });
    }
    let h = Vector3::new(pi[1], pi[2], pi[3]).norm();
    if p.mass == 0.0 && h > 0.0 {
        return Err(Inconsistency::MomentWithoutMass { first_moment: h });
    }
    let mut e: Vec<f64> = p
        .inertia_com
        .symmetric_eigenvalues()
        .iter()
        .copied()
        .collect();
    e.sort_by(f64::total_cmp);
    let scale = e[2].abs().max(1e-300);
    if e[0] < -tol * scale {
        return Err(Inconsistency::NotPositive { moment: e[0] });
    }
    if e[2] > e[0] + e[1] + tol * scale {
        return Err(Inconsistency::Triangle {
            moments: [e[0], e[1], e[2]],
        });
    }
    Ok(())
}

/// A correction `delta` to a link's nominal parameters `nominal`, in
/// words: the mass change, how far the centre of mass moves (mm), the
/// change of the inertia about the centre of mass (kg m^2; diagonal, and
/// the products where they change).
///
/// ```
/// use dynamics_sim2real::inertial::describe;
/// let nominal = nalgebra::SVector::<f64, 10>::from([2.0, 0.2, 0.0, 0.0, 0.01, 0.0, 0.03, 0.0, 0.0, 0.03]);
/// let mut delta = nalgebra::SVector::<f64, 10>::zeros();
/// delta[0] = 0.31;
/// let s = describe("panda_link5", &nominal, &delta);
/// assert!(s.starts_with("panda_link5: mass +0.310 kg, COM moved"), "{s}");
/// ```
pub fn describe(link: &str, nominal: &SVector<f64, 10>, delta: &SVector<f64, 10>) -> String {
    let before = mass_properties(nominal);
    let after = mass_properties(&(nominal + delta));
    let dm = after.mass - before.mass;
    let dc = (after.com - before.com) * 1e3;
    let di = after.inertia_com - before.inertia_com;
    let mut s = format!(
        "{link}: mass {dm:+.3} kg, COM moved ({:+.1}, {:+.1}, {:+.1}) mm ({:.1} mm), \
         inertia about the COM (xx, yy, zz) {:+.2e}, {:+.2e}, {:+.2e} kg m^2",
        dc.x,
        dc.y,
        dc.z,
        dc.norm(),
        di[(0, 0)],
        di[(1, 1)],
        di[(2, 2)]
    );
    let off = [di[(0, 1)], di[(0, 2)], di[(1, 2)]];
    let scale = di.diagonal().abs().max().max(1e-12);
    if off.iter().any(|v| v.abs() > 1e-3 * scale) {
        s += &format!(
            ", (xy, xz, yz) {:+.2e}, {:+.2e}, {:+.2e}",
            off[0], off[1], off[2]
        );
    }
    s
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A thin uniform rod along x (the tests' common link): 2 kg, centre of
    /// mass 0.3 m out, 0.4 m long; I about the origin by the parallel axis.
    pub(crate) fn rod() -> SVector<f64, 10> {
        let (m, c, l) = (2.0, 0.3, 0.4);
        let iyy = m * l * l / 12.0 + m * c * c;
        SVector::from([m, m * c, 0.0, 0.0, 1e-4, 0.0, iyy, 0.0, 0.0, iyy])
    }

    /// A box of mass m, sides a, b, c, centred at `c`, rotated by `r`.
    fn box_pi(m: f64, sides: [f64; 3], c: Vector3<f64>, r: Matrix3<f64>) -> SVector<f64, 10> {
        let [a, b, cc] = sides;
        let ic = Matrix3::from_diagonal(&Vector3::new(
            m * (b * b + cc * cc) / 12.0,
            m * (a * a + cc * cc) / 12.0,
            m * (a * a + b * b) / 12.0,
        ));
        let i = r * ic * r.transpose()
            + (Matrix3::identity() * c.norm_squared() - c * c.transpose()) * m;
        parameters(m, c * m, &i)
    }

    #[test]
    fn a_box_round_trips_and_is_physical() {
        let r = nalgebra::Rotation3::from_euler_angles(0.3, -0.2, 0.9).into_inner();
        let c = Vector3::new(0.1, -0.05, 0.2);
        let pi = box_pi(3.0, [0.1, 0.2, 0.4], c, r);
        let p = mass_properties(&pi);
        assert!((p.com - c).norm() < 1e-14);
        let mut e: Vec<f64> = p
            .inertia_com
            .symmetric_eigenvalues()
            .iter()
            .copied()
            .collect();
        e.sort_by(f64::total_cmp);
        let want = [3.0 * 0.05 / 12.0, 3.0 * 0.17 / 12.0, 3.0 * 0.2 / 12.0];
        for (a, b) in e.iter().zip(want) {
            assert!((a - b).abs() < 1e-12, "{e:?}");
        }
        assert!(check(&pi, 1e-9).is_ok());
    }

    #[test]
    fn unphysical_sets_are_named() {
        let pi = box_pi(1.0, [0.1, 0.1, 0.1], Vector3::zeros(), Matrix3::identity());
        let mut neg = pi;
        neg[0] = -0.1;
        assert!(matches!(
            check(&neg, 1e-9),
            Err(Inconsistency::NegativeMass { .. })
        ));
        let mut lopsided = pi;
        lopsided[4] = -0.01;
        assert!(matches!(
            check(&lopsided, 1e-9),
            Err(Inconsistency::NotPositive { .. })
        ));
        let mut nan = pi;
        nan[7] = f64::NAN;
        assert_eq!(
            check(&nan, 1e-9),
            Err(Inconsistency::NotFinite { name: "I_xz" })
        );
        // A point mass is physical (all principal moments zero about it).
        let point = box_pi(
            1.0,
            [0.0; 3],
            Vector3::new(0.3, 0.0, 0.0),
            Matrix3::identity(),
        );
        assert!(check(&point, 1e-9).is_ok());
    }

    #[test]
    fn a_moved_mass_is_described_in_millimetres() {
        let nominal = box_pi(
            2.0,
            [0.1, 0.1, 0.3],
            Vector3::new(0.0, 0.0, 0.1),
            Matrix3::identity(),
        );
        let moved = box_pi(
            2.0,
            [0.1, 0.1, 0.3],
            Vector3::new(0.003, 0.0, 0.1),
            Matrix3::identity(),
        );
        let s = describe("link 5", &nominal, &(moved - nominal));
        assert!(
            s.contains("mass +0.000 kg") && s.contains("(+3.0, +0.0, +0.0) mm"),
            "{s}"
        );
    }
}
