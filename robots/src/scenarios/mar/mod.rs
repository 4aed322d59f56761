//! Vibration paper: inertial vibrations of the MAR manipulator's links during the
//! second step of motion (q1 still, q2 and q3 moving the gripper along the
//! flat path of Table 2). Pipeline, one file a step:
//! [`path`] (gripper path and motion law, Figs. 2-3) -> [`ik`] (q2, q3,
//! Fig. 4) -> [`vibration`] (inverse dynamics, Fig. 5; elastic drives and
//! the perturbation equation, Figs. 7-8) -> this module (CSV, SVG, summary).
//!
//! q1 is held at 0: links 2 and 3 move in the vertical plane, under the
//! full weight. There the first joint's perturbation decouples (its
//! forcing and couplings are proportional to sin q1 or q1d) and stays zero.

pub mod ik;
pub mod path;
pub mod vibration;

use std::fmt::Write as _;
use std::path::Path;

use dynamics_runtime::{Robot, SimError};
use nalgebra::Vector3;
use thiserror::Error;

use super::{outputs_csv, write, ScenarioError};
use crate::Mar;
use dynamics_cli::plot::{svg, Series};
use vibration::{inertial_vibration, nonlinear, peaks, Drives, Plan, Vibration};

/// Why the MAR analysis failed.
#[derive(Debug, Error)]
pub enum MarError {
    /// The path leaves the workspace.
    #[error(transparent)]
    Ik(#[from] ik::IkError),
    /// An integration stopped.
    #[error(transparent)]
    Sim(#[from] SimError),
    /// The perturbation stiffness at rest is singular (no static deflection).
    #[error("the stiffness matrix of the perturbation equation at rest is singular")]
    SingularStiffness,
}

/// Output step, s.
const DT: f64 = 1e-3;

/// `dynamics scenario mar-vibration`: CSVs, the figures as SVG, and the
/// summary with the peak perturbation and acceleration per link, written
/// into the existing folder `dir`.
///
/// ```
/// let dir = std::env::temp_dir().join("dynamics-doc-mar-vibration");
/// std::fs::create_dir_all(&dir).unwrap();
/// let lines = robots::scenarios::mar::run(&dir).unwrap();
/// assert!(dir.join("fig7-link2.svg").exists() && dir.join("perturbation.csv").exists());
/// assert!(lines.iter().any(|l| l.starts_with("2     q2")));
/// ```
pub fn run(dir: &Path) -> Result<Vec<String>, ScenarioError> {
    let plan = Plan::new(0.0)?;
    let v = inertial_vibration(&plan, &Drives::TABLE1, DT)?;
    let x0 = v.response.dx[0];
    let nl = nonlinear(&plan, &Drives::TABLE1, x0, DT)?;
    outputs_csv::<Mar>("mar-vibration", &v.response.nominal, dir)?;
    write(dir, "perturbation.csv", &perturbation_csv(&v))?;
    figures(&v, dir)?;

    let mut lines = vec![
        format!(
            "second step of motion, q1 = 0; path Q = {}, L = {}, K = {}, R = {} m, {:.3} m in {:.3} s (stops at the 4 segment joints)",
            path::Q, path::L, path::K, path::R, path::length(), plan.duration()
        ),
        format!(
            "drives (Table 1): k = {:?}, c = {:?}; motors on the nominal motion",
            Drives::TABLE1.stiffness, Drives::TABLE1.damping
        ),
        format!(
            "static deflection at rest: x1 = [{:.3e}, {:.3e}, {:.3e}]",
            x0[0], x0[1], x0[2]
        ),
        "link  joint  peak |x1|          peak |x1dd|".to_string(),
    ];
    let units = [("rad", "rad/s^2"), ("rad", "rad/s^2"), ("m", "m/s^2")];
    for (j, (d, a)) in peaks(&v).iter().enumerate() {
        lines.push(format!(
            "{}     {}     {:.3e} {:<4}     {:.3e} {}",
            j + 1,
            Mar::JOINT_NAMES[j],
            d,
            units[j].0,
            a,
            units[j].1
        ));
    }
    let mut worst = Vector3::<f64>::zeros();
    for ((t, q), dx) in nl.t.iter().zip(&nl.q).zip(&v.response.dx) {
        let dev = q - plan.at(*t).1.q;
        worst = worst.zip_map(&(dev - dx), |w, e| w.max(e.abs()));
    }
    lines.push(format!(
        "linear eq. 9 vs nonlinear elastic-drive simulation: largest difference [{:.1e}, {:.1e}, {:.1e}]",
        worst[0], worst[1], worst[2]
    ));
    let dev = v.gripper.iter().fold(0.0f64, |m, d| m.max(*d));
    lines.push(format!(
        "peak gripper deviation |J x1| = {:.3} mm (J: the gripper's point Jacobian on the nominal motion)",
        dev * 1e3
    ));
    let tau_peak = v.driving.iter().fold(Vector3::<f64>::zeros(), |m, t| {
        m.zip_map(t, |a, b| a.max(b.abs()))
    });
    lines.push(format!(
        "peak driving quantities: M2 = {:.2} N m, F3 = {:.2} N",
        tau_peak[1], tau_peak[2]
    ));
    Ok(lines)
}

/// t, beta and the gripper, then x1, x1d, x1dd and tau_n per joint.
fn perturbation_csv(v: &Vibration) -> String {
    let mut out = String::from("t,beta_deg,x,y,speed,accel_t,accel_abs,gripper_dev");
    for kind in ["dx", "dxd", "dxdd", "tau_n"] {
        for j in Mar::JOINT_NAMES {
            let _ = write!(out, ",{kind}_{j}");
        }
    }
    out.push('\n');
    let r = &v.response;
    for i in 0..r.nominal.t.len() {
        let p = &v.path[i];
        let _ = write!(
            out,
            "{},{},{},{},{},{},{},{:e}",
            r.nominal.t[i],
            p.beta.to_degrees(),
            p.p.x,
            p.p.y,
            p.speed,
            p.accel,
            p.a.norm(),
            v.gripper[i]
        );
        for vec in [&r.dx[i], &r.dxd[i], &r.dxdd[i], &v.driving[i]] {
            for x in vec.iter() {
                let _ = write!(out, ",{x:e}");
            }
        }
        out.push('\n');
    }
    out
}

/// One series against beta in degrees.
fn vs_beta<'a>(v: &Vibration, name: &'a str, f: impl Fn(usize) -> f64) -> Series<'a> {
    Series {
        name,
        points: v
            .path
            .iter()
            .enumerate()
            .map(|(i, p)| (p.beta.to_degrees(), f(i)))
            .collect(),
    }
}

/// The vibration paper's Figs. 3, 4, 5, 7, 8 (and the path of Fig. 2).
fn figures(v: &Vibration, dir: &Path) -> Result<(), ScenarioError> {
    let r = &v.response;
    let beta = "beta [deg]";
    let path: Vec<(f64, f64)> = v.path.iter().map(|p| (p.p.x, p.p.y)).collect();
    let plots: Vec<(&str, String)> = vec![
        (
            "fig2-path.svg",
            svg(
                "MAR gripper path (Table 2), local frame X1 Y1",
                "X1 [m]",
                "Y1 [m]",
                &[Series {
                    name: "gripper",
                    points: path,
                }],
                true,
            ),
        ),
        (
            "fig3-gripper.svg",
            svg(
                "Fig. 3: gripper velocity and acceleration",
                beta,
                "[m/s], [m/s^2]",
                &[
                    vs_beta(v, "v [m/s]", |i| v.path[i].speed),
                    vs_beta(v, "a tangential [m/s^2]", |i| v.path[i].accel),
                    vs_beta(v, "|a| [m/s^2]", |i| v.path[i].a.norm()),
                ],
                false,
            ),
        ),
        (
            "fig4-q.svg",
            svg(
                "Fig. 4: generalized coordinates",
                beta,
                "[rad], [m]",
                &[
                    vs_beta(v, "q2 [rad]", |i| r.nominal.q[i][1]),
                    vs_beta(v, "q3 [m]", |i| r.nominal.q[i][2]),
                ],
                false,
            ),
        ),
        (
            "fig5-driving.svg",
            svg(
                "Fig. 5: driving quantities of the nominal motion",
                beta,
                "[N m], [N]",
                &[
                    vs_beta(v, "M2 [N m]", |i| v.driving[i][1]),
                    vs_beta(v, "F3 [N]", |i| v.driving[i][2]),
                ],
                false,
            ),
        ),
    ];
    for (file, text) in plots {
        write(dir, file, &text)?;
    }
    for (j, link, unit) in [(1, "2", "rad"), (2, "3", "m")] {
        let name = format!("x1 link {link} [{unit}]");
        write(
            dir,
            &format!("fig7-link{link}.svg"),
            &svg(
                &format!("Fig. 7: perturbation of link {link}'s position"),
                beta,
                &format!("[{unit}]"),
                &[vs_beta(v, &name, |i| r.dx[i][j])],
                false,
            ),
        )?;
        let name = format!("x1dd link {link} [{unit}/s^2]");
        write(
            dir,
            &format!("fig8-link{link}.svg"),
            &svg(
                &format!("Fig. 8: acceleration of link {link}'s vibration"),
                beta,
                &format!("[{unit}/s^2]"),
                &[vs_beta(v, &name, |i| r.dxdd[i][j])],
                false,
            ),
        )?;
    }
    Ok(())
}
