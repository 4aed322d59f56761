//! A link's size: the units a change of its ten parameters is measured
//! in. Its mass for the mass, its mass times its size for the first
//! moments, its mass times its size squared for the inertia, the size
//! being the larger of its centre of mass's distance from the frame
//! origin and its radius of gyration about it. The prior toward a
//! nominal model (`diagnose::prior`) and the completion of a correction
//! into a physical body (`consistent.rs`) both measure in them.

use nalgebra::{SVector, Vector3};

/// The smallest mass (kg) a link's units are computed from: a link the
/// CAD model leaves massless may still carry something.
pub const LIGHTEST: f64 = 0.1;

/// The smallest size (m) a link's units are computed from.
pub const SMALLEST: f64 = 0.05;

/// The units of a change of each of the ten parameters (Pinocchio's
/// order) of a link whose nominal parameters are `nominal`.
///
/// ```
/// use dynamics_sim2real::inertial::units;
/// // 2 kg, centre of mass 0.3 m out on x, radius of gyration 0.28 m: size 0.3 m.
/// let rod = nalgebra::SVector::<f64, 10>::from([2.0, 0.6, 0.0, 0.0, 0.0, 0.0, 0.16, 0.0, 0.0, 0.16]);
/// let u = units(&rod);
/// assert!((u[0] - 2.0).abs() < 1e-12 && (u[1] - 0.6).abs() < 1e-12 && (u[4] - 0.18).abs() < 1e-12);
/// ```
pub fn units(nominal: &SVector<f64, 10>) -> SVector<f64, 10> {
    let m = nominal[0].max(LIGHTEST);
    let c = Vector3::new(nominal[1], nominal[2], nominal[3]) / m;
    // Radius of gyration about the frame origin: tr(I) = 2 m r^2.
    let trace = nominal[4] + nominal[6] + nominal[9];
    let r = (trace.max(0.0) / (2.0 * m)).sqrt();
    let size = c.norm().max(r).max(SMALLEST);
    let (sm, sh, si) = (m, m * size, m * size * size);
    SVector::from([sm, sh, sh, sh, si, si, si, si, si, si])
}
