//! Seed 001, sec. 3.2: a joint with clearance (Figs. 3.12-3.18). The pin of
//! link 2 (radius r2) rolls inside the ring of link 1 (radius r1) while the
//! ring pushes it; when the contact reaction Ru reaches zero the pin leaves
//! the ring and flies freely inside the clearance until it hits the ring
//! again. Both switches are located as events on the dense output
//! (Illinois regula falsi, to 1e-12 s), never by stepping over them.
//!
//! In contact (coordinates `(phi1, psi, u, phi2)` of [`ClearanceArm`]) the
//! constraints (3.25) hold. The OCR prints `f1 = u - (r1 - r2)` and
//! `f2 = r1 psi - r2 phi2`, the second with its sign garbled; derived again:
//! the pin's material point at the contact moves with
//! `(r1 - r2) (phi1' + psi') + r2 (phi1' + psi' + phi2')` along the ring,
//! the ring's with `r1 phi1'`; no slip makes them equal, `r1 psi' + r2 phi2' = 0`,
//! so `f2 = r1 psi + r2 phi2 - c0` with c0 fixed where contact begins.
//! The motion follows the seed's eq. 3.37, `D A qdd = D (Q + Qqt + U)` with
//! D^T spanning the motions the constraints allow, together with the
//! second derivatives of (3.25) (Baumgarte-stabilised); the reaction is
//! `R = A qdd - Q - Qqt - U` and Ru its u-row (sec. 3.2.2). The ring can
//! only push: contact holds while `Ru < 0` (inward along u).
//!
//! Rolling needs a tangential force Ft, which friction can give only up to
//! `mu |Ru|`: the seed's no-slip assumption holds while `|Ft| <= mu |Ru|`.
//! Where it fails the pin slides on the ring with Coulomb friction (only
//! f1 holds), and rolls again when the slip stops and friction suffices;
//! without this the model is inconsistent where Ru -> 0, because the
//! no-slip force would stay finite while the normal force vanishes. Not in
//! the seed, chosen here: mu = 0.15 (dry steel on steel, lubricated 0.1).
//!
//! In slide and flight the Cartesian model [`crate::ClearanceArmFree`]
//! integrates (see [`super::clearance_modes`]). A pin that reaches the ring
//! again hits it plastically and without friction (the seed gives no impact
//! law; restitution 0, chosen here): the normal velocity is removed in the
//! metric of A, which costs `1/2 vn^2 / (J A^-1 J^T)`; then it slides, or
//! stays in flight if the ring would have to pull.
//!
//! Drives: `M1 = M0 sin(w t)` on link 1, `M2 = M0 cos(w t)` between the
//! links, M0 = -1 N m, w = 2 rad/s. Not in the seed (it names phi10,
//! psi0, ... only), chosen here: at rest at t = 0, link 1 horizontal, link 2
//! straight up, the pin at the bottom of the ring; the contact is then lost
//! once within 4 s. (From both links horizontal the ring keeps pushing,
//! |Ru| >= 0.49 N, for 10 s: clearance alone does not open the joint.)
//! The OCR's `delta = 0.005 m` does not match r1 - r2 = 5e-5 m; the radii
//! are used.

use std::f64::consts::FRAC_PI_2;

use dynamics_runtime::ode::{locate_event, Dopri5, JointState, Tolerances};
use dynamics_runtime::{Robot, SimError};
use nalgebra::{Vector2, Vector4};

use super::clearance_modes::{flight, impact, residual, roll, slide, slip_rate, to_free, to_seed};
use super::support::sim_error;
use super::ScenarioError;
use crate::{ClearanceArm, ClearanceArmFree};

/// Ring radius r1, m.
pub const R1: f64 = 0.0025;
/// Pin radius r2, m.
pub const R2: f64 = 0.00245;
/// Clearance r1 - r2, m.
pub const GAP: f64 = R1 - R2;
/// Drive amplitude M0, N m.
pub const M0: f64 = -1.0;
/// Drive frequency w, rad/s.
pub const OMEGA: f64 = 2.0;
/// Friction coefficient pin-ring (chosen; not in the seed).
pub const MU: f64 = 0.15;
/// Time tolerance of the event location, s.
pub const EVENT_TOL: f64 = 1e-12;
/// Half-width of the bracket each switch is checked on, s.
pub const EVENT_CHECK: f64 = 1e-9;
/// Baumgarte gain of the contact constraints, 1/s.
pub(crate) const BAUMGARTE: f64 = 20.0;

/// How the pin meets the ring.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    /// Rolling without slip: (3.25) holds.
    Roll,
    /// Sliding with Coulomb friction: only f1 holds.
    Slide,
    /// Inside the clearance, no contact.
    Flight,
}

/// A located switch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Switch {
    /// Time, s.
    pub t: f64,
    /// The mode left.
    pub from: Mode,
    /// The mode entered.
    pub to: Mode,
    /// The watch function that fired (roll: `-Ru`, `mu |Ru| - |Ft|`;
    /// slide: `-Ru`, slip rate along the slip; flight: `r1 - r2 - u`)
    /// [`EVENT_CHECK`] before `t`, on the same dense output: positive.
    pub g_before: f64,
    /// The same [`EVENT_CHECK`] after `t`: negative.
    pub g_after: f64,
    /// Energy the impact removed (re-contact), J.
    pub impact_loss: f64,
    /// The state at the switch in the seed's coordinates, before the
    /// change (velocities before an impact).
    pub q: Vector4<f64>,
    /// Its rates.
    pub qd: Vector4<f64>,
}

/// One output sample, in the seed's coordinates in every mode.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// Time, s.
    pub t: f64,
    /// Mode.
    pub mode: Mode,
    /// (phi1, psi, u, phi2).
    pub q: Vector4<f64>,
    /// Their rates.
    pub qd: Vector4<f64>,
    /// Pin centre from A in link 1's frame, m.
    pub pin: Vector2<f64>,
    /// Contact reaction Ru along u, N (negative: the ring pushes; 0 in flight).
    pub ru: f64,
    /// Tangential contact force, N (0 in flight).
    pub ft: f64,
    /// Slip rate `r1 psi' + r2 phi2'`, m/s.
    pub slip: f64,
    /// Residuals of (3.25) in contact, m (roll: both; slide: f1).
    pub residual: Vector2<f64>,
    /// T + Pi, J.
    pub energy: f64,
    /// Work of the drives since t = 0, J.
    pub work: f64,
    /// Work of friction since t = 0 (negative), J.
    pub friction_work: f64,
    /// Energy removed by impacts since t = 0, J.
    pub impact_loss: f64,
}

/// The motion with its switches.
#[derive(Debug, Clone, Default)]
pub struct ClearanceRun {
    /// Samples every dt.
    pub samples: Vec<Sample>,
    /// Switches in time order.
    pub switches: Vec<Switch>,
}

type State = (JointState<4>, Vector2<f64>);

#[derive(Debug, Clone, Copy)]
enum Active {
    Roll { c0: f64 },
    Slide { sigma: f64 },
    Flight,
}

impl Active {
    fn mode(&self) -> Mode {
        match self {
            Active::Roll { .. } => Mode::Roll,
            Active::Slide { .. } => Mode::Slide,
            Active::Flight => Mode::Flight,
        }
    }
}

/// The drive torques (M1, M2) at time t.
pub fn drives(t: f64) -> (f64, f64) {
    (M0 * (OMEGA * t).sin(), M0 * (OMEGA * t).cos())
}

/// Where the motion starts: link angles and rates, the pin on the ring at
/// the angle `contact` (world frame) from the ring's centre.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Start {
    /// Link 1's angle phi1, rad.
    pub phi1: f64,
    /// Link 2's angle to link 1 (`psi + phi2`), rad.
    pub phi: f64,
    /// Their rates, rad/s.
    pub rates: Vector2<f64>,
    /// Direction of the contact point from the ring's centre, world frame, rad.
    pub contact: f64,
}

impl Default for Start {
    /// Link 1 horizontal, link 2 straight up, at rest, the pin at the
    /// bottom of the ring.
    fn default() -> Self {
        Start {
            phi1: 0.0,
            phi: FRAC_PI_2,
            rates: Vector2::zeros(),
            contact: -FRAC_PI_2,
        }
    }
}

impl Start {
    /// The seed coordinates (phi1, psi, u, phi2) and rates (pin rolling).
    pub fn seed(&self) -> (Vector4<f64>, Vector4<f64>) {
        let psi = self.contact - self.phi1;
        let k = R2 / GAP;
        (
            Vector4::new(self.phi1, psi, GAP, self.phi - psi),
            Vector4::new(
                self.rates[0],
                -k * self.rates[1],
                0.0,
                (1.0 + k) * self.rates[1],
            ),
        )
    }
}

/// The default start in seed coordinates.
pub fn start() -> (Vector4<f64>, Vector4<f64>) {
    Start::default().seed()
}

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
) -> Result<(f64, State, Option<(usize, f64, f64)>), SimError> {
    let mut ode = Dopri5::new(t0, x0, tol);
    let mut hit: Option<(f64, State, usize, f64, f64)> = None;
    // A watch fires only once it has been seen positive: a mode entered on
    // its own boundary (slip starting from rest) is not left again on the
    // round-off of its first steps.
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
) -> Result<(Active, State), SimError> {
    let free = |a| Ok((a, (JointState { q: *q, qd: *qd }, work)));
    let slides = |sigma: f64| -> Result<bool, SimError> { Ok(slide(t, q, qd, MU, sigma)?.1 < 0.0) };
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
    if n > 0.0 && ft.abs() <= MU * n {
        return Ok((Active::Roll { c0 }, (JointState { q: qs, qd: qds }, work)));
    }
    let sigma = -ft.signum();
    if slides(sigma)? {
        free(Active::Slide { sigma })
    } else {
        free(Active::Flight)
    }
}

/// Simulates `[0, t_end]` sampled every `dt`.
///
/// ```
/// use dynamics_runtime::ode::Tolerances;
/// let run = robots::scenarios::clearance::simulate(0.05, 0.01, Tolerances::default()).unwrap();
/// assert_eq!(run.samples.len(), 6);
/// ```
pub fn simulate(t_end: f64, dt: f64, tol: Tolerances) -> Result<ClearanceRun, ScenarioError> {
    simulate_from(Start::default(), t_end, dt, tol)
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
    let (q0, qd0) = from.seed();
    let (qf0, qfd0) = to_free(&q0, &qd0);
    let (mut active, mut x) = decide(0.0, &qf0, &qfd0, Vector2::zeros(), true, q0[1])?;
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
                    Ok((_, r)) => [-r[2], -MU * r[2] - (r[3] / R2).abs()],
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
                    let (qdd, lam) = slide(t, &x.0.q, &x.0.qd, MU, sigma)?;
                    let (m1, m2) = drives(t);
                    let p = m1 * x.0.qd[0] + m2 * x.0.qd[3];
                    let pf = MU * sigma * lam * slip_rate(&x.0.q, &x.0.qd);
                    Ok((JointState { q: x.0.qd, qd: qdd }, Vector2::new(p, pf)))
                };
                let mut g = |t: f64, x: &State| match slide(t, &x.0.q, &x.0.qd, MU, sigma) {
                    Ok((_, lam)) => [-lam, sigma * slip_rate(&x.0.q, &x.0.qd)],
                    Err(_) => [f64::NAN; 2],
                };
                let mut record = |ts: f64, x: &State| {
                    let lam = slide(ts, &x.0.q, &x.0.qd, MU, sigma).map_or(f64::NAN, |r| r.1);
                    let (q, qd) = to_seed(&x.0.q, &x.0.qd, *psi);
                    *psi = q[1];
                    samples.push(Sample {
                        t: ts,
                        mode: Mode::Slide,
                        q,
                        qd,
                        pin: Vector2::new(x.0.q[1], x.0.q[2]),
                        ru: lam,
                        ft: MU * sigma * lam,
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
                // Leave the seed's coordinates for the Cartesian ones.
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
            (Active::Slide { .. }, _) => decide(t, &x.0.q, &x.0.qd, x.1, true, psi_last)?,
            (Active::Flight, _) => {
                let mut q = x.0.q;
                let scale = GAP / q[1].hypot(q[2]);
                q[1] *= scale;
                q[2] *= scale;
                let (qd, l) = impact(&q, &x.0.qd)?;
                lost = l;
                loss += l;
                decide(t, &q, &qd, x.1, false, psi_last)?
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

/// The rolling constant of a seed state on the ring (for forces only).
fn residual_c0(q: &Vector4<f64>) -> f64 {
    R1 * q[1] + R2 * q[3]
}
