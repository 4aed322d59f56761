//! Dissertation, chapter 4: the 3R arm (payload 2 kg, b1..b3 = 1) draws a
//! circle with its tip under three controllers. The dissertation gives no circle
//! data; here: centre (0.25, 0.15) m, radius 0.08 m, tool (link 3) kept
//! horizontal, one turn in 4 s with a rest-to-rest angle profile
//! `theta(t) = 2 pi (t/T - sin(2 pi t/T) / (2 pi))`, and the arm starting
//! 0.05 rad off the reference in every joint.

use std::f64::consts::PI;
use std::path::Path;

use dynamics_runtime::control::{ComputedTorque, Controller, PdGravity, Reference, SlidingMode};
use dynamics_runtime::ode::Tolerances;
use dynamics_runtime::{simulate, Robot};
use nalgebra::{Vector2, Vector3};

use super::{outputs_csv, write, ScenarioError};
use dynamics_cli::plot::{svg, Series};

const CENTRE: (f64, f64) = (0.25, 0.15);
const RADIUS: f64 = 0.08;
const PERIOD: f64 = 4.0;
const L: [f64; 3] = [0.2, 0.2, 0.1];

/// The tip target at time t.
fn target(t: f64) -> Vector2<f64> {
    let s = (t / PERIOD).clamp(0.0, 1.0);
    let th = 2.0 * PI * (s - (2.0 * PI * s).sin() / (2.0 * PI));
    Vector2::new(CENTRE.0 + RADIUS * th.cos(), CENTRE.1 + RADIUS * th.sin())
}

/// Planar 3R inverse kinematics with link 3 horizontal (elbow up).
fn ik(p: Vector2<f64>) -> Vector3<f64> {
    let w = p - Vector2::new(L[2], 0.0);
    let c2 =
        ((w.norm_squared() - L[0] * L[0] - L[1] * L[1]) / (2.0 * L[0] * L[1])).clamp(-1.0, 1.0);
    let q2 = c2.acos();
    let q1 = w.y.atan2(w.x) - (L[1] * q2.sin()).atan2(L[0] + L[1] * q2.cos());
    Vector3::new(q1, q2, -q1 - q2)
}

fn reference(t: f64) -> Reference<3> {
    let h = 1e-4;
    let (qm, q0, qp) = (ik(target(t - h)), ik(target(t)), ik(target(t + h)));
    Reference {
        q: q0,
        qd: (qp - qm) / (2.0 * h),
        qdd: (qp - q0 * 2.0 + qm) / (h * h),
    }
}

/// Runs the three controllers.
pub fn run(dir: &Path) -> Result<Vec<String>, ScenarioError> {
    let plant = crate::Arm3r::new(crate::Arm3rParams {
        m: 2.0,
        b1: 1.0,
        b2: 1.0,
        b3: 1.0,
    });
    let model = plant;
    let tol = Tolerances {
        rtol: 1e-9,
        atol: 1e-11,
        ..Default::default()
    };
    let q0 = reference(0.0).q + Vector3::repeat(0.05);
    let mut pd = PdGravity {
        model: &model,
        kp: Vector3::repeat(400.0),
        kd: Vector3::repeat(40.0),
    };
    let mut ct = ComputedTorque {
        model: &model,
        kp: Vector3::repeat(100.0),
        kd: Vector3::repeat(20.0),
    };
    let mut smc = SlidingMode {
        model: &model,
        lambda: Vector3::repeat(20.0),
        k: Vector3::repeat(5.0),
        phi: 0.05,
    };
    let controllers: [(&str, &mut dyn Controller<3>); 3] = [
        ("pd-gravity", &mut pd),
        ("computed-torque", &mut ct),
        ("sliding-mode", &mut smc),
    ];
    let circle: Vec<(f64, f64)> = (0..=200)
        .map(|k| {
            let a = 2.0 * PI * k as f64 / 200.0;
            (CENTRE.0 + RADIUS * a.cos(), CENTRE.1 + RADIUS * a.sin())
        })
        .collect();
    let mut paths = vec![Series {
        name: "reference",
        points: circle,
    }];
    let mut lines = vec![format!(
        "circle centre ({}, {}) m, radius {} m, one turn in {} s; start 0.05 rad off in every joint",
        CENTRE.0, CENTRE.1, RADIUS, PERIOD
    )];
    for (name, c) in controllers {
        let tr = simulate(
            &plant,
            q0,
            Vector3::zeros(),
            |t, q, qd| c.effort(q, qd, &reference(t)),
            PERIOD,
            0.005,
            tol,
        )?;
        outputs_csv::<crate::Arm3r>(&format!("arm3r-circle-{name}"), &tr, dir)?;
        let tip: Vec<(f64, f64)> =
            tr.q.iter()
                .filter_map(|q| plant.point_position(0, q))
                .map(|p| (p[0], p[1]))
                .collect();
        let errs: Vec<f64> =
            tr.t.iter()
                .zip(&tip)
                .map(|(t, p)| (Vector2::new(p.0, p.1) - target(*t)).norm())
                .collect();
        let settled: Vec<f64> =
            tr.t.iter()
                .zip(&errs)
                .filter(|(t, _)| **t >= 1.0)
                .map(|(_, e)| *e)
                .collect();
        let rms = (settled.iter().map(|e| e * e).sum::<f64>() / settled.len().max(1) as f64).sqrt();
        let max = settled.iter().fold(0.0f64, |m, e| m.max(*e));
        let peak_tau = tr.tau.iter().fold(0.0f64, |m, t| m.max(t.abs().max()));
        lines.push(format!(
            "{name:16} tip error after 1 s: RMS {rms:.2e} m, max {max:.2e} m; peak |tau| {peak_tau:.2} N m"
        ));
        let tau: Vec<Series> = (0..3)
            .map(|j| Series {
                name: crate::Arm3r::JOINT_NAMES[j],
                points: tr.t.iter().zip(&tr.tau).map(|(t, v)| (*t, v[j])).collect(),
            })
            .collect();
        write(
            dir,
            &format!("tau-{name}.svg"),
            &svg(
                &format!("arm3r circle, {name}: torques"),
                "t [s]",
                "tau [N m]",
                &tau,
                false,
            ),
        )?;
        paths.push(Series { name, points: tip });
    }
    write(
        dir,
        "path.svg",
        &svg(
            "arm3r circle: tip paths over the reference",
            "x [m]",
            "y [m]",
            &paths,
            true,
        ),
    )?;
    Ok(lines)
}
