//! Dissertation, sec. 3.3: the arm with an elastic grip (Figs. 3.19-3.21), the
//! four-coordinate model (phi, theta, u, y) of eq. 3.57 derived by `robot!`
//! from the transfer matrices (3.49) and the potential (3.56), under the
//! constant drives M10 = 0.2 N m, M20 = 0.5 N m, F0 = 7.5 N from rest.
//!
//! Two cases: the handle (push rod CD) massless (sec. 3.3.1, Fig. 3.20) and
//! with its mass m0 = 0.75 kg lumped into M by the equivalent-kinetic-energy
//! factor of eq. 3.58 (sec. 3.3.2, Fig. 3.21). The available text of eq. 3.58 keeps
//! only `km = 1/l3 int_0^l3 (eta_x / eta)^2 dx`; derived again: for a
//! uniform rod clamped at C with the load at its end D, the static
//! deflection shape is `eta_x / eta = (3 l3 x^2 - x^3) / (2 l3^3)`, so
//! `km = int_0^1 (s^2 (3 - s) / 2)^2 ds = 33/140` and the mass at D becomes
//! `m + 33/140 m0` (the rod's kinetic energy when it vibrates in that
//! shape). [`beam_frequencies`] is the full model of the rod the factor
//! stands for: Euler-Bernoulli beam elements with the rod's mass spread
//! along it and M at its end.

use std::f64::consts::PI;
use std::path::Path;

use dynamics_runtime::ode::{JointState, Tolerances};
use dynamics_runtime::{Robot, SimError, Trajectory};
use nalgebra::{DMatrix, SVector, Vector2, Vector4};

use super::support::{sample, trajectory_csv};
use super::{write, ScenarioError};
use crate::{ElasticGrip, ElasticGripParams};
use dynamics_cli::plot::{svg, Series};

/// Drives of sec. 3.3: M10, M20 (N m), F0 (N), nothing on y.
pub const DRIVES: [f64; 4] = [0.2, 0.5, 7.5, 0.0];
/// The drag coefficients beta1, beta2, beta3 of sec. 3.3 (none on y).
pub const DRAG: [f64; 4] = [0.01, 0.01, 0.05, 0.0];
/// Mass M at D, kg.
pub const LOAD: f64 = 1.0;
/// Mass m0 of the handle (push rod CD), kg (sec. 3.3.2).
pub const HANDLE_MASS: f64 = 0.75;
/// Equivalent-mass factor of eq. 3.58 for a cantilever with an end load.
pub const KM: f64 = 33.0 / 140.0;
/// Bending stiffness E I of the rod, N m^2.
pub const EI: f64 = 6.626e10 * 1.14197e-8;
/// Rod length l3, m.
pub const ROD: f64 = 0.5;
/// Simulated time, s.
pub const DURATION: f64 = 6.0;

/// A simulated motion with the work done on it.
#[derive(Debug, Clone)]
pub struct GripRun {
    /// The mass at D used, kg.
    pub mass: f64,
    /// The motion (`tau` = the drives).
    pub trajectory: Trajectory<4>,
    /// Work of the drives since t = 0, J.
    pub drive_work: Vec<f64>,
    /// Work of the drag since t = 0 (negative), J.
    pub drag_work: Vec<f64>,
}

/// Simulates the model with mass `mass` at D from rest at q = 0 over
/// `[0, t_end]`, sampled every `dt`, integrating the work of the drives and
/// of the drag beside the motion.
///
/// ```
/// use robots::scenarios::elastic_grip::{simulate, LOAD};
/// let run = simulate(LOAD, 0.1, 0.01).unwrap();
/// assert_eq!(run.trajectory.t.len(), 11);
/// ```
pub fn simulate(mass: f64, t_end: f64, dt: f64) -> Result<GripRun, ScenarioError> {
    if !(mass.is_finite() && mass > 0.0) {
        return Err(ScenarioError::Data(format!(
            "elastic grip: the mass at D must be positive, got {mass}"
        )));
    }
    if !(t_end.is_finite() && t_end > 0.0 && dt > 0.0 && dt <= t_end) {
        return Err(SimError::Span(format!("t_end = {t_end}, dt = {dt}")).into());
    }
    let grip = ElasticGrip::new(ElasticGripParams {
        m: mass,
        ..ElasticGripParams::default()
    });
    let u = Vector4::from(DRIVES);
    let drag = Vector4::from(DRAG);
    type State = (JointState<4>, Vector2<f64>);
    let mut rhs = |t: f64, x: &State| -> Result<State, SimError> {
        let qdd = grip
            .forward_dynamics(&x.0.q, &x.0.qd, &u)
            .map_err(|source| SimError::Dynamics { t, source })?;
        let qd = x.0.qd;
        let power = Vector2::new(u.dot(&qd), -qd.component_mul(&qd).dot(&drag));
        Ok((JointState { q: qd, qd: qdd }, power))
    };
    let tol = Tolerances {
        rtol: 1e-11,
        atol: 1e-13,
        ..Default::default()
    };
    let x0: State = (
        JointState {
            q: SVector::zeros(),
            qd: SVector::zeros(),
        },
        Vector2::zeros(),
    );
    let samples = sample(&mut rhs, 0.0, x0, t_end, dt, tol)?;
    let mut run = GripRun {
        mass,
        trajectory: Trajectory::default(),
        drive_work: Vec::new(),
        drag_work: Vec::new(),
    };
    for (t, (x, w)) in samples {
        let qdd = grip
            .forward_dynamics(&x.q, &x.qd, &u)
            .map_err(|source| SimError::Dynamics { t, source })?;
        let tr = &mut run.trajectory;
        tr.t.push(t);
        tr.q.push(x.q);
        tr.qd.push(x.qd);
        tr.qdd.push(qdd);
        tr.tau.push(u);
        run.drive_work.push(w[0]);
        run.drag_work.push(w[1]);
    }
    Ok(run)
}

/// The natural frequencies (Hz, ascending) of the full handle model: a
/// uniform Euler-Bernoulli rod (bending stiffness `ei`, mass `rod_mass`,
/// length `length`) clamped at one end, carrying `tip_mass` at the other,
/// cut into `elements` beam elements with consistent mass matrices.
///
/// ```
/// use robots::scenarios::elastic_grip::beam_frequencies;
/// // A light rod with a heavy end mass: sqrt(3 E I / l^3 / m) / (2 pi).
/// let f = beam_frequencies(1.0, 1e-6, 3.0, 1.0, 8).unwrap()[0];
/// assert!((f - 3.0 / (2.0 * std::f64::consts::PI)).abs() < 1e-6);
/// ```
pub fn beam_frequencies(
    tip_mass: f64,
    rod_mass: f64,
    ei: f64,
    length: f64,
    elements: usize,
) -> Result<Vec<f64>, ScenarioError> {
    let bad =
        |what: &str, v: f64| ScenarioError::Data(format!("beam: {what} must be positive, got {v}"));
    for (what, v) in [
        ("tip mass", tip_mass),
        ("rod mass", rod_mass),
        ("E I", ei),
        ("length", length),
    ] {
        if !(v.is_finite() && v > 0.0) {
            return Err(bad(what, v));
        }
    }
    if elements == 0 {
        return Err(bad("the number of elements", 0.0));
    }
    let h = length / elements as f64;
    let rho = rod_mass / length;
    // Element matrices for the dofs (w1, w1', w2, w2').
    let ke = [
        [12.0, 6.0 * h, -12.0, 6.0 * h],
        [6.0 * h, 4.0 * h * h, -6.0 * h, 2.0 * h * h],
        [-12.0, -6.0 * h, 12.0, -6.0 * h],
        [6.0 * h, 2.0 * h * h, -6.0 * h, 4.0 * h * h],
    ];
    let me = [
        [156.0, 22.0 * h, 54.0, -13.0 * h],
        [22.0 * h, 4.0 * h * h, 13.0 * h, -3.0 * h * h],
        [54.0, 13.0 * h, 156.0, -22.0 * h],
        [-13.0 * h, -3.0 * h * h, -22.0 * h, 4.0 * h * h],
    ];
    let n = 2 * (elements + 1);
    let mut k = DMatrix::<f64>::zeros(n, n);
    let mut m = DMatrix::<f64>::zeros(n, n);
    for e in 0..elements {
        for i in 0..4 {
            for j in 0..4 {
                k[(2 * e + i, 2 * e + j)] += ei / h.powi(3) * ke[i][j];
                m[(2 * e + i, 2 * e + j)] += rho * h / 420.0 * me[i][j];
            }
        }
    }
    m[(n - 2, n - 2)] += tip_mass;
    // Clamped at C: drop w and w' of the first node.
    let k = k.view((2, 2), (n - 2, n - 2)).into_owned();
    let m = m.view((2, 2), (n - 2, n - 2)).into_owned();
    let l = m
        .cholesky()
        .ok_or_else(|| ScenarioError::Data("beam: mass matrix not positive definite".into()))?
        .l();
    let li = l
        .try_inverse()
        .ok_or_else(|| ScenarioError::Data("beam: singular mass factor".into()))?;
    let c = &li * k * li.transpose();
    let c = (&c + c.transpose()) * 0.5;
    let mut f: Vec<f64> = c
        .symmetric_eigenvalues()
        .iter()
        .map(|w2| w2.max(0.0).sqrt() / (2.0 * PI))
        .collect();
    f.sort_by(f64::total_cmp);
    Ok(f)
}

/// The frequency (Hz) of M on the rod's bending stiffness alone.
pub fn equivalent_frequency(tip_mass: f64, rod_mass: f64) -> f64 {
    (3.0 * EI / ROD.powi(3) / (tip_mass + KM * rod_mass)).sqrt() / (2.0 * PI)
}

/// Mean frequency (Hz) of the fast oscillation of y: local maxima per second.
fn y_frequency(tr: &Trajectory<4>) -> f64 {
    let y: Vec<f64> = tr.q.iter().map(|q| q[3]).collect();
    let peaks: Vec<f64> = (1..y.len() - 1)
        .filter(|&k| y[k] > y[k - 1] && y[k] >= y[k + 1])
        .map(|k| tr.t[k])
        .collect();
    match (peaks.first(), peaks.last()) {
        (Some(a), Some(b)) if peaks.len() > 1 => (peaks.len() - 1) as f64 / (b - a),
        _ => 0.0,
    }
}

/// Runs both cases: CSV and the plots of Figs. 3.20-3.21.
pub fn run(dir: &Path) -> Result<Vec<String>, ScenarioError> {
    let dt = 1e-3;
    let cases = [
        ("massless handle", "massless", simulate(LOAD, DURATION, dt)?),
        (
            "handle m0 = 0.75 kg",
            "handle",
            simulate(LOAD + KM * HANDLE_MASS, DURATION, dt)?,
        ),
    ];
    let mut lines = vec![format!(
        "{DURATION} s from rest at q = 0 under M10 = 0.2 N m, M20 = 0.5 N m, F0 = 7.5 N; c4 = 3 E I / l3^3 = {:.0} N/m; km = 33/140 (eq. 3.58)",
        3.0 * EI / ROD.powi(3)
    )];
    for (label, file, run) in &cases {
        trajectory_csv::<ElasticGrip, 4>(&format!("elastic-grip-{file}"), &run.trajectory, dir)?;
        let tr = &run.trajectory;
        let params = ElasticGripParams {
            m: run.mass,
            ..ElasticGripParams::default()
        };
        let model = ElasticGrip::new(params);
        let e0 = model.total_energy(&tr.q[0], &tr.qd[0]);
        let balance = (0..tr.t.len())
            .map(|k| {
                (model.total_energy(&tr.q[k], &tr.qd[k])
                    - e0
                    - run.drive_work[k]
                    - run.drag_work[k])
                    .abs()
            })
            .fold(0.0, f64::max);
        let y_amp = tr.q.iter().map(|q| q[3].abs()).fold(0.0, f64::max);
        let u_range =
            tr.q.iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), q| {
                    (a.min(q[2]), b.max(q[2]))
                });
        let last = tr.t.len() - 1;
        lines.push(format!(
            "{label}: mass at D {:.4} kg; u in [{:.4}, {:.4}] m, |y| <= {:.3e} m, y oscillates at {:.2} Hz (M on the rod alone, arms held: {:.2} Hz; the arms recoil); phi(6 s) = {:.4}, theta(6 s) = {:.4} rad; |E - E0 - W| <= {balance:.1e} J",
            run.mass,
            u_range.0,
            u_range.1,
            y_amp,
            y_frequency(tr),
            equivalent_frequency(run.mass, 0.0),
            tr.q[last][0],
            tr.q[last][1],
        ));
    }
    let full = beam_frequencies(LOAD, HANDLE_MASS, EI, ROD, 40)?[0];
    let eq = equivalent_frequency(LOAD, HANDLE_MASS);
    lines.push(format!(
        "first bending mode with the handle's mass spread along the rod (40 beam elements): {full:.4} Hz; equivalent mass (3.58): {eq:.4} Hz ({:+.3} %)",
        100.0 * (eq - full) / full
    ));
    let plot = |file: &str, title: &str, ylabel: &str, j: usize| -> Result<(), ScenarioError> {
        let series: Vec<Series> = cases
            .iter()
            .map(|(label, _, run)| Series {
                name: label,
                points: run
                    .trajectory
                    .t
                    .iter()
                    .zip(&run.trajectory.q)
                    .map(|(t, q)| (*t, q[j]))
                    .collect(),
            })
            .collect();
        write(dir, file, &svg(title, "t [s]", ylabel, &series, false))
    };
    plot("phi.svg", "elastic grip: arm angle phi", "phi [rad]", 0)?;
    plot(
        "theta.svg",
        "elastic grip: arm angle theta",
        "theta [rad]",
        1,
    )?;
    plot(
        "u.svg",
        "elastic grip: push-rod shift u (Figs. 3.20-3.21)",
        "u [m]",
        2,
    )?;
    plot(
        "y.svg",
        "elastic grip: deflection y at D (Figs. 3.20-3.21)",
        "y [m]",
        3,
    )?;
    // The first 0.3 s of y, where the rod's vibration is visible.
    let zoom: Vec<Series> = cases
        .iter()
        .map(|(label, _, run)| Series {
            name: label,
            points: run
                .trajectory
                .t
                .iter()
                .zip(&run.trajectory.q)
                .take_while(|(t, _)| **t <= 0.3)
                .map(|(t, q)| (*t, q[3]))
                .collect(),
        })
        .collect();
    write(
        dir,
        "y-zoom.svg",
        &svg(
            "elastic grip: y, first 0.3 s",
            "t [s]",
            "y [m]",
            &zoom,
            false,
        ),
    )?;
    Ok(lines)
}
