//! The hybrid integration of the clearance scenario (see
//! [`super::clearance`]): one mode at a time on Dormand-Prince 5(4) with
//! its watch functions, every switch located on the dense output, the
//! mode decisions at the ring, and the samples.

use dynamics_runtime::ode::{locate_event, Dopri5, JointState, Tolerances};
use dynamics_runtime::{Robot, SimError};
use nalgebra::{Vector2, Vector4};

use super::clearance::{
    drives, Active, ClearanceRun, Mode, Sample, Start, State, Switch, EVENT_CHECK, EVENT_TOL, GAP,
    R1, R2,
};
use super::clearance_modes::{flight, impact, residual, roll, slide, slip_rate, to_free, to_seed};
use super::support::sim_error;
use super::ScenarioError;
use crate::{ClearanceArm, ClearanceArmFree};

/// End of a phase: time, state, and the watch that fired with its values
/// before and after.
type PhaseEnd = (f64, State, Option<(usize, f64, f64)>);

/// Runs one mode from (t0, x0) until one of its watch functions crosses
/// from positive to negative, or to `t_end`; records the grid on the way.
/// Returns the end time, state and the watch that fired with its values
/// [`EVENT_CHECK`] before and after.
#[allow(clippy::too_many_arguments)]
fn phase(
    rhs: &mut impl FnMut(f64, &State) -> Result<State, SimError>,
    g: &mut impl FnMut(f64, &State) -> [f64; 2],
    record: &mut impl FnMut(f64, &State),
    grid: &mut (usize, usize, f64),
    t0: f64,
    x0: State,
    t_end: f64,
    tol: Tolerances,
) -> Result<PhaseEnd, SimError> {
    let mut ode = Dopri5::new(t0, x0, tol);
    let mut hit: Option<(f64, State, usize, f64, f64)> = None;
    // A watch fires only once it has been seen positive, and not within
    // [`EVENT_CHECK`] of the entry: a mode entered on its own boundary (slip
    // starting from rest) is not left again on the round-off of its first
    // steps.
    let mut armed = g(t0, &x0).map(|v| v > 0.0);
    ode.run(rhs, t_end, |step| {
        let (g0, g1) = (g(step.t0, &step.y0), g(step.t0 + step.h, &step.y1));
        let mut fired: Option<(f64, usize)> = None;
        for k in 0..2 {
            if !(armed[k] && g1[k] < 0.0) {
                armed[k] |= g1[k] > 0.0;
                continue;
            }
            let te = if g0[k] > 0.0 {
                let mut gk = |t: f64, x: &State| g(t, x)[k];
                locate_event(step, &mut gk, g0[k], g1[k], EVENT_TOL)
            } else {
                step.t0
            };
            if te <= t0 + EVENT_CHECK {
                // Within the switch resolution of the entry: the round-off
                // of the boundary the mode was entered on, not a new event.
                armed[k] = false;
                continue;
            }
            if fired.is_none_or(|f| te < f.0) {
                fired = Some((te, k));
            }
        }
        let limit = fired.map_or(step.t0 + step.h + 1e-12, |f| f.0);
        while grid.0 <= grid.1 {
            let ts = (grid.0 as f64 * grid.2).min(t_end);
            if ts > limit {
                break;
            }
            record(ts, &step.at(ts));
            grid.0 += 1;
        }
        if let Some((te, k)) = fired {
            let a = (te - EVENT_CHECK).max(step.t0);
            let b = (te + EVENT_CHECK).min(step.t0 + step.h);
            let (ga, gb) = (g(a, &step.at(a))[k], g(b, &step.at(b))[k]);
            hit = Some((te, step.at(te), k, ga, gb));
            return false;
        }
        true
    })
    .map_err(sim_error)?;
    Ok(match hit {
        Some((te, x, k, ga, gb)) => (te, x, Some((k, ga, gb))),
        None => (ode.t(), *ode.y(), None),
    })
}

/// The mode a pin on the ring (Cartesian state, normal velocity 0) goes on
/// in, with its state in that mode's coordinates. `stopped`: the slip has
/// just stopped (rolling may hold).
fn decide(
    t: f64,
    q: &Vector4<f64>,
    qd: &Vector4<f64>,
    work: Vector2<f64>,
    stopped: bool,
    psi_near: f64,
    mu: f64,
) -> Result<(Active, State), SimError> {
    let free = |a| Ok((a, (JointState { q: *q, qd: *qd }, work)));
    let slides = |sigma: f64| -> Result<bool, SimError> { Ok(slide(t, q, qd, mu, sigma)?.1 < 0.0) };
    let vs = slip_rate(q, qd);
    if !stopped && vs != 0.0 {
        let sigma = vs.signum();
        return if slides(sigma)? {
            free(Active::Slide { sigma })
        } else {
            free(Active::Flight)
        };
    }
    let (qs, qds) = to_seed(q, qd, psi_near);
    let c0 = R1 * qs[1] + R2 * qs[3];
    let (_, r) = roll(t, &qs, &qds, c0)?;
    let (n, ft) = (-r[2], r[3] / R2);
    if n > 0.0 && ft.abs() <= mu * n {
        return Ok((Active::Roll { c0 }, (JointState { q: qs, qd: qds }, work)));
    }
    let sigma = -ft.signum();
    if slides(sigma)? {
        free(Active::Slide { sigma })
    } else {
        free(Active::Flight)
    }
}

/// Simulates from `from` over `[0, t_end]` sampled every `dt`.
pub fn simulate_from(
    from: Start,
    t_end: f64,
    dt: f64,
    tol: Tolerances,
) -> Result<ClearanceRun, ScenarioError> {
    if !(t_end.is_finite() && t_end > 0.0 && dt > 0.0 && dt <= t_end) {
        return Err(SimError::Span(format!("t_end = {t_end}, dt = {dt}")).into());
    }
    let arm = ClearanceArm::default();
    let free = ClearanceArmFree::default();
    let mut run = ClearanceRun::default();
    let mu = from.mu;
    if !(mu.is_finite() && mu >= 0.0) {
        return Err(ScenarioError::Data(format!(
            "clearance: the friction coefficient must be finite and >= 0, got {mu}"
        )));
    }
    let (q0, qd0) = from.seed();
    let (qf0, qfd0) = to_free(&q0, &qd0);
    let (mut active, mut x) = decide(0.0, &qf0, &qfd0, Vector2::zeros(), true, q0[1], mu)?;
    let mut grid = (0usize, (t_end / dt).round() as usize, dt);
    let mut loss = 0.0;
    let mut psi_last = q0[1];
    let mut t = 0.0;
    while t < t_end {
        if run.switches.len() > 100_000 {
            return Err(ScenarioError::Data(format!(
                "clearance: more than 100000 switches by t = {t} s (chattering)"
            )));
        }
        let samples = &mut run.samples;
        let psi = &mut psi_last;
        let (te, xe, ev) = match active {
            Active::Roll { c0 } => {
                let mut rhs = |t: f64, x: &State| -> Result<State, SimError> {
                    let (qdd, _) = roll(t, &x.0.q, &x.0.qd, c0)?;
                    let (m1, m2) = drives(t);
                    let p = m1 * x.0.qd[0] + m2 * (x.0.qd[1] + x.0.qd[3]);
                    Ok((JointState { q: x.0.qd, qd: qdd }, Vector2::new(p, 0.0)))
                };
                let mut g = |t: f64, x: &State| match roll(t, &x.0.q, &x.0.qd, c0) {
                    Ok((_, r)) => [-r[2], -mu * r[2] - (r[3] / R2).abs()],
                    Err(_) => [f64::NAN; 2],
                };
                let mut record = |ts: f64, x: &State| {
                    let (q, qd) = (x.0.q, x.0.qd);
                    let r = roll(ts, &q, &qd, c0).map_or(Vector4::repeat(f64::NAN), |r| r.1);
                    let (pin, _) = to_free(&q, &qd);
                    *psi = q[1];
                    samples.push(Sample {
                        t: ts,
                        mode: Mode::Roll,
                        q,
                        qd,
                        pin: Vector2::new(pin[1], pin[2]),
                        ru: r[2],
                        ft: r[3] / R2,
                        slip: R1 * qd[1] + R2 * qd[3],
                        residual: residual(&q, c0),
                        energy: arm.total_energy(&q, &qd),
                        work: x.1[0],
                        friction_work: x.1[1],
                        impact_loss: loss,
                    });
                };
                phase(&mut rhs, &mut g, &mut record, &mut grid, t, x, t_end, tol)?
            }
            Active::Slide { sigma } => {
                let mut rhs = |t: f64, x: &State| -> Result<State, SimError> {
                    let (qdd, lam) = slide(t, &x.0.q, &x.0.qd, mu, sigma)?;
                    let (m1, m2) = drives(t);
                    let p = m1 * x.0.qd[0] + m2 * x.0.qd[3];
                    let pf = mu * sigma * lam * slip_rate(&x.0.q, &x.0.qd);
                    Ok((JointState { q: x.0.qd, qd: qdd }, Vector2::new(p, pf)))
                };
                let mut g = |t: f64, x: &State| match slide(t, &x.0.q, &x.0.qd, mu, sigma) {
                    Ok((_, lam)) => [-lam, sigma * slip_rate(&x.0.q, &x.0.qd)],
                    Err(_) => [f64::NAN; 2],
                };
                let mut record = |ts: f64, x: &State| {
                    let lam = slide(ts, &x.0.q, &x.0.qd, mu, sigma).map_or(f64::NAN, |r| r.1);
                    let (q, qd) = to_seed(&x.0.q, &x.0.qd, *psi);
                    *psi = q[1];
                    samples.push(Sample {
                        t: ts,
                        mode: Mode::Slide,
                        q,
                        qd,
                        pin: Vector2::new(x.0.q[1], x.0.q[2]),
                        ru: lam,
                        ft: mu * sigma * lam,
                        slip: slip_rate(&x.0.q, &x.0.qd),
                        residual: Vector2::new(q[2] - GAP, 0.0),
                        energy: free.total_energy(&x.0.q, &x.0.qd),
                        work: x.1[0],
                        friction_work: x.1[1],
                        impact_loss: loss,
                    });
                };
                phase(&mut rhs, &mut g, &mut record, &mut grid, t, x, t_end, tol)?
            }
            Active::Flight => {
                let mut rhs = |t: f64, x: &State| -> Result<State, SimError> {
                    let qdd = flight(t, &x.0.q, &x.0.qd)?;
                    let (m1, m2) = drives(t);
                    let p = m1 * x.0.qd[0] + m2 * x.0.qd[3];
                    Ok((JointState { q: x.0.qd, qd: qdd }, Vector2::new(p, 0.0)))
                };
                let mut g = |_t: f64, x: &State| [GAP - x.0.q[1].hypot(x.0.q[2]), 1.0];
                let mut record = |ts: f64, x: &State| {
                    let (q, qd) = to_seed(&x.0.q, &x.0.qd, *psi);
                    *psi = q[1];
                    samples.push(Sample {
                        t: ts,
                        mode: Mode::Flight,
                        q,
                        qd,
                        pin: Vector2::new(x.0.q[1], x.0.q[2]),
                        ru: 0.0,
                        ft: 0.0,
                        slip: slip_rate(&x.0.q, &x.0.qd),
                        residual: Vector2::zeros(),
                        energy: free.total_energy(&x.0.q, &x.0.qd),
                        work: x.1[0],
                        friction_work: x.1[1],
                        impact_loss: loss,
                    });
                };
                phase(&mut rhs, &mut g, &mut record, &mut grid, t, x, t_end, tol)?
            }
        };
        t = te;
        x = xe;
        let Some((k, g_before, g_after)) = ev else {
            continue;
        };
        let from = active.mode();
        let mut lost = 0.0;
        let (sq, sqd) = match active {
            Active::Roll { .. } => (x.0.q, x.0.qd),
            _ => to_seed(&x.0.q, &x.0.qd, psi_last),
        };
        (active, x) = match (active, k) {
            (Active::Roll { .. }, _) => {
                // Leave the dissertation's coordinates for the Cartesian ones.
                let r = roll(t, &x.0.q, &x.0.qd, residual_c0(&x.0.q))?.1;
                psi_last = x.0.q[1];
                let (q, qd) = to_free(&x.0.q, &x.0.qd);
                let next = if k == 0 {
                    Active::Flight
                } else {
                    Active::Slide {
                        sigma: -(r[3]).signum(),
                    }
                };
                (next, (JointState { q, qd }, x.1))
            }
            (Active::Slide { .. }, 0) => (Active::Flight, x),
            (Active::Slide { .. }, _) => decide(t, &x.0.q, &x.0.qd, x.1, true, psi_last, mu)?,
            (Active::Flight, _) => {
                let mut q = x.0.q;
                let scale = GAP / q[1].hypot(q[2]);
                q[1] *= scale;
                q[2] *= scale;
                let (qd, l) = impact(&q, &x.0.qd)?;
                lost = l;
                loss += l;
                decide(t, &q, &qd, x.1, false, psi_last, mu)?
            }
        };
        if let Active::Roll { .. } = active {
            psi_last = x.0.q[1];
        }
        run.switches.push(Switch {
            t,
            from,
            to: active.mode(),
            g_before,
            g_after,
            impact_loss: lost,
            q: sq,
            qd: sqd,
        });
    }
    Ok(run)
}

/// The rolling constant of a state in the dissertation's coordinates on the ring (for forces only).
fn residual_c0(q: &Vector4<f64>) -> f64 {
    R1 * q[1] + R2 * q[3]
}

/// Simulates `[0, t_end]` sampled every `dt`.
///
/// ```
/// use dynamics_runtime::ode::Tolerances;
/// let run = robots::scenarios::clearance_run::simulate(0.05, 0.01, Tolerances::default()).unwrap();
/// assert_eq!(run.samples.len(), 6);
/// ```
pub fn simulate(t_end: f64, dt: f64, tol: Tolerances) -> Result<ClearanceRun, ScenarioError> {
    simulate_from(Start::default(), t_end, dt, tol)
}
