//! Dissertation, sec. 3.4: the piston's end point C follows the line KL
//! (eq. 3.89) while the environment resists its motion with the
//! velocity-dependent force `F = -mu |v|^(alpha-1) v` (mu = 0.05 N s/m,
//! alpha = 2), under the constant drives M1 = 7.5 N m, M2 = 0.5 N m,
//! F = 100 N from rest at q = 0 (the point L).
//!
//! The motion equations (3.88), `D A qdd = D (Q + Qqt + Qc)` with the
//! second derivative of the program, are those of `simulate_program`: the
//! ideal control force `J^T lambda` keeps C on KL and Baumgarte's terms
//! hold the drift down; `Qc = J_C^T F` is the resistance through the
//! Jacobian of C (the effects library's `environment_resistance` at the
//! arm's tip). The orbit error is the distance of C from KL,
//! `|f| / sqrt(1 + a^2)`.

use std::path::Path;

use dynamics_runtime::ode::Tolerances;
use dynamics_runtime::{simulate_program, Baumgarte, Constrained, ProgramMotion};
use dynamics_sim2real::effects::{Effect, Tip};
use nalgebra::Vector3;

use super::{outputs, write, ScenarioError};
use crate::Piston;
use dynamics_cli::plot::{svg, Series};

/// Resistance coefficient mu of sec. 3.4, N s/m (alpha = 2).
pub const MU: f64 = 0.05;
/// Velocity exponent alpha of sec. 3.4.
pub const ALPHA: f64 = 2.0;
/// Drives M1, M2 (N m) and F (N) of sec. 3.4.
pub const DRIVES: [f64; 3] = [7.5, 0.5, 100.0];
/// Slope a of the line KL (chosen; see [`crate::Piston`]).
pub const SLOPE: f64 = 2.0;
/// Simulated time, s.
pub const DURATION: f64 = 3.0;

/// A program motion against the environment.
#[derive(Debug, Clone)]
pub struct EnvironmentRun {
    /// The constrained motion; `trajectory.tau` holds drives + resistance +
    /// control forces.
    pub motion: ProgramMotion<3, 1>,
    /// The resistance force at C (world frame) at each sample.
    pub force: Vec<Vector3<f64>>,
    /// Its generalized force `Qc = J_C^T F` at each sample.
    pub qc: Vec<Vector3<f64>>,
    /// Distance of C from KL at each sample, m.
    pub orbit_error: Vec<f64>,
}

impl EnvironmentRun {
    /// Largest distance of C from KL, m.
    pub fn max_orbit_error(&self) -> f64 {
        self.orbit_error.iter().fold(0.0, |m, e| m.max(*e))
    }
}

/// Simulates sec. 3.4 with resistance `mu`, `alpha` over `[0, t_end]`,
/// sampled every `dt`.
///
/// ```
/// let run = robots::scenarios::environment::simulate(0.05, 2.0, 0.2, 0.01).unwrap();
/// assert!(run.max_orbit_error() < 1e-7);
/// ```
pub fn simulate(mu: f64, alpha: f64, t_end: f64, dt: f64) -> Result<EnvironmentRun, ScenarioError> {
    let tol = Tolerances {
        rtol: 1e-11,
        atol: 1e-12,
        ..Default::default()
    };
    simulate_with(mu, alpha, t_end, dt, tol)
}

/// [`simulate`] with the integrator's tolerances given.
pub fn simulate_with(
    mu: f64,
    alpha: f64,
    t_end: f64,
    dt: f64,
    tol: Tolerances,
) -> Result<EnvironmentRun, ScenarioError> {
    let arm = Piston::default();
    let env = Effect::EnvironmentResistance { mu, alpha };
    env.validate().map_err(ScenarioError::Data)?;
    let tip = Tip::of::<Piston, 3>();
    let drives = Vector3::from(DRIVES);
    let resistance = |q: &Vector3<f64>, qd: &Vector3<f64>| {
        let (_, jac) = tip.position_jacobian(&arm, q);
        let f = env.resistance(&(jac * qd));
        (f, jac.transpose() * f)
    };
    let motion = simulate_program(
        &arm,
        Vector3::zeros(),
        Vector3::zeros(),
        |_, q, qd| drives + resistance(q, qd).1,
        t_end,
        dt,
        tol,
        Baumgarte::default(),
    )?;
    let scale = (1.0 + SLOPE * SLOPE).sqrt();
    let mut run = EnvironmentRun {
        force: Vec::new(),
        qc: Vec::new(),
        orbit_error: Vec::new(),
        motion,
    };
    for (k, q) in run.motion.trajectory.q.iter().enumerate() {
        let (f, qc) = resistance(q, &run.motion.trajectory.qd[k]);
        run.force.push(f);
        run.qc.push(qc);
        let t = run.motion.trajectory.t[k];
        run.orbit_error
            .push(arm.constraint_residual(t, q)[0].abs() / scale);
    }
    Ok(run)
}

/// Runs the scenario: with and without the environment, CSV and plots.
pub fn run(dir: &Path) -> Result<Vec<String>, ScenarioError> {
    let dt = 1e-3;
    let with = simulate(MU, ALPHA, DURATION, dt)?;
    let without = simulate(0.0, ALPHA, DURATION, dt)?;
    // Matlab's ode45 default tolerances (the dissertation computed with Matlab).
    let loose = Tolerances {
        rtol: 1e-3,
        atol: 1e-6,
        ..Default::default()
    };
    let coarse = simulate_with(MU, ALPHA, DURATION, dt, loose)?;
    let arm = Piston::default();
    let tr = &with.motion.trajectory;
    outputs(&arm, "environment", tr, 0, dir)?;
    let mut csv = String::from("t,x_c,y_c,vx_c,vy_c,fx,fy,resistance_power,orbit_error,lambda\n");
    let tip = Tip::of::<Piston, 3>();
    let mut work = 0.0;
    let mut last_power = 0.0;
    for k in 0..tr.t.len() {
        let (p, jac) = tip.position_jacobian(&arm, &tr.q[k]);
        let v = jac * tr.qd[k];
        let f = with.force[k];
        let power = f.dot(&v);
        if k > 0 {
            work += 0.5 * (power + last_power) * (tr.t[k] - tr.t[k - 1]);
        }
        last_power = power;
        csv.push_str(&format!(
            "{},{},{},{},{},{},{},{},{},{}\n",
            tr.t[k],
            p[0],
            p[1],
            v[0],
            v[1],
            f[0],
            f[1],
            power,
            with.orbit_error[k],
            with.motion.lambda[k][0]
        ));
    }
    write(dir, "environment-tip.csv", &csv)?;
    let series = |name: &'static str, f: &dyn Fn(usize) -> f64| Series {
        name,
        points: tr.t.iter().enumerate().map(|(k, t)| (*t, f(k))).collect(),
    };
    write(
        dir,
        "orbit-error.svg",
        &svg(
            "environment: distance of C from KL",
            "t [s]",
            "error [m]",
            &[series("orbit error", &|k| with.orbit_error[k])],
            false,
        ),
    )?;
    write(
        dir,
        "resistance.svg",
        &svg(
            "environment: resistance at C, F = -mu |v|^(alpha-1) v",
            "t [s]",
            "F [N]",
            &[
                series("Fx", &|k| with.force[k][0]),
                series("Fy", &|k| with.force[k][1]),
            ],
            false,
        ),
    )?;
    let piston: Vec<Series> = vec![
        series("q3, mu = 0.05", &|k| tr.q[k][2]),
        series("q3, mu = 0", &|k| without.motion.trajectory.q[k][2]),
    ];
    write(
        dir,
        "piston.svg",
        &svg(
            "environment: piston stroke with and without resistance",
            "t [s]",
            "q3 [m]",
            &piston,
            false,
        ),
    )?;
    let gap =
        tr.q.iter()
            .zip(&without.motion.trajectory.q)
            .map(|(a, b)| (tip.position(&arm, a) - tip.position(&arm, b)).norm())
            .fold(0.0, f64::max);
    let last = tr.t.len() - 1;
    Ok(vec![
        format!(
            "{DURATION} s from q = 0 (C at L) with M1 = {} N m, M2 = {} N m, F = {} N; spring k = 650 N/m, l0 = 0.1 m; KL slope a = {SLOPE}",
            DRIVES[0], DRIVES[1], DRIVES[2]
        ),
        format!(
            "orbit error (largest distance of C from KL): {:.2e} m (seed: about 1e-7)",
            with.max_orbit_error()
        ),
        format!(
            "with ode45's default tolerances (rtol 1e-3, atol 1e-6) and the same drift control: {:.2e} m",
            coarse.max_orbit_error()
        ),
        format!("work of the resistance mu = {MU}, alpha = {ALPHA}: {work:.4} J"),
        format!(
            "q(3 s) = [{:.4}, {:.4}, {:.4}]; C moves up to {gap:.4} m apart from the motion without resistance",
            tr.q[last][0], tr.q[last][1], tr.q[last][2]
        ),
    ])
}
