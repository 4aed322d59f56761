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

use nalgebra::{DVector, SVector};

use super::analysis::{Fit, Prepared};
use super::candidate::Candidate;
use super::compound::Explanation;
use super::explain::Holdout;
use super::fit::aicc;
use super::pool::{linear_columns, whitened, Pool};
use super::report::{EffectWindow, Explained};
use super::Options;
use crate::effects::Window;

/// Fewest fit rows inside a window, and outside it.
const MIN_ROWS: usize = 4;
/// The effect fitted outside the window must stay below this share of the
/// fit inside (or be insignificant).
const OUTSIDE_SHARE: f64 = 0.2;

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

/// A window found by the search, in rows of the fit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Found {
    /// First row inside.
    pub first: usize,
    /// One past the last row inside.
    pub last: usize,
    /// The column's coefficient inside.
    pub theta: f64,
    /// Whitened SSE gained inside.
    pub gain: f64,
    /// Whitened SSE a free coefficient outside would gain.
    pub outside_gain: f64,
    /// That coefficient.
    pub outside_theta: f64,
}

/// The best window of column `x` against `y` (both whitened, `n` values a
/// row): every pair of rows `[first, last)` with at least [`MIN_ROWS`]
/// inside and outside; the coefficient's sign kept to `sign` when given
/// (`Some(1.0)`: >= 0).
pub fn search<const N: usize>(x: &[f64], y: &[f64], sign: Option<f64>) -> Option<Found> {
    let rows = x.len() / N;
    if rows < 2 * MIN_ROWS {
        return None;
    }
    let (mut a, mut b) = (vec![0.0; rows + 1], vec![0.0; rows + 1]);
    for r in 0..rows {
        let (mut s, mut c) = (0.0, 0.0);
        for j in 0..N {
            s += x[r * N + j] * y[r * N + j];
            c += x[r * N + j] * x[r * N + j];
        }
        a[r + 1] = a[r] + s;
        b[r + 1] = b[r] + c;
    }
    let (sa, sb) = (a[rows], b[rows]);
    let mut best: Option<Found> = None;
    for first in 0..=rows - MIN_ROWS {
        for last in first + MIN_ROWS..=rows {
            // A window, not the whole record.
            if rows - (last - first) < MIN_ROWS {
                continue;
            }
            let (s, c) = (a[last] - a[first], b[last] - b[first]);
            if c <= 0.0 {
                continue;
            }
            let theta = s / c;
            if sign.is_some_and(|g| theta * g < 0.0) {
                continue;
            }
            let gain = s * s / c;
            if best.is_none_or(|f| gain > f.gain) {
                let (so, co) = (sa - s, sb - c);
                let (outside_theta, outside_gain) = if co > 0.0 {
                    (so / co, so * so / co)
                } else {
                    (0.0, 0.0)
                };
                best = Some(Found {
                    first,
                    last,
                    theta,
                    gain,
                    outside_gain,
                    outside_theta,
                });
            }
        }
    }
    best
}

/// Whether a found window is a window at all: its effect outside is
/// absent (insignificant against `margin`, or small against inside).
fn outside_absent(f: &Found, margin: f64) -> bool {
    f.outside_gain < margin || f.outside_theta.abs() <= OUTSIDE_SHARE * f.theta.abs()
}

/// The per-sample column of linear candidate `c` on `p` (its first
/// parameter), whitened, and the whitened residual, at sample `k`.
fn sample<const N: usize>(
    c: Candidate,
    p: &Prepared<N>,
    k: usize,
) -> (SVector<f64, N>, SVector<f64, N>) {
    let col = c.columns(&p.sig, &p.basis, k)[0];
    let x = SVector::from_fn(|j, _| {
        let v = col[j] / p.sig.floor[j];
        if v.is_finite() {
            v
        } else {
            0.0
        }
    });
    let y = SVector::from_fn(|j, _| {
        let v = p.sig.residual[k][j] / p.sig.floor[j];
        if v.is_finite() {
            v
        } else {
            0.0
        }
    });
    (x, y)
}

/// The sample in `(lo, hi]` where the step of size `theta` in column `c`
/// best starts (`rising`) or stops: the full-rate residual decides.
fn edge<const N: usize>(
    c: Candidate,
    p: &Prepared<N>,
    lo: usize,
    hi: usize,
    theta: f64,
    rising: bool,
) -> usize {
    // cost(s) = sum over k in [lo, hi) of |y - theta x [inside]|^2; inside
    // is k >= s when rising, k < s otherwise.
    let terms: Vec<f64> = (lo..hi)
        .map(|k| {
            let (x, y) = sample(c, p, k);
            if !p.sig.mask.usable(k) {
                return 0.0;
            }
            theta * theta * x.norm_squared() - 2.0 * theta * x.dot(&y)
        })
        .collect();
    let total: f64 = terms.iter().sum();
    let mut before = 0.0;
    let mut best = (f64::INFINITY, hi);
    for (i, s) in (lo..=hi).enumerate() {
        if i > 0 {
            before += terms[i - 1];
        }
        let cost = if rising { total - before } else { before };
        if s > lo && cost < best.0 {
            best = (cost, s);
        }
    }
    best.1
}

/// The window of a found one in seconds, its edges refined at the full
/// sample rate (an edge at the first or last row is the record's own).
pub fn refine<const N: usize>(c: Candidate, p: &Prepared<N>, f: &Found) -> Window {
    let rows = &p.rows;
    let z = p.sig.range.1;
    let t = &p.sig.t;
    // An edge at the first or last row is the record's own.
    let end_time = t.last().copied().unwrap_or(0.0) + p.sig.dt;
    let start = if f.first == 0 {
        t.first().copied().unwrap_or(0.0)
    } else {
        let (lo, hi) = (rows[f.first - 1], rows[f.first]);
        t[edge(c, p, lo, hi + 1, f.theta, true).min(z - 1)]
    };
    let end = if f.last >= rows.len() {
        end_time
    } else {
        let (lo, hi) = (rows[f.last - 1], rows[f.last]);
        t[edge(c, p, lo, hi + 1, f.theta, false).min(z - 1)]
    };
    Window { start, end }
}

/// The rows of `p` inside `w`, as a 0/1 mask over the whitened values.
fn inside<const N: usize>(p: &Prepared<N>, w: &Window) -> Vec<f64> {
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
pub fn of(windows: &Windows, c: Candidate) -> Option<Window> {
    windows.iter().find(|w| w.0 == c).map(|w| w.1)
}

/// The pool's columns of the windowed terms limited to their windows (two
/// more parameters each).
pub fn limit_pool<const N: usize>(pool: &mut Pool, windows: &Windows, p: &Prepared<N>) {
    for t in 0..pool.terms.len() {
        let Some(w) = of(windows, pool.terms[t].fit.candidate) else {
            continue;
        };
        if pool.terms[t].fixed.is_some() || pool.terms[t].link.is_some() {
            continue;
        }
        let m = DVector::from_vec(inside(p, &w));
        for &c in &pool.terms[t].cols.clone() {
            let col = pool.x.column(c).component_mul(&m);
            pool.x.set_column(c, &col);
            let v = pool.x.tr_mul(&pool.x.column(c));
            pool.gram.set_column(c, &v);
            pool.gram.set_row(c, &v.transpose());
            pool.xty[c] = pool.x.column(c).dot(&pool.y);
        }
        pool.terms[t].k += 2;
        pool.terms[t].fit.k = pool.terms[t].k;
    }
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
    if of(windows, f.candidate).is_none() {
        return f.corrected(h);
    }
    let theta = f.theta.first().copied().unwrap_or(0.0);
    let w = holdout_window(f.candidate, h, theta);
    let mut r = h.sig.residual.clone();
    let Some(w) = w else { return r };
    let (a, z) = h.sig.range;
    for (k, rk) in r.iter_mut().enumerate().take(z).skip(a) {
        if w.contains(h.sig.t[k]) {
            *rk -= f.candidate.columns(&h.sig, &h.basis, k)[0] * theta;
        }
    }
    r
}

/// The explanation's windowed effects limited to their held-out windows on
/// the held-out side (found there by the same search, the training fit's
/// sign kept).
pub fn limit_holdout<const N: usize>(
    hold: &mut Holdout<N>,
    h: &Prepared<N>,
    pool: &Pool,
    e: &Explanation,
    windows: &Windows,
) {
    for (i, &t) in e.set.iter().enumerate() {
        let c = pool.terms[t].fit.candidate;
        if of(windows, c).is_none() {
            continue;
        }
        let theta = e.sol.theta[i].first().copied().unwrap_or(0.0);
        let m = match holdout_window(c, h, theta) {
            Some(w) => DVector::from_vec(inside(h, &w)),
            None => DVector::zeros(h.n()),
        };
        for col in hold.free_mut(i) {
            col.component_mul_assign(&m);
        }
    }
}

/// The training windows on the report's entries of the explanation.
pub fn annotate(effects: &mut [Explained], pool: &Pool, e: &Explanation, windows: &Windows) {
    for (entry, &t) in effects.iter_mut().zip(&e.set) {
        if let Some(w) = of(windows, pool.terms[t].fit.candidate) {
            entry.window = Some(EffectWindow {
                start: w.start,
                end: w.end,
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A step column switched on between rows 30 and 70 of 100 is found
    /// there exactly; on all the time, the search's best window gains
    /// less over the whole record than its two bounds must earn.
    #[test]
    fn the_search_finds_the_rows_of_a_step() {
        let rows = 100;
        let x: Vec<f64> = (0..rows).map(|r| 1.0 + (r as f64 * 0.37).sin()).collect();
        let mut rng = crate::synth::Rng::new(3);
        let y: Vec<f64> = (0..rows)
            .map(|r| {
                let on = if (30..70).contains(&r) { 2.0 } else { 0.0 };
                on * x[r] + 0.1 * rng.normal()
            })
            .collect();
        let f = search::<1>(&x, &y, Some(1.0)).unwrap();
        assert_eq!((f.first, f.last), (30, 70));
        assert!((f.theta - 2.0).abs() < 0.05 && outside_absent(&f, 10.0));
        let always: Vec<f64> = (0..rows).map(|r| 2.0 * x[r] + 0.1 * rng.normal()).collect();
        let g = search::<1>(&x, &always, Some(1.0)).unwrap();
        let (s, c) = x
            .iter()
            .zip(&always)
            .fold((0.0, 0.0), |(s, c), (x, y)| (s + x * y, c + x * x));
        assert!(g.gain - s * s / c < 10.0, "{g:?}");
    }
}
