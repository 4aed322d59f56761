//! Effects that start and stop: an encoder that slips at t0 and keeps the
//! offset, a tool inside a medium for a while, a payload picked up at t1
//! and put down at t2. Such an effect is its ordinary columns times the
//! indicator of a window `[a, b)`.
//!
//! The window is found from the gap's time structure: a change-point
//! search over every pair of fit rows (`search`: the one-column fit of the
//! candidate's first column, a payload's mass, on `[a, b)` from prefix
//! sums, so all pairs cost little; a long record's over blocks of rows
//! first, then at the row), then refined at the full sample rate
//! (`refine`: each edge where the residual crosses the fitted step, within
//! a row spacing); every column of the candidate is then refitted on the
//! window's rows (a payload's first moments go in and out with its
//! mass). The windowed fit is
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

use nalgebra::{DMatrix, DVector, SVector};

use super::one::Fit;
use crate::diagnose::candidates::{linear_columns, whitened, Candidate, Prepared};
use crate::diagnose::numeric::{aicc, constrained_least_squares};
use crate::diagnose::Options;
use crate::effects::Window;
use search::outside_absent;

/// The candidates found limited in time, with their training windows.
pub type Windows = Vec<(Candidate, Window)>;

/// Whether a candidate may be limited in time: the effects that start and
/// stop in practice (an encoder slip, a medium, a payload with or without
/// its centre of mass).
pub fn windowable(c: Candidate) -> bool {
    matches!(
        c,
        Candidate::EncoderOffset(_)
            | Candidate::Payload
            | Candidate::PayloadCom(_)
            | Candidate::Environment(_)
    )
}

/// The sign the first parameter of windowed candidate `c` keeps in the
/// window search (`Some(1.0)`: >= 0). A payload picked up adds mass: a
/// window of negative mass (part of the robot absent for a while) is not
/// a thing that happens, although a payload on all the time may be
/// negative relative to the model (`columns::lower_bounds`). Others keep
/// their parameter's own constraint.
fn window_sign(c: Candidate) -> Option<f64> {
    match c {
        Candidate::Payload | Candidate::PayloadCom(_) => Some(1.0),
        _ => c
            .linear_parameters()
            .first()
            .and_then(|q| q.1.then_some(1.0)),
    }
}

/// The whitened column of a candidate's first parameter on the rows of
/// `p`: the column the window is searched on (a payload's mass; its first
/// moments follow the mass in and out of the window).
fn main_column<const N: usize>(c: Candidate, p: &Prepared<N>) -> Vec<f64> {
    whitened(p, |k| c.columns(&p.sig, &p.basis, k)[0])
}

/// The rows of `p` inside `w`, as a 0/1 mask over the whitened values.
pub fn inside<const N: usize>(p: &Prepared<N>, w: &Window) -> Vec<f64> {
    p.rows
        .iter()
        .flat_map(|&k| std::iter::repeat_n(if w.contains(p.sig.t[k]) { 1.0 } else { 0.0 }, N))
        .collect()
}

/// The windowed fit of a linear candidate on `p`, if it beats the
/// ordinary fit `f` (see the module's rule); the window in seconds. The
/// window is searched on the candidate's first column; every column of
/// the candidate is then refitted on the window's rows (a payload's mass
/// and first moments together).
pub fn fit_windowed<const N: usize>(
    f: &Fit,
    p: &Prepared<N>,
    margin: f64,
) -> Option<(Fit, Window)> {
    let c = f.candidate;
    let params = c.linear_parameters();
    if !windowable(c) || params.is_empty() || !f.sse.is_finite() {
        return None;
    }
    let x = main_column(c, p);
    let y = whitened(p, |k| p.sig.residual[k]);
    let sign = window_sign(c);
    let found = search::<N>(&x, &y, sign)?;
    if !outside_absent(&found, margin) {
        return None;
    }
    let w = refine(c, p, &found);
    // Refit every column on the refined window's rows.
    let m = inside(p, &w);
    let cols = if params.len() == 1 {
        vec![x]
    } else {
        linear_columns(c, p)
    };
    let n = p.n();
    let xm = DMatrix::from_fn(n, cols.len(), |r, i| m[r] * cols[i][r]);
    if xm.column(0).norm_squared() <= 0.0 {
        return None;
    }
    let nonneg: Vec<bool> = params.iter().map(|q| q.1).collect();
    let g = constrained_least_squares(&xm, &DVector::from_vec(y), &nonneg);
    let theta = g.theta.first().copied().unwrap_or(0.0);
    if theta == 0.0 || sign.is_some_and(|s| theta * s < 0.0) {
        return None;
    }
    let k = f.k + 2;
    if aicc(g.sse, n, k) > aicc(f.sse, n, f.k) - margin {
        return None;
    }
    Some((
        Fit {
            theta: g.theta,
            std: g.std,
            sse: g.sse,
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
    holdout_window_in(c, h, theta, &whitened(h, |k| h.sig.residual[k]))
}

/// [`holdout_window`] searched on the whitened residual `y` over the fit
/// rows of `h` (the residual other effects leave, where they are known).
pub fn holdout_window_in<const N: usize>(
    c: Candidate,
    h: &Prepared<N>,
    theta: f64,
    y: &[f64],
) -> Option<Window> {
    if c.linear_parameters().is_empty() {
        return None;
    }
    let x = main_column(c, h);
    if x.len() != y.len() {
        return None;
    }
    let sign = if theta >= 0.0 { 1.0 } else { -1.0 };
    let found = search::<N>(&x, y, Some(sign))?;
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

/// [`corrected`] at the rows of `h` only, one entry a row: the same
/// values, the columns made at the rows alone.
pub fn corrected_rows<const N: usize>(
    f: &Fit,
    h: &Prepared<N>,
    windows: &Windows,
) -> Vec<SVector<f64, N>> {
    if window_of(windows, f.candidate).is_none() {
        return f.corrected_rows(h);
    }
    let theta = f.theta.first().copied().unwrap_or(0.0);
    let w = holdout_window(f.candidate, h, theta);
    h.rows
        .iter()
        .map(|&k| corrected_in_at(f, h, w, k))
        .collect()
}

/// Sample `k` of [`corrected_in`].
fn corrected_in_at<const N: usize>(
    f: &Fit,
    p: &Prepared<N>,
    w: Option<Window>,
    k: usize,
) -> SVector<f64, N> {
    let mut r = p.sig.residual[k];
    let (a, z) = p.sig.range;
    if w.is_some_and(|w| k >= a && k < z && w.contains(p.sig.t[k])) {
        let cols = f.candidate.columns(&p.sig, &p.basis, k);
        for (col, th) in cols.iter().zip(&f.theta) {
            r -= col * *th;
        }
    }
    r
}

/// The smoothed residual of `p` once windowed fit `f` is added within
/// window `w` (`None`: nowhere).
pub fn corrected_in<const N: usize>(
    f: &Fit,
    p: &Prepared<N>,
    w: Option<Window>,
) -> Vec<SVector<f64, N>> {
    let mut r = p.sig.residual.clone();
    if w.is_none() {
        return r;
    }
    let (a, z) = p.sig.range;
    for (k, rk) in r.iter_mut().enumerate().take(z).skip(a) {
        *rk = corrected_in_at(f, p, w, k);
    }
    r
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnose::candidates::Candidate;
    use crate::effects::Effect;
    use crate::synth::{synthesize, SynthOptions};
    use crate::test_robots::Arm2;

    /// A windowed fit's residual, made sample by sample at the rows, is the
    /// whole record's at the rows to the bit, inside and outside the window.
    #[test]
    fn a_windowed_residual_at_a_row_is_the_whole_records() {
        let robot = Arm2::default();
        let opts = SynthOptions {
            duration: 3.0,
            seed: 13,
            ..Default::default()
        };
        let effects = [Effect::ViscousFriction { joint: 0, fv: 0.3 }];
        let m = synthesize(&robot, &effects, &opts).expect("a generated record");
        let p = Prepared::new(&robot, &m);
        let f = Fit {
            candidate: Candidate::Viscous(0),
            theta: vec![0.25],
            std: vec![0.0],
            motor: None,
            motor_std: None,
            sse: 0.0,
            k: 1,
        };
        let w = Window {
            start: 1.0,
            end: 2.0,
        };
        for w in [Some(w), None] {
            let whole = corrected_in(&f, &p, w);
            let mut inside = 0;
            for &k in &p.rows {
                let at = corrected_in_at(&f, &p, w, k);
                for j in 0..2 {
                    assert_eq!(at[j].to_bits(), whole[k][j].to_bits(), "sample {k}");
                }
                if w.is_some_and(|w| w.contains(p.sig.t[k])) && at != p.sig.residual[k] {
                    inside += 1;
                }
            }
            assert_eq!(inside > 10, w.is_some(), "{inside}");
        }
    }
}
