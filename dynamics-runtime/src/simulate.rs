//! Forward simulation of a generated robot under a joint-effort input.

use std::io::Write;

use nalgebra::SVector;
use thiserror::Error;

use crate::ode::{Dopri5, JointState, OdeError, OdeState, Tolerances};
use crate::{DynamicsError, Robot};

/// Why a simulation stopped. Every variant says when.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum SimError {
    /// The dynamics could not be evaluated (singular A, non-finite values).
    #[error("at t = {t:.6} s: {source}")]
    Dynamics {
        /// Time.
        t: f64,
        /// What failed.
        source: DynamicsError,
    },
    /// The input returned NaN or an infinity.
    #[error("at t = {t:.6} s: the input effort of joint `{joint}` is not finite")]
    Input {
        /// Time.
        t: f64,
        /// The joint.
        joint: &'static str,
    },
    /// The step size fell below the minimum: the motion is too stiff or diverges.
    #[error("at t = {t:.6} s: the step size collapsed to {h:e} s (stiff or diverging motion)")]
    StepSizeCollapsed {
        /// Time.
        t: f64,
        /// Step size.
        h: f64,
    },
    /// More steps than allowed.
    #[error("at t = {t:.6} s: too many integration steps")]
    TooManySteps {
        /// Time.
        t: f64,
    },
    /// The time span or output rate is unusable.
    #[error("bad time span: {0}")]
    Span(String),
}

/// A simulated motion, sampled at the output times.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Trajectory<const N: usize> {
    /// Sample times.
    pub t: Vec<f64>,
    /// Positions.
    pub q: Vec<SVector<f64, N>>,
    /// Velocities.
    pub qd: Vec<SVector<f64, N>>,
    /// Accelerations.
    pub qdd: Vec<SVector<f64, N>>,
    /// Efforts applied.
    pub tau: Vec<SVector<f64, N>>,
}

impl<const N: usize> Trajectory<N> {
    /// Writes the trajectory CSV format (docs/cli.md): `t`, then `q_<joint>`,
    /// `qd_<joint>`, `qdd_<joint>`, `tau_<joint>` for each joint.
    ///
    /// ```
    /// let tr = dynamics_runtime::Trajectory::<1> {
    ///     t: vec![0.0], q: vec![[1.0].into()], qd: vec![[0.0].into()],
    ///     qdd: vec![[0.5].into()], tau: vec![[2.0].into()],
    /// };
    /// let mut out = Vec::new();
    /// tr.write_csv(&mut out, &["j"]).unwrap();
    /// assert_eq!(String::from_utf8(out).unwrap(), "t,q_j,qd_j,qdd_j,tau_j\n0,1,0,0.5,2\n");
    /// ```
    pub fn write_csv(&self, out: &mut impl Write, joints: &[&str; N]) -> std::io::Result<()> {
        let mut header = vec!["t".to_string()];
        for prefix in ["q", "qd", "qdd", "tau"] {
            header.extend(joints.iter().map(|j| format!("{prefix}_{j}")));
        }
        writeln!(out, "{}", header.join(","))?;
        for k in 0..self.t.len() {
            let mut row = vec![format!("{}", self.t[k])];
            for v in [&self.q[k], &self.qd[k], &self.qdd[k], &self.tau[k]] {
                row.extend(v.iter().map(|x| format!("{x}")));
            }
            writeln!(out, "{}", row.join(","))?;
        }
        Ok(())
    }
}

/// Simulates `robot` from (q0, qd0) under `input(t, q, qd) -> tau` over
/// `[0, t_end]`, sampled every `dt` (dense output of Dormand-Prince 5(4)).
///
/// ```
/// use dynamics_runtime::{simulate, ode::Tolerances, Robot};
/// dynamics_macros::robot! {
///     pub robot Pendulum;
///     gravity = [0.0, -9.81, 0.0];
///     link base;
///     link rod { mass = 1.0; com = [1.0, 0.0, 0.0]; }
///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
/// }
/// let p = Pendulum::default();
/// let tr = simulate(&p, [0.0].into(), [0.0].into(), |_, _, _| [0.0].into(), 1.0, 0.1, Tolerances::default()).unwrap();
/// assert_eq!(tr.t.len(), 11);
/// assert!(tr.q[10][0] < -0.5); // it falls
/// ```
pub fn simulate<R: Robot<N>, const N: usize>(
    robot: &R,
    q0: SVector<f64, N>,
    qd0: SVector<f64, N>,
    mut input: impl FnMut(f64, &SVector<f64, N>, &SVector<f64, N>) -> SVector<f64, N>,
    t_end: f64,
    dt: f64,
    tol: Tolerances,
) -> Result<Trajectory<N>, SimError> {
    check_span(t_end, dt)?;
    let mut accel =
        |t: f64, x: &JointState<N>| -> Result<(SVector<f64, N>, SVector<f64, N>), SimError> {
            let tau = input(t, &x.q, &x.qd);
            if let Some(i) = tau.iter().position(|v| !v.is_finite()) {
                return Err(SimError::Input {
                    t,
                    joint: R::JOINT_NAMES[i],
                });
            }
            let qdd = robot
                .forward_dynamics(&x.q, &x.qd, &tau)
                .map_err(|source| SimError::Dynamics { t, source })?;
            Ok((qdd, tau))
        };
    /// Accelerations and efforts at a state.
    type Accel<'a, const N: usize> =
        dyn FnMut(f64, &JointState<N>) -> Result<(SVector<f64, N>, SVector<f64, N>), SimError> + 'a;
    let mut out = Trajectory::default();
    let record = |t: f64,
                  x: &JointState<N>,
                  out: &mut Trajectory<N>,
                  accel: &mut Accel<N>|
     -> Result<(), SimError> {
        let (qdd, tau) = accel(t, x)?;
        out.t.push(t);
        out.q.push(x.q);
        out.qd.push(x.qd);
        out.qdd.push(qdd);
        out.tau.push(tau);
        Ok(())
    };
    let x0 = JointState { q: q0, qd: qd0 };
    let mut rhs = |t: f64, x: &JointState<N>| -> Result<JointState<N>, SimError> {
        let (qdd, _) = accel(t, x)?;
        Ok(JointState { q: x.qd, qd: qdd })
    };
    let (pending, failure) = sampled(&mut rhs, x0, t_end, dt, tol);
    for (t, x) in pending {
        if let Some(i) = [x.q, x.qd]
            .iter()
            .flat_map(|v| v.iter())
            .position(|v| !v.is_finite())
        {
            return Err(SimError::Dynamics {
                t,
                source: DynamicsError::Diverged {
                    quantity: if i < N { "q" } else { "qd" },
                    index: i % N,
                },
            });
        }
        record(t, &x, &mut out, &mut accel)?;
    }
    match failure {
        Some(e) => Err(e),
        None => Ok(out),
    }
}

/// Fails unless `0 < dt <= t_end < inf`.
pub(crate) fn check_span(t_end: f64, dt: f64) -> Result<(), SimError> {
    if !(t_end.is_finite() && t_end > 0.0) {
        return Err(SimError::Span(format!(
            "t_end must be positive and finite, got {t_end}"
        )));
    }
    if !(dt.is_finite() && dt > 0.0 && dt <= t_end) {
        return Err(SimError::Span(format!(
            "the output step must be in (0, t_end], got {dt}"
        )));
    }
    Ok(())
}

/// Integrates `rhs` from (0, x0) to `t_end` by Dormand-Prince 5(4) and
/// returns the dense-output samples at 0, dt, 2 dt, ... reached, with the
/// error that ended the run early, if any (the samples before it are kept
/// so that callers can report them).
pub(crate) fn sampled<S: OdeState>(
    rhs: &mut impl FnMut(f64, &S) -> Result<S, SimError>,
    x0: S,
    t_end: f64,
    dt: f64,
    tol: Tolerances,
) -> (Vec<(f64, S)>, Option<SimError>) {
    let n_out = (t_end / dt).round() as usize;
    let mut samples = vec![(0.0, x0)];
    let mut next = 1usize;
    let mut ode = Dopri5::new(0.0, x0, tol);
    let run = ode.run(rhs, t_end, |step| {
        while next <= n_out {
            let ts = (next as f64 * dt).min(t_end);
            if ts > step.t0 + step.h + 1e-12 {
                break;
            }
            samples.push((ts, step.at(ts)));
            next += 1;
        }
        true
    });
    let failure = match run {
        Ok(()) => None,
        Err(OdeError::Rhs(e)) => Some(e),
        Err(OdeError::StepSizeCollapsed { t, h }) => Some(SimError::StepSizeCollapsed { t, h }),
        Err(OdeError::TooManySteps { t }) => Some(SimError::TooManySteps { t }),
    };
    (samples, failure)
}
