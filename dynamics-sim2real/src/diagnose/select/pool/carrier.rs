//! Whether a payload leaves the body that carries the tip a physical body.
//!
//! A payload relative to the model is a point mass added to the last link
//! (the body that carries the tip, with everything welded to it). Negative,
//! it takes mass away: no more than the body has (the fit's bound), and
//! not from where the body has none to give. A negative point mass whose
//! centre of mass lies far from the body's leaves a first moment without
//! the mass to carry it (the KUKA's flange, 0.3 kg at its frame's origin,
//! less 0.296 kg placed 0.18 m out: 4 g with its centre of mass 13 m
//! away). The sum must be a physical body: its pseudo-inertia positive
//! semi-definite (Wensing, Kim and Slotine, RA-L 2018), the carrier's
//! rotational inertia kept as the model's, as the payload term keeps it.

use nalgebra::{Matrix3, SVector, Vector3};

use crate::diagnose::candidates::{payload_com, Candidate};
use crate::effects::Tip;
use crate::inertial::{point_mass, pseudo_inertia};
use dynamics_runtime::Robot;

/// The body that carries the tip: its nominal parameters (Pinocchio's
/// order, in its frame) and the tip's pose in its frame.
#[derive(Debug, Clone, PartialEq)]
pub struct Carrier {
    /// The body's nominal inertial parameters.
    pub nominal: SVector<f64, 10>,
    /// The tip frame's axes in the body's frame.
    pub rot: Matrix3<f64>,
    /// The tip's origin in the body's frame.
    pub at: Vector3<f64>,
}

impl Carrier {
    /// The carrier of `robot`'s tip: the last of its links with
    /// `nominal` parameters; `None` when the robot lists no link or does
    /// not place the tip or that link's frame.
    pub fn of<R: Robot<N>, const N: usize>(
        robot: &R,
        nominal: &[SVector<f64, 10>],
    ) -> Option<Carrier> {
        let nominal = *nominal.last()?;
        let link = R::frame_index(R::LINK_NAMES.last()?)?;
        let q = SVector::<f64, N>::zeros();
        let body = robot.frame_pose(link, &q)?;
        let rot_b = body.fixed_view::<3, 3>(0, 0).into_owned();
        let pos_b = body.fixed_view::<3, 1>(0, 3).into_owned();
        let tip = Tip::of::<R, N>();
        let (rot_t, pos_t) = match tip {
            Tip::Frame(i) => {
                let t = robot.frame_pose(i, &q)?;
                (
                    t.fixed_view::<3, 3>(0, 0).into_owned(),
                    t.fixed_view::<3, 1>(0, 3).into_owned(),
                )
            }
            Tip::Point(_) => (rot_b, tip.position(robot, &q)),
        };
        Some(Carrier {
            nominal,
            rot: rot_b.transpose() * rot_t,
            at: rot_b.transpose() * (pos_t - pos_b),
        })
    }

    /// The carrier's parameters with a point mass `mass` at `com` in the
    /// tip's frame.
    pub fn with_point_mass(&self, mass: f64, com: &Vector3<f64>) -> SVector<f64, 10> {
        self.nominal + point_mass(mass, &(self.at + self.rot * com))
    }

    /// Whether payload term `c` fitted `theta` (a mass, and for a payload
    /// with its centre of mass the mass times it, in the tip's frame) with
    /// standard deviations `std` leaves the carrier a physical body: its
    /// pseudo-inertia's least eigenvalue not below `-1e-9` of its largest
    /// with the centre of mass as fitted, or anywhere within two standard
    /// deviations of it on each axis (a grid of five points an axis: the
    /// data that leave a centre of mass loose do not say it is where no
    /// body could give its mass).
    pub fn carries(&self, c: Candidate, theta: &[f64], std: &[f64]) -> bool {
        let mass = theta.first().copied().unwrap_or(0.0);
        let com = match c {
            Candidate::PayloadCom(_) => Vector3::from(payload_com(theta)),
            Candidate::Payload => Vector3::zeros(),
            _ => return true,
        };
        if !mass.is_finite() || com.iter().any(|x| !x.is_finite()) {
            return false;
        }
        let body = |com: &Vector3<f64>| {
            let e = pseudo_inertia(&self.with_point_mass(mass, com)).symmetric_eigenvalues();
            e.min() >= -1e-9 * e.amax().max(1e-300)
        };
        if body(&com) {
            return true;
        }
        // The centre of mass's spread on each axis: its first moment's
        // over the mass.
        let spread = Vector3::from_fn(|i, _| match (c, std.get(i + 1)) {
            (Candidate::PayloadCom(_), Some(s)) if s.is_finite() && mass != 0.0 => {
                2.0 * s / mass.abs()
            }
            _ => 0.0,
        });
        if spread == Vector3::zeros() {
            return false;
        }
        const STEPS: [f64; 5] = [-1.0, -0.5, 0.0, 0.5, 1.0];
        STEPS.iter().any(|&a| {
            STEPS.iter().any(|&b| {
                STEPS
                    .iter()
                    .any(|&d| body(&(com + Vector3::new(a, b, d).component_mul(&spread))))
            })
        })
    }
}

/// Whether term `c` fitted `theta` (standard deviations `std`) is a
/// payload that leaves the body carrying the tip no physical body
/// ([`Carrier::carries`]; `carrier` unknown: none is said not to).
pub(in crate::diagnose) fn payload_leaves_no_body(
    carrier: Option<&Carrier>,
    c: Candidate,
    theta: &[f64],
    std: &[f64],
) -> bool {
    matches!(c, Candidate::Payload | Candidate::PayloadCom(_))
        && carrier.is_some_and(|k| !k.carries(c, theta, std))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A flange of 0.3 kg at its frame's origin (inertia 0.05 kg m^2 on
    /// each axis), the tip 0.1 m out along z: taking 0.2 kg away at the
    /// tip leaves a body, so does adding 2 kg 0.3 m out; taking 0.296 kg
    /// away 0.18 m beyond the tip leaves 4 g with its centre of mass metres
    /// away, no body, unless the data leave its centre of mass loose
    /// enough; nor does taking more than the flange has.
    #[test]
    fn a_payload_must_leave_the_tip_body_a_body() {
        let k = Carrier {
            nominal: SVector::from([0.3, 0.0, 0.0, 0.0, 0.05, 0.0, 0.05, 0.0, 0.0, 0.05]),
            rot: Matrix3::identity(),
            at: Vector3::new(0.0, 0.0, 0.1),
        };
        assert!(k.carries(Candidate::Payload, &[-0.2], &[]));
        assert!(k.carries(Candidate::PayloadCom([0.0; 3]), &[2.0, 0.0, 0.0, 0.6], &[]));
        let (m, c) = (-0.296, Vector3::new(0.014, -0.036, 0.18));
        let theta = [m, m * c.x, m * c.y, m * c.z];
        assert!(!k.carries(Candidate::PayloadCom([0.0; 3]), &theta, &[]));
        assert!(!k.carries(
            Candidate::PayloadCom([0.0; 3]),
            &theta,
            &[0.01, 1e-3, 1e-3, 1e-3]
        ));
        assert!(payload_leaves_no_body(
            Some(&k),
            Candidate::PayloadCom([0.0; 3]),
            &theta,
            &[]
        ));
        // 0.25 kg taken 0.1 m beyond the tip leaves none; with the centre
        // of mass's height loose by 5 cm (a first moment's spread of 12.5
        // g m), the mass could come from the tip's frame, 0.1 m from the
        // body's: a body.
        let theta = [-0.25, 0.0, 0.0, -0.025];
        assert!(!k.carries(
            Candidate::PayloadCom([0.0; 3]),
            &theta,
            &[0.01, 1e-4, 1e-4, 1e-3]
        ));
        assert!(k.carries(
            Candidate::PayloadCom([0.0; 3]),
            &theta,
            &[0.01, 1e-4, 1e-4, 0.0125]
        ));
        assert!(!payload_leaves_no_body(
            None,
            Candidate::PayloadCom([0.0; 3]),
            &theta,
            &[]
        ));
        assert!(!k.carries(Candidate::Payload, &[-0.4], &[0.05]));
        // Other terms are not payloads.
        assert!(!payload_leaves_no_body(
            Some(&k),
            Candidate::Viscous(0),
            &[-9.0],
            &[]
        ));
    }

    /// The carrier's frame and the tip's are found from the robot: a rod
    /// whose tip frame sits 1 m along it.
    #[test]
    fn the_tip_is_placed_in_its_carriers_frame() {
        dynamics_macros::robot! {
            robot Rod;
            gravity = [0.0, -9.81, 0.0];
            link base;
            link rod { mass = 1.5; com = [0.5, 0.0, 0.0]; inertia = [1e-4, 0.1, 0.1]; }
            link tool0;
            joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
            joint f = fixed(rod -> tool0) { transfer = [trans_x(1.0)]; }
        }
        let rod = Rod::default();
        let mut nominal = vec![SVector::<f64, 10>::zeros(); Rod::LINK_NAMES.len()];
        assert!(rod.inertial_parameters(&mut nominal).is_ok());
        let k = Carrier::of(&rod, &nominal).expect("a carrier");
        assert!(
            (k.at - Vector3::new(1.0, 0.0, 0.0)).norm() < 1e-12,
            "{}",
            k.at
        );
        assert!((k.nominal[0] - 1.5).abs() < 1e-12);
        // 1 kg at the tip of a 1.5 kg rod: a body.
        assert!(k.carries(Candidate::Payload, &[1.0], &[]));
    }
}
