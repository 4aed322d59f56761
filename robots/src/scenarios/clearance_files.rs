//! Outputs of the clearance scenario (dissertation, sec. 3.2): CSV of the motion
//! and of the switches, the plots of Figs. 3.15-3.18, the joint without
//! clearance for comparison, and the summary.

use std::fmt::Write as _;
use std::path::Path;

use dynamics_runtime::ode::Tolerances;
use dynamics_runtime::{simulate_program, Baumgarte};
use nalgebra::{Vector2, Vector4};

use super::clearance::{drives, start, ClearanceRun, Mode, GAP};
use super::clearance_run::simulate;
use super::support::trajectory_csv;
use super::{write, ScenarioError};
use crate::ClearanceArmFree;
use dynamics_cli::plot::{svg, Series};

/// Simulated time, s.
pub const DURATION: f64 = 4.0;

/// Tolerances of the scenario.
pub fn tolerances() -> Tolerances {
    Tolerances {
        rtol: 1e-10,
        atol: 1e-13,
        ..Default::default()
    }
}

fn name(m: Mode) -> &'static str {
    match m {
        Mode::Roll => "roll",
        Mode::Slide => "slide",
        Mode::Flight => "flight",
    }
}

fn csv(run: &ClearanceRun) -> String {
    let mut s = String::from("t,mode,phi1,psi,u,phi2,phi1d,psid,ud,phi2d,pin_x,pin_y,ru,ft,slip,f1,f2,energy,work,friction_work,impact_loss\n");
    for p in &run.samples {
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}",
            p.t,
            name(p.mode),
            p.q[0],
            p.q[1],
            p.q[2],
            p.q[3],
            p.qd[0],
            p.qd[1],
            p.qd[2],
            p.qd[3],
            p.pin[0],
            p.pin[1],
            p.ru,
            p.ft,
            p.slip,
            p.residual[0],
            p.residual[1],
            p.energy,
            p.work,
            p.friction_work,
            p.impact_loss
        );
    }
    s
}

/// Runs the scenario into `dir`.
pub fn run(dir: &Path) -> Result<Vec<String>, ScenarioError> {
    let dt = 1e-3;
    let run = simulate(DURATION, dt, tolerances())?;
    write(dir, "clearance.csv", &csv(&run))?;
    let mut sw = String::from("t,from,to,g_before,g_after,impact_loss\n");
    for s in &run.switches {
        let _ = writeln!(
            sw,
            "{},{},{},{},{},{}",
            s.t,
            name(s.from),
            name(s.to),
            s.g_before,
            s.g_after,
            s.impact_loss
        );
    }
    write(dir, "clearance-switches.csv", &sw)?;
    // The joint without clearance (delta = 0): the pin held at A.
    let free = ClearanceArmFree::default();
    let (q0, _) = start();
    let rigid = simulate_program(
        &free,
        Vector4::new(q0[0], 0.0, 0.0, q0[1] + q0[3]),
        Vector4::zeros(),
        |t, _, _| {
            let (m1, m2) = drives(t);
            Vector4::new(m1, 0.0, 0.0, m2)
        },
        DURATION,
        dt,
        tolerances(),
        Baumgarte::default(),
    )?;
    trajectory_csv::<ClearanceArmFree, 4>("clearance-nogap", &rigid.trajectory, dir)?;
    let ts = |f: &dyn Fn(usize) -> f64| -> Vec<(f64, f64)> {
        run.samples
            .iter()
            .enumerate()
            .map(|(k, p)| (p.t, f(k)))
            .collect()
    };
    let s = &run.samples;
    let rt = &rigid.trajectory;
    let plots: [(&str, &str, &str, Vec<Series>); 7] = [
        (
            "phi1-nogap.svg",
            "no clearance (delta = 0): phi1 and its rate (Fig. 3.15)",
            "rad, rad/s",
            vec![
                Series {
                    name: "phi1",
                    points: rt.t.iter().zip(&rt.q).map(|(t, q)| (*t, q[0])).collect(),
                },
                Series {
                    name: "phi1'",
                    points: rt.t.iter().zip(&rt.qd).map(|(t, q)| (*t, q[0])).collect(),
                },
            ],
        ),
        (
            "phi1.svg",
            "phi1 with and without clearance",
            "phi1 [rad]",
            vec![
                Series {
                    name: "clearance",
                    points: ts(&|k| s[k].q[0]),
                },
                Series {
                    name: "no clearance",
                    points: rt.t.iter().zip(&rt.q).map(|(t, q)| (*t, q[0])).collect(),
                },
            ],
        ),
        (
            "psi.svg",
            "line of centres: psi and its rate (Fig. 3.16)",
            "rad, rad/s",
            vec![
                Series {
                    name: "psi",
                    points: ts(&|k| s[k].q[1]),
                },
                Series {
                    name: "psi' / 100",
                    points: ts(&|k| s[k].qd[1] / 100.0),
                },
            ],
        ),
        (
            "phi2.svg",
            "link 2 against the line of centres: phi2 and its rate (Fig. 3.17)",
            "rad, rad/s",
            vec![
                Series {
                    name: "phi2",
                    points: ts(&|k| s[k].q[3]),
                },
                Series {
                    name: "phi2' / 100",
                    points: ts(&|k| s[k].qd[3] / 100.0),
                },
            ],
        ),
        (
            "reaction.svg",
            "contact reaction Ru along u (Fig. 3.18) and friction Ft; 0 in flight",
            "N",
            vec![
                Series {
                    name: "Ru",
                    points: ts(&|k| s[k].ru),
                },
                Series {
                    name: "Ft",
                    points: ts(&|k| s[k].ft),
                },
            ],
        ),
        (
            "u.svg",
            "distance u of the pin centre from the ring's (r1 - r2 = 5e-5 m in contact)",
            "u [m]",
            vec![Series {
                name: "u",
                points: ts(&|k| s[k].q[2]),
            }],
        ),
        (
            "energy.svg",
            "energy balance: E - E0 - W(drives) - W(friction) + impact losses",
            "J",
            vec![Series {
                name: "balance",
                points: ts(&|k| {
                    s[k].energy - s[0].energy - s[k].work - s[k].friction_work + s[k].impact_loss
                }),
            }],
        ),
    ];
    for (file, title, ylabel, series) in &plots {
        write(dir, file, &svg(title, "t [s]", ylabel, series, false))?;
    }
    let ring: Vec<(f64, f64)> = (0..=200)
        .map(|k| {
            let a = 2.0 * std::f64::consts::PI * k as f64 / 200.0;
            (GAP * a.cos(), GAP * a.sin())
        })
        .collect();
    write(
        dir,
        "pin.svg",
        &svg(
            "pin centre inside the clearance (link 1's frame)",
            "x [m]",
            "y [m]",
            &[
                Series {
                    name: "r1 - r2",
                    points: ring,
                },
                Series {
                    name: "pin centre",
                    points: s.iter().map(|p| (p.pin[0], p.pin[1])).collect(),
                },
            ],
            true,
        ),
    )?;
    Ok(summary(&run, &rigid.trajectory.q))
}

fn summary(run: &ClearanceRun, rigid: &[Vector4<f64>]) -> Vec<String> {
    let count = |from: Option<Mode>, to: Mode| {
        run.switches
            .iter()
            .filter(|w| w.to == to && from.is_none_or(|f| w.from == f))
            .count()
    };
    let losses: Vec<String> = run
        .switches
        .iter()
        .filter(|w| w.to == Mode::Flight && w.from != Mode::Flight)
        .take(4)
        .map(|w| format!("{:.9}", w.t))
        .collect();
    let hits: Vec<String> = run
        .switches
        .iter()
        .filter(|w| w.from == Mode::Flight)
        .take(4)
        .map(|w| format!("{:.9}", w.t))
        .collect();
    let s = &run.samples;
    let e0 = s[0].energy;
    let balance = s
        .iter()
        .map(|p| (p.energy - e0 - p.work - p.friction_work + p.impact_loss).abs())
        .fold(0.0, f64::max);
    let roll_res = s
        .iter()
        .filter(|p| p.mode != Mode::Flight)
        .map(|p| p.residual.abs().max())
        .fold(0.0, f64::max);
    let share = |m: Mode| 100.0 * s.iter().filter(|p| p.mode == m).count() as f64 / s.len() as f64;
    let ru_min = s.iter().map(|p| p.ru).fold(f64::INFINITY, f64::min);
    let dphi = s
        .iter()
        .zip(rigid)
        .map(|(p, q)| (p.q[0] - q[0]).abs())
        .fold(0.0, f64::max);
    let unbracketed = run
        .switches
        .iter()
        .filter(|w| !(w.g_before > 0.0 && w.g_after < 0.0))
        .count();
    let last = s.last().copied();
    let radius = s
        .iter()
        .map(|p| Vector2::new(p.pin[0], p.pin[1]).norm())
        .fold(0.0, f64::max);
    vec![
        format!(
            "{DURATION} s from rest, link 1 horizontal, link 2 up, pin at the ring's bottom; r1 = 0.0025, r2 = 0.00245 m; M1 = -sin 2t, M2 = -cos 2t N m; friction mu = {}",
            super::clearance::MU
        ),
        format!(
            "time share: rolling {:.1} %, sliding {:.1} %, flight {:.1} %",
            share(Mode::Roll),
            share(Mode::Slide),
            share(Mode::Flight)
        ),
        format!(
            "{} losses of contact (Ru -> 0), first at t = {} s",
            count(Some(Mode::Roll), Mode::Flight) + count(Some(Mode::Slide), Mode::Flight),
            losses.join(", ")
        ),
        format!(
            "{} re-contacts (impacts), first at t = {} s; impacts removed {:.3e} J",
            run.switches.iter().filter(|w| w.from == Mode::Flight).count(),
            hits.join(", "),
            last.map_or(0.0, |p| p.impact_loss)
        ),
        format!(
            "{} roll -> slide (|Ft| = mu |Ru|), {} slide -> roll; friction did {:.3e} J",
            count(Some(Mode::Roll), Mode::Slide),
            count(Some(Mode::Slide), Mode::Roll),
            last.map_or(0.0, |p| p.friction_work)
        ),
        format!(
            "{} switches located to {:.0e} s on the dense output; {} without a sign change of their watch function within +-1e-9 s",
            run.switches.len(),
            super::clearance::EVENT_TOL,
            unbracketed
        ),
        format!("largest push of the ring -Ru = {:.3} N; pin centre within {radius:.3e} m of A (r1 - r2 = {GAP:.1e} m)", -ru_min),
        format!("largest residual of (3.25) in contact: {roll_res:.2e} m; energy balance |E - E0 - W + losses| <= {balance:.2e} J"),
        format!("phi1 differs from the joint without clearance by up to {dphi:.4} rad"),
    ]
}
