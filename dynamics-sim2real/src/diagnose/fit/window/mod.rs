//! Effects that start and stop: an encoder that slips at t0 and keeps the
//! offset, a tool inside a medium for a while, a payload picked up at t1
//! and put down at t2. Such an effect is its ordinary column times the
//! indicator of a window `[a, b)`.
//!
//! The window is found from the gap's time structure: a change-point
//! search over every pair of fit rows (`search`: the one-column fit of the
//! column on `[a, b)` from prefix sums, so all pairs cost little), then
//! refined at the full sample rate (`refine`: each edge where the residual
//! crosses the fitted step, within a row spacing). The windowed fit is
//! judged by the same information criterion as the ordinary one with the
//! window's two bounds counted as parameters, and must beat it by
//! [`Options::nesting_margin`]; besides, the effect outside the window
//! must be absent (a fit of the column there is either insignificant or
//! small against the fit inside), so that an effect on all the time keeps
//! its ordinary candidate. The held-out check finds the window on the
//! held-out data by the same search, the sign taken from the training fit
//! (never the training window's times).

mod search;

use search::{refine, search};

use nalgebra::SVector;

use super::one::Fit;
use crate::diagnose::candidates::{linear_columns, whitened, Candidate, Prepared};
use crate::diagnose::numeric::aicc;
use crate::diagnose::Options;
use crate::effects::Window;
use search::outside_absent;

/// The candidates found limited in time, with their training windows.
pub type Windows = Vec<(Candidate, Window)>;

/// Whether a candidate may be limited in time: the effects that start and
/// stop in practice (an encoder slip, a medium, a payload).
pub fn windowable(c: Candidate) -> bool {
    matches!(
        c,
        Candidate::EncoderOffset(_) | Candidate::Payload | Candidate::Environment(_)
    )
}

/// The rows of `p` inside `w`, as a 0/1 mask over the whitened values.
pub fn inside<const N: usize>(p: &Prepared<N>, w: &Window) -> Vec<f64> {
    p.rows
        .iter()
        .flat_map(|&k| std::iter::repeat_n(if w.contains(p.sig.t[k]) { 1.0 } else { 0.0 }, N))
        .collect()
}

/// The windowed fit of a one-column candidate on `p`, if it beats the
/// ordinary fit `f` (see the module's rule); the window in seconds.
pub fn fit_windowed<const N: usize>(
    f: &Fit,
    p: &Prepared<N>,
    margin: f64,
) -> Option<(Fit, Window)> {
    let c = f.candidate;
    let params = c.linear_parameters();
    if !windowable(c) || params.len() != 1 || !f.sse.is_finite() {
        return None;
    }
    let x = linear_columns(c, p).pop()?;
    let y = whitened(p, |k| p.sig.residual[k]);
    let sign = params[0].1.then_some(1.0);
    let found = search::<N>(&x, &y, sign)?;
    if !outside_absent(&found, margin) {
        return None;
    }
    let w = refine(c, p, &found);
    // Refit on the refined window's rows.
    let m = inside(p, &w);
    let (mut s, mut cc) = (0.0, 0.0);
    for i in 0..x.len() {
        s += m[i] * x[i] * y[i];
        cc += m[i] * x[i] * x[i];
    }
    if cc <= 0.0 {
        return None;
    }
    let theta = s / cc;
    if sign.is_some_and(|g| theta * g < 0.0) {
        return None;
    }
    let yy: f64 = y.iter().map(|v| v * v).sum();
    let sse = (yy - s * s / cc).max(0.0);
    let n = p.n();
    let k = f.k + 2;
    if aicc(sse, n, k) > aicc(f.sse, n, f.k) - margin {
        return None;
    }
    let dof = (n as f64 - k as f64).max(1.0);
    Some((
        Fit {
            theta: vec![theta],
            std: vec![(sse / dof / cc).sqrt()],
            sse,
            k,
            ..f.clone()
        },
        w,
    ))
}

/// Every fit limited to its window where the windowed fit wins (the
/// module's rule), and the windows found.
pub fn windowed<const N: usize>(
    fits: Vec<Fit>,
    p: &Prepared<N>,
    options: &Options,
) -> (Vec<Fit>, Windows) {
    let mut windows = Windows::new();
    let fits = fits
        .into_iter()
        .map(|f| match fit_windowed(&f, p, options.nesting_margin) {
            Some((g, w)) => {
                windows.push((g.candidate, w));
                g
            }
            None => f,
        })
        .collect();
    (fits, windows)
}

/// The training window of candidate `c`, if it is limited in time.
pub fn window_of(windows: &Windows, c: Candidate) -> Option<Window> {
    windows.iter().find(|w| w.0 == c).map(|w| w.1)
}

/// The held-out window of windowed candidate `c` (trained coefficient
/// `theta`): the same search on the held-out rows, the sign of the
/// training fit kept.
pub fn holdout_window<const N: usize>(c: Candidate, h: &Prepared<N>, theta: f64) -> Option<Window> {
    let x = linear_columns(c, h).pop()?;
    let y = whitened(h, |k| h.sig.residual[k]);
    let sign = if theta >= 0.0 { 1.0 } else { -1.0 };
    let found = search::<N>(&x, &y, Some(sign))?;
    Some(refine(c, h, &found))
}

/// The smoothed residual of `h` once fit `f` is added, limited to the
/// held-out window found by [`holdout_window`] when `f` is windowed (no
/// window found there: the effect is taken as absent).
pub fn corrected<const N: usize>(
    f: &Fit,
    h: &Prepared<N>,
    windows: &Windows,
) -> Vec<SVector<f64, N>> {
    if window_of(windows, f.candidate).is_none() {
        return f.corrected(h);
    }
    let theta = f.theta.first().copied().unwrap_or(0.0);
    corrected_in(f, h, holdout_window(f.candidate, h, theta))
}

/// The smoothed residual of `p` once windowed fit `f` is added within
/// window `w` (`None`: nowhere).
pub fn corrected_in<const N: usize>(
    f: &Fit,
    p: &Prepared<N>,
    w: Option<Window>,
) -> Vec<SVector<f64, N>> {
    let theta = f.theta.first().copied().unwrap_or(0.0);
    let mut r = p.sig.residual.clone();
    let Some(w) = w else { return r };
    let (a, z) = p.sig.range;
    for (k, rk) in r.iter_mut().enumerate().take(z).skip(a) {
        if w.contains(p.sig.t[k]) {
            *rk -= f.candidate.columns(&p.sig, &p.basis, k)[0] * theta;
        }
    }
    r
}
