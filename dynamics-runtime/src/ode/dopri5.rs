//! Adaptive Dormand-Prince 5(4) with error control, dense output and events.

use super::tableau::{A, B, C, D, E};
use super::OdeState;

/// Tolerances and limits of [`Dopri5`].
///
/// ```
/// use dynamics_runtime::ode::Tolerances;
/// // Tighter than the default, and never a step longer than 1 ms.
/// let tol = Tolerances { rtol: 1e-10, atol: 1e-12, h_max: 1e-3, ..Default::default() };
/// assert_eq!(tol.max_steps, Tolerances::default().max_steps);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tolerances {
    /// Relative tolerance.
    pub rtol: f64,
    /// Absolute tolerance.
    pub atol: f64,
    /// Smallest step before the integration is declared stuck.
    pub h_min: f64,
    /// Largest step.
    pub h_max: f64,
    /// Most steps in one call.
    pub max_steps: usize,
}

impl Default for Tolerances {
    fn default() -> Self {
        Tolerances {
            rtol: 1e-8,
            atol: 1e-10,
            h_min: 1e-12,
            h_max: f64::INFINITY,
            max_steps: 10_000_000,
        }
    }
}

/// Why an adaptive integration stopped early.
///
/// ```
/// use dynamics_runtime::ode::{Dopri5, OdeError, Tolerances};
/// use nalgebra::Vector1;
/// // x' = x^2 from x(0) = 1 blows up at t = 1.
/// let mut f = |_t: f64, x: &Vector1<f64>| Ok::<_, ()>(x.component_mul(x));
/// let mut ode = Dopri5::new(0.0, Vector1::new(1.0), Tolerances::default());
/// match ode.run(&mut f, 2.0, |_| true) {
///     Err(OdeError::StepSizeCollapsed { t, .. }) => assert!((t - 1.0).abs() < 1e-3),
///     other => panic!("{other:?}"),
/// }
/// ```
#[derive(Debug, Clone, PartialEq)]
pub enum OdeError<E> {
    /// The right-hand side failed.
    Rhs(E),
    /// The step size fell below `h_min` at time `t`.
    StepSizeCollapsed {
        /// Time.
        t: f64,
        /// The step size tried.
        h: f64,
    },
    /// More than `max_steps` steps.
    TooManySteps {
        /// Time reached.
        t: f64,
    },
}

/// One accepted step with its dense output.
///
/// ```
/// use dynamics_runtime::ode::{Dopri5, Tolerances};
/// use nalgebra::Vector1;
/// // x' = cos t: dense output inside every step matches sin t.
/// let mut f = |t: f64, _x: &Vector1<f64>| Ok::<_, ()>(Vector1::new(t.cos()));
/// let mut ode = Dopri5::new(0.0, Vector1::new(0.0), Tolerances::default());
/// let mut worst = 0.0f64;
/// ode.run(&mut f, 2.0, |step| {
///     let mid = step.t0 + 0.5 * step.h;
///     worst = worst.max((step.at(mid)[0] - mid.sin()).abs());
///     true
/// }).unwrap();
/// assert!(worst < 1e-6);
/// ```
#[derive(Debug, Clone, Copy)]
pub struct Step<S> {
    /// Start time.
    pub t0: f64,
    /// Step size.
    pub h: f64,
    /// State at t0.
    pub y0: S,
    /// State at t0 + h.
    pub y1: S,
    r2: S,
    r3: S,
    r4: S,
    r5: S,
}

impl<S: OdeState> Step<S> {
    /// The continuous extension (order 4) at `t` in [t0, t0 + h].
    pub fn at(&self, t: f64) -> S {
        let th = if self.h == 0.0 {
            1.0
        } else {
            (t - self.t0) / self.h
        };
        let th1 = 1.0 - th;
        // y0 + th (r2 + th1 (r3 + th (r4 + th1 r5)))
        let inner = self.r4.axpy(th1, &self.r5);
        let inner = self.r3.axpy(th, &inner);
        let inner = self.r2.axpy(th1, &inner);
        self.y0.axpy(th, &inner)
    }
}

/// The integrator's state between calls.
///
/// ```
/// use dynamics_runtime::ode::{Dopri5, Tolerances};
/// use nalgebra::Vector2;
/// // Harmonic oscillator x'' = -x from (1, 0): x(t) = cos t.
/// let mut f = |_t: f64, y: &Vector2<f64>| Ok::<_, ()>(Vector2::new(y[1], -y[0]));
/// let mut ode = Dopri5::new(0.0, Vector2::new(1.0, 0.0), Tolerances { rtol: 1e-10, atol: 1e-12, ..Default::default() });
/// let mut last = 0.0;
/// ode.run(&mut f, 3.0, |step| { last = step.at(step.t0 + step.h)[0]; true }).unwrap();
/// assert!((last - 3.0f64.cos()).abs() < 1e-9);
/// ```
pub struct Dopri5<S> {
    t: f64,
    y: S,
    h: f64,
    k1: Option<S>,
    tol: Tolerances,
}

impl<S: OdeState> Dopri5<S> {
    /// Starts at (t0, y0).
    pub fn new(t0: f64, y0: S, tol: Tolerances) -> Self {
        Dopri5 {
            t: t0,
            y: y0,
            h: 0.0,
            k1: None,
            tol,
        }
    }

    /// Current time.
    pub fn t(&self) -> f64 {
        self.t
    }

    /// Current state.
    pub fn y(&self) -> &S {
        &self.y
    }

    /// Restarts from a new state at the current time (after an event).
    pub fn reset(&mut self, y: S) {
        self.y = y;
        self.k1 = None;
    }

    /// Integrates to `t_end`, calling `on_step` after every accepted step;
    /// `on_step` returning false stops the run at that step.
    pub fn run<E>(
        &mut self,
        f: &mut impl FnMut(f64, &S) -> Result<S, E>,
        t_end: f64,
        mut on_step: impl FnMut(&Step<S>) -> bool,
    ) -> Result<(), OdeError<E>> {
        let mut k1 = match self.k1 {
            Some(k) => k,
            None => f(self.t, &self.y).map_err(OdeError::Rhs)?,
        };
        if self.h == 0.0 {
            self.h = self.initial_step(&k1, t_end);
        }
        let mut steps = 0;
        while self.t < t_end {
            steps += 1;
            if steps > self.tol.max_steps {
                return Err(OdeError::TooManySteps { t: self.t });
            }
            let h = self.h.min(t_end - self.t).min(self.tol.h_max);
            let mut k = [k1; 7];
            for s in 1..7 {
                let mut ys = self.y;
                for (j, kj) in k.iter().enumerate().take(s) {
                    if A[s][j] != 0.0 {
                        ys = ys.axpy(h * A[s][j], kj);
                    }
                }
                k[s] = f(self.t + C[s] * h, &ys).map_err(OdeError::Rhs)?;
            }
            let mut y1 = self.y;
            let mut err = S::zero();
            for s in 0..7 {
                if B[s] != 0.0 {
                    y1 = y1.axpy(h * B[s], &k[s]);
                }
                if E[s] != 0.0 {
                    err = err.axpy(h * E[s], &k[s]);
                }
            }
            let e = S::error_norm(&err, &self.y, &y1, self.tol.rtol, self.tol.atol);
            let finite = y1.first_non_finite().is_none() && e.is_finite();
            if finite && e <= 1.0 {
                let ydiff = y1.axpy(-1.0, &self.y);
                let bspl = S::zero().axpy(h, &k[0]).axpy(-1.0, &ydiff);
                let r4 = ydiff.axpy(-h, &k[6]).axpy(-1.0, &bspl);
                let mut r5 = S::zero();
                for s in 0..7 {
                    if D[s] != 0.0 {
                        r5 = r5.axpy(h * D[s], &k[s]);
                    }
                }
                let step = Step {
                    t0: self.t,
                    h,
                    y0: self.y,
                    y1,
                    r2: ydiff,
                    r3: bspl,
                    r4,
                    r5,
                };
                self.t += h;
                self.y = y1;
                k1 = k[6];
                self.k1 = Some(k1);
                let fac = if e == 0.0 {
                    5.0
                } else {
                    (0.9 * e.powf(-0.2)).clamp(0.2, 5.0)
                };
                self.h = h * fac;
                if !on_step(&step) {
                    return Ok(());
                }
            } else {
                let fac = if finite {
                    (0.9 * e.powf(-0.2)).clamp(0.1, 0.9)
                } else {
                    0.1
                };
                self.h = h * fac;
                if self.h < self.tol.h_min {
                    return Err(OdeError::StepSizeCollapsed {
                        t: self.t,
                        h: self.h,
                    });
                }
            }
        }
        Ok(())
    }

    fn initial_step(&self, k1: &S, t_end: f64) -> f64 {
        let d = S::error_norm(k1, &self.y, &self.y, self.tol.rtol, self.tol.atol);
        let h = if d > 1e-10 { 0.01 / d } else { 1e-3 };
        h.min((t_end - self.t).abs().max(1e-12)).min(self.tol.h_max)
    }
}

/// Locates a sign change of `g` on a step's dense output, to `tol` in time
/// (Illinois variant of regula falsi). `g0` and `g1` are g at the ends.
///
/// ```
/// use dynamics_runtime::ode::{locate_event, Dopri5, Tolerances};
/// use nalgebra::Vector2;
/// // A ball thrown up at 5 m/s: when does it come back to the ground?
/// let mut f = |_t: f64, y: &Vector2<f64>| Ok::<_, ()>(Vector2::new(y[1], -9.81));
/// let mut ode = Dopri5::new(0.0, Vector2::new(0.0, 5.0), Tolerances::default());
/// let mut height = |_t: f64, y: &Vector2<f64>| y[0];
/// let mut landing = None;
/// ode.run(&mut f, 2.0, |step| {
///     let (g0, g1) = (step.y0[0], step.y1[0]);
///     if step.t0 > 0.0 && g0 > 0.0 && g1 <= 0.0 {
///         landing = Some(locate_event(step, &mut height, g0, g1, 1e-12));
///         return false;
///     }
///     true
/// }).unwrap();
/// assert!((landing.unwrap() - 2.0 * 5.0 / 9.81).abs() < 1e-9);
/// ```
pub fn locate_event<S: OdeState>(
    step: &Step<S>,
    g: &mut impl FnMut(f64, &S) -> f64,
    g0: f64,
    g1: f64,
    tol: f64,
) -> f64 {
    let (mut a, mut b) = (step.t0, step.t0 + step.h);
    let (mut ga, mut gb) = (g0, g1);
    let mut side = 0;
    for _ in 0..200 {
        if (b - a).abs() <= tol {
            break;
        }
        let mut t = (a * gb - b * ga) / (gb - ga);
        if !(t > a && t < b) {
            t = 0.5 * (a + b);
        }
        let gt = g(t, &step.at(t));
        if gt == 0.0 {
            return t;
        }
        if (gt > 0.0) == (gb > 0.0) {
            b = t;
            gb = gt;
            if side == -1 {
                ga *= 0.5;
            }
            side = -1;
        } else {
            a = t;
            ga = gt;
            if side == 1 {
                gb *= 0.5;
            }
            side = 1;
        }
    }
    0.5 * (a + b)
}
