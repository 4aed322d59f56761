//! The MAR with elastic drives and the inertial vibrations of its second
//! step of motion (vibration paper, eqs. 5-9).
//!
//! **The elastic-drive model.** Each joint's motor side and link side are
//! joined by Table 1's drive stiffness `k_i` and damping `c_i`: the drive
//! applies `U_i = k_i (q_m,i - q_i) + c_i (qd_m,i - qd_i)` to the rigid
//! links. The motor side is not a body of its own: as in the vibration paper, the
//! drives *impose the nominal motion*, `q_m(t) = q_n(t)` (q1 held still,
//! q2 and q3 from the inverse kinematics of the gripper path). The link then
//! lags behind its motor by the perturbation `x1 = q - q_n`, driven by the
//! inertial (and gravity) forces the drive must transmit.
//!
//! **The perturbation equation.** With the rigid residual
//! `F_r(q, qd, qdd) = A qdd - Q - Qqt1 - Qqt2`, the model reads
//! `F_r(q, qd, qdd) + k (q - q_n) + c (qd - qd_n) = 0`. Linearised about the
//! nominal motion (where `F_r(x_n) = tau_n`, the rigid inverse dynamics of
//! Fig. 5):
//!
//! ```text
//! A(x_n) x1dd + (D_r + c) x1d + (K_r + k) x1 = -tau_n(t)        (vibration paper, eq. 9)
//! ```
//!
//! `D_r + c` and `K_r + k` are exactly the perturbation Jacobians the macro
//! emits for [`Mar`] with its drive parameters set (the drive's spring and
//! damper enter `F` linearly), so [`perturbation_response`] integrates the
//! equation with `dU = -tau_n(t)`: the paper's `[Z]` at `x1 = 0`.

use dynamics_runtime::ode::{JointState, Tolerances};
use dynamics_runtime::{perturbation_response, simulate, Perturbed, Robot, Trajectory};
use nalgebra::Vector3;

use super::ik::{joints, JointMotion};
use super::path::{self, PathPoint};
use super::MarError;
use crate::mar::{DRIVE_DAMPING, DRIVE_STIFFNESS};
use crate::{Mar, MarParams};

/// Integration tolerances of both the linear and the nonlinear runs.
pub const TOL: Tolerances = Tolerances {
    rtol: 1e-10,
    atol: 1e-13,
    h_min: 1e-12,
    h_max: f64::INFINITY,
    max_steps: 10_000_000,
};

/// Stiffness and damping of the three drives.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Drives {
    /// N m/rad (q1, q2), N/m (q3).
    pub stiffness: [f64; 3],
    /// N m s/rad (q1, q2), N s/m (q3).
    pub damping: [f64; 3],
}

impl Drives {
    /// Table 1 of the vibration paper.
    pub const TABLE1: Drives = Drives {
        stiffness: DRIVE_STIFFNESS,
        damping: DRIVE_DAMPING,
    };

    /// Stiffness times `ks`, damping times `cs`.
    ///
    /// ```
    /// use robots::scenarios::mar::vibration::Drives;
    /// let soft = Drives::TABLE1.scaled(0.25, 0.5);
    /// assert_eq!(soft.stiffness[2], 0.25 * Drives::TABLE1.stiffness[2]);
    /// ```
    pub fn scaled(&self, ks: f64, cs: f64) -> Drives {
        Drives {
            stiffness: self.stiffness.map(|k| k * ks),
            damping: self.damping.map(|c| c * cs),
        }
    }

    /// The MAR with these drives and its motors at zero: its perturbation
    /// Jacobians hold the drive terms (`k` in K, `c` in D), which do not
    /// depend on where the motors are.
    pub fn model(&self) -> Mar {
        let [k1, k2, k3] = self.stiffness;
        let [d1, d2, d3] = self.damping;
        Mar::new(MarParams {
            k1,
            k2,
            k3,
            d1,
            d2,
            d3,
            q1_m: 0.0,
            q2_m: 0.0,
            q3_m: 0.0,
        })
    }

    /// The drives' effort on the links, motor side at (`q_m`, `qd_m`).
    ///
    /// ```
    /// use nalgebra::Vector3;
    /// use robots::scenarios::mar::vibration::Drives;
    /// let z = Vector3::zeros();
    /// let u = Drives::TABLE1.effort(&Vector3::new(0.0, 1e-3, 0.0), &z, &z, &z);
    /// assert!((u[1] - 110.066).abs() < 1e-9);
    /// ```
    pub fn effort(
        &self,
        q_m: &Vector3<f64>,
        qd_m: &Vector3<f64>,
        q: &Vector3<f64>,
        qd: &Vector3<f64>,
    ) -> Vector3<f64> {
        Vector3::from(self.stiffness).component_mul(&(q_m - q))
            + Vector3::from(self.damping).component_mul(&(qd_m - qd))
    }
}

/// The nominal motion of the second step: the gripper path and the joint
/// motion under it, q1 held at `q1`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plan {
    /// The fixed first coordinate, rad.
    pub q1: f64,
}

impl Plan {
    /// Checks that the whole path is reachable (every 1 ms) with q1 at `q1`.
    ///
    /// ```
    /// use robots::scenarios::mar::vibration::Plan;
    /// let plan = Plan::new(0.0).unwrap();
    /// // At rest the drives hold gravity only: q3's drive carries link 3.
    /// let tau = plan.driving(0.0);
    /// assert!(tau[2].abs() > 50.0 && tau[2].abs() < 15.0 * 9.81);
    /// ```
    pub fn new(q1: f64) -> Result<Plan, MarError> {
        let n = (path::cycle_time() / 1e-3).ceil() as usize;
        for i in 0..=n {
            joints(q1, &path::at(i as f64 * 1e-3))?;
        }
        Ok(Plan { q1 })
    }

    /// Length of the cycle, s.
    pub fn duration(&self) -> f64 {
        path::cycle_time()
    }

    /// The gripper and the joints at time `t`. The path was checked by
    /// [`Plan::new`]; were a point unreachable all the same, the joint values
    /// are NaN and the integrators stop with an error naming the time.
    pub fn at(&self, t: f64) -> (PathPoint, JointMotion) {
        let pt = path::at(t);
        let nan = Vector3::repeat(f64::NAN);
        let m = joints(self.q1, &pt).unwrap_or(JointMotion {
            q: nan,
            qd: nan,
            qdd: nan,
        });
        (pt, m)
    }

    /// The rigid inverse dynamics along the plan (the driving quantities of
    /// the nominal motion, vibration paper, Fig. 5): N m, N m, N.
    pub fn driving(&self, t: f64) -> Vector3<f64> {
        let m = self.at(t).1;
        Mar::default().inverse_dynamics(&m.q, &m.qd, &m.qdd)
    }
}

/// The linear response x1 of [`perturbation_response`] along the plan.
#[derive(Debug, Clone)]
pub struct Vibration {
    /// Nominal motion (integrated alongside) and x1, x1d, x1dd.
    pub response: Perturbed<3>,
    /// The gripper at the output times.
    pub path: Vec<PathPoint>,
    /// Rigid inverse dynamics tau_n at the output times (Fig. 5).
    pub driving: Vec<Vector3<f64>>,
    /// |J x1|: how far the links' perturbation moves the gripper, m (J the
    /// gripper's point Jacobian on the nominal motion).
    pub gripper: Vec<f64>,
}

/// The perturbation at rest at t = 0: the static deflection `K x1 =
/// -tau_n(0)` of the drives under gravity, so that the run starts without a
/// spurious transient.
///
/// ```
/// use robots::scenarios::mar::vibration::{static_deflection, Drives, Plan};
/// let plan = Plan::new(0.0).unwrap();
/// let x = static_deflection(&plan, &Drives::TABLE1).unwrap();
/// // About tau / k per joint.
/// let tau = plan.driving(0.0);
/// assert!((x[2] + tau[2] / Drives::TABLE1.stiffness[2]).abs() < 1e-6);
/// ```
pub fn static_deflection(plan: &Plan, drives: &Drives) -> Result<Vector3<f64>, MarError> {
    let m = plan.at(0.0).1;
    let pj = drives.model().perturbation_jacobians(&m.q, &m.qd, &m.qdd);
    pj.k.lu()
        .solve(&-plan.driving(0.0))
        .ok_or(MarError::SingularStiffness)
}

/// Integrates the vibration paper's eq. 9 over one cycle, output every `dt`.
///
/// ```
/// use robots::scenarios::mar::vibration::{inertial_vibration, peaks, Drives, Plan};
/// let v = inertial_vibration(&Plan::new(0.0).unwrap(), &Drives::TABLE1, 1e-2).unwrap();
/// // Links 2 and 3 lag their motors by well under a milliradian / millimetre.
/// let p = peaks(&v);
/// assert!(p[1].0 > 1e-5 && p[1].0 < 1e-3 && p[2].0 < 1e-3);
/// ```
pub fn inertial_vibration(plan: &Plan, drives: &Drives, dt: f64) -> Result<Vibration, MarError> {
    let model = drives.model();
    let start = plan.at(0.0).1;
    let x0 = JointState {
        q: static_deflection(plan, drives)?,
        qd: Vector3::zeros(),
    };
    let response = perturbation_response(
        &model,
        start.q,
        start.qd,
        // Feedforward of the model with drives: the nominal follows the plan
        // (any drift is pulled back by the drive springs).
        |t, _, _| {
            let m = plan.at(t).1;
            model.inverse_dynamics(&m.q, &m.qd, &m.qdd)
        },
        |t| -plan.driving(t),
        x0,
        plan.duration(),
        dt,
        TOL,
    )?;
    let path = response.nominal.t.iter().map(|t| path::at(*t)).collect();
    let driving = response
        .nominal
        .t
        .iter()
        .map(|t| plan.driving(*t))
        .collect();
    let g = Mar::point_index("gripper").unwrap_or(0);
    let gripper = response
        .nominal
        .q
        .iter()
        .zip(&response.dx)
        .map(|(q, dx)| {
            model
                .point_jacobian(g, q)
                .map_or(f64::NAN, |j| (j * dx).norm())
        })
        .collect();
    Ok(Vibration {
        response,
        path,
        driving,
        gripper,
    })
}

/// The nonlinear elastic-drive model: the rigid MAR under the drive efforts
/// with the motors on the plan, started at `q_n(0) + x0`. Its deviation
/// `q - q_n(t)` is what eq. 9 approximates.
///
/// ```
/// use robots::scenarios::mar::vibration::{nonlinear, Drives, Plan};
/// let plan = Plan::new(0.0).unwrap();
/// let tr = nonlinear(&plan, &Drives::TABLE1, nalgebra::Vector3::zeros(), 0.01).unwrap();
/// let last = tr.q.len() - 1;
/// assert!((tr.q[last] - plan.at(tr.t[last]).1.q).norm() < 1e-3);
/// ```
pub fn nonlinear(
    plan: &Plan,
    drives: &Drives,
    x0: Vector3<f64>,
    dt: f64,
) -> Result<Trajectory<3>, MarError> {
    let start = plan.at(0.0).1;
    Ok(simulate(
        &Mar::default(),
        start.q + x0,
        start.qd,
        |t, q, qd| {
            let m = plan.at(t).1;
            drives.effort(&m.q, &m.qd, q, qd)
        },
        plan.duration(),
        dt,
        TOL,
    )?)
}

/// Largest |x1| and |x1dd| per joint.
pub fn peaks(v: &Vibration) -> [(f64, f64); 3] {
    let mut out = [(0.0f64, 0.0f64); 3];
    for (d, a) in v.response.dx.iter().zip(&v.response.dxdd) {
        for j in 0..3 {
            out[j].0 = out[j].0.max(d[j].abs());
            out[j].1 = out[j].1.max(a[j].abs());
        }
    }
    out
}
