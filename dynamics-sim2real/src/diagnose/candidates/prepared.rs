//! One data set made ready for fitting candidates: its signals, the
//! column cache every candidate's columns come from, the rows a fit uses
//! and the sensors' noise levels behind the floor.

use std::sync::Arc;

use nalgebra::SVector;

use super::basis::Basis;
use crate::data::Measured;
use crate::diagnose::signals::Signals;
use dynamics_runtime::Robot;

/// A data set ready for fitting: signals, shared model quantities, and the
/// (decimated) sample rows the fit uses.
#[derive(Debug, Clone)]
pub struct Prepared<const N: usize> {
    /// Signals.
    pub sig: Signals<N>,
    /// Shared quantities (never changed once made: shared, not copied,
    /// by copies of the record).
    pub basis: Arc<Basis<N>>,
    /// Sample indices used as rows (every half-window, away from the edges).
    pub rows: Vec<usize>,
    /// Sensor noise levels per joint (q, qd, tau; stated, or estimated
    /// from the data) behind the noise floor and the prediction yardstick.
    pub levels: [SVector<f64, N>; 3],
    /// Samples the model is evaluated at a time along the record
    /// ([`Options::chunk`](crate::diagnose::Options::chunk)).
    pub chunk: usize,
}

impl<const N: usize> Prepared<N> {
    /// Prepares `m` for `robot`.
    pub fn new<R: Robot<N> + Clone + Send + Sync + 'static>(robot: &R, m: &Measured<N>) -> Self {
        Self::with_noise(robot, m, None)
    }

    /// Prepares `m` for `robot`; the torque residual's noise floor is what
    /// sensor noise of `levels` (q, qd, tau per joint) makes of it, the
    /// levels estimated from the data when not known (`noise.rs`).
    pub fn with_noise<R: Robot<N> + Clone + Send + Sync + 'static>(
        robot: &R,
        m: &Measured<N>,
        levels: Option<&[SVector<f64, N>; 3]>,
    ) -> Self {
        Self::chunked(robot, m, levels, 0)
    }

    /// [`Prepared::with_noise`], the model evaluated along the record
    /// `chunk` samples at a time (0: the default; the result does not
    /// depend on it).
    ///
    /// ```
    /// use dynamics_runtime::Robot;
    /// use dynamics_sim2real::data::Measured;
    /// use dynamics_sim2real::diagnose::Prepared;
    /// fn ready<R: Robot<3> + Clone + Send + Sync + 'static>(robot: &R, m: &Measured<3>) -> Prepared<3> {
    ///     Prepared::chunked(robot, m, None, 512)
    /// }
    /// ```
    pub fn chunked<R: Robot<N> + Clone + Send + Sync + 'static>(
        robot: &R,
        m: &Measured<N>,
        levels: Option<&[SVector<f64, N>; 3]>,
        chunk: usize,
    ) -> Self {
        let (sig, levels) = Signals::new(robot, m, levels, chunk);
        Self::of_signals(robot, sig, levels, chunk)
    }

    /// [`Prepared::chunked`] on a record handed over, which the signals
    /// share ([`Signals::shared`]) rather than copy what they read of it.
    pub(crate) fn shared<R: Robot<N> + Clone + Send + Sync + 'static>(
        robot: &R,
        m: &Arc<Measured<N>>,
        levels: Option<&[SVector<f64, N>; 3]>,
        chunk: usize,
    ) -> Self {
        let (sig, levels) = Signals::shared(robot, m, levels, chunk);
        Self::of_signals(robot, sig, levels, chunk)
    }

    /// The rows and the column cache of `sig`.
    fn of_signals<R: Robot<N> + Clone + Send + Sync + 'static>(
        robot: &R,
        sig: Signals<N>,
        levels: [SVector<f64, N>; 3],
        chunk: usize,
    ) -> Self {
        let h = sig.sg.half();
        let (a, z) = sig.range;
        let rows: Vec<usize> = (a + h..z.saturating_sub(h))
            .step_by(h.max(1))
            .filter_map(|k| row_near(&sig, k, h))
            .collect();
        let basis = Arc::new(Basis::new(robot, &sig, &rows, chunk));
        Prepared {
            sig,
            basis,
            rows,
            levels,
            chunk,
        }
    }

    /// Whitened residual sum of squares of `r` over the rows.
    pub fn sse(&self, r: &[SVector<f64, N>]) -> f64 {
        self.rows
            .iter()
            .map(|&k| {
                (0..N)
                    .map(|j| (r[k][j] / self.sig.floor[j]).powi(2))
                    .sum::<f64>()
            })
            .sum()
    }

    /// [`Prepared::sse`] of `r` given at the rows (one entry a row, in
    /// their order).
    pub fn sse_rows(&self, r: &[SVector<f64, N>]) -> f64 {
        r.iter()
            .take(self.rows.len())
            .map(|v| {
                (0..N)
                    .map(|j| (v[j] / self.sig.floor[j]).powi(2))
                    .sum::<f64>()
            })
            .sum()
    }

    /// RMS of joint `j` of `r` over the rows in use.
    pub fn rms(&self, r: &[SVector<f64, N>], j: usize) -> f64 {
        let s: f64 = self.rows.iter().map(|&k| r[k][j].powi(2)).sum();
        (s / self.rows.len().max(1) as f64).sqrt()
    }

    /// [`Prepared::rms`] of `r` given at the rows (one entry a row, in
    /// their order).
    pub fn rms_rows(&self, r: &[SVector<f64, N>], j: usize) -> f64 {
        let s: f64 = r.iter().take(self.rows.len()).map(|v| v[j].powi(2)).sum();
        (s / self.rows.len().max(1) as f64).sqrt()
    }

    /// The largest ratio over the joints of the torque residual's RMS to
    /// its noise floor.
    pub fn gap_ratio(&self) -> f64 {
        (0..N)
            .map(|j| self.rms(&self.sig.residual, j) / self.sig.floor[j])
            .fold(0.0, f64::max)
    }

    /// Number of scalar rows.
    pub fn n(&self) -> usize {
        self.rows.len() * N
    }
}

/// The usable sample nearest after `k` within a row spacing, if any (a
/// row skips a filled sample but not a whole stretch of them).
fn row_near<const N: usize>(sig: &Signals<N>, k: usize, h: usize) -> Option<usize> {
    (k..k + h.max(1)).find(|&i| sig.mask.usable(i))
}
