//! Pieces shared by the dissertation's scenarios of sec. 3.2-3.4: dense sampling
//! of an adaptive Dormand-Prince run whose state carries more than a
//! robot's (q, qd) (work integrals), and the CSV of an N-joint motion.

use std::path::Path;

use dynamics_runtime::ode::{Dopri5, OdeError, OdeState, Tolerances};
use dynamics_runtime::{Robot, SimError, Trajectory};

use super::{io, write, ScenarioError};

/// The trajectory as `<name>.csv` in the trajectory CSV format (docs/cli.md).
pub(crate) fn trajectory_csv<R: Robot<N>, const N: usize>(
    name: &str,
    tr: &Trajectory<N>,
    dir: &Path,
) -> Result<(), ScenarioError> {
    let mut csv = Vec::new();
    tr.write_csv(&mut csv, &R::JOINT_NAMES)
        .map_err(|e| io(dir, e))?;
    write(dir, &format!("{name}.csv"), &String::from_utf8_lossy(&csv))
}

/// Integrates `rhs` from `(t0, x0)` to `t_end`, returning the dense-output
/// samples at `t0 + k dt` (the start included) and the final state.
pub(crate) fn sample<S: OdeState>(
    rhs: &mut impl FnMut(f64, &S) -> Result<S, SimError>,
    t0: f64,
    x0: S,
    t_end: f64,
    dt: f64,
    tol: Tolerances,
) -> Result<Vec<(f64, S)>, SimError> {
    let n_out = ((t_end - t0) / dt).round() as usize;
    let mut out = vec![(t0, x0)];
    let mut next = 1usize;
    let mut ode = Dopri5::new(t0, x0, tol);
    ode.run(rhs, t_end, |step| {
        while next <= n_out {
            let ts = (t0 + next as f64 * dt).min(t_end);
            if ts > step.t0 + step.h + 1e-12 {
                break;
            }
            out.push((ts, step.at(ts)));
            next += 1;
        }
        true
    })
    .map_err(sim_error)?;
    Ok(out)
}

/// The runtime's error for an integrator failure.
pub(crate) fn sim_error(e: OdeError<SimError>) -> SimError {
    match e {
        OdeError::Rhs(e) => e,
        OdeError::StepSizeCollapsed { t, h } => SimError::StepSizeCollapsed { t, h },
        OdeError::TooManySteps { t } => SimError::TooManySteps { t },
    }
}
