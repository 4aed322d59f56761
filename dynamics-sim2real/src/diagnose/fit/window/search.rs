//! The change-point search of a window: the one-column fit of a
//! candidate's column on `[first, last)` over every pair of fit rows from
//! prefix sums, then each edge refined at the full sample rate where the
//! residual crosses the fitted step.

use nalgebra::SVector;

use crate::diagnose::candidates::Candidate;
use crate::diagnose::candidates::Prepared;
use crate::effects::Window;

/// Fewest fit rows inside a window, and outside it.
pub(super) const MIN_ROWS: usize = 4;
/// The effect fitted outside the window must stay below this share of the
/// fit inside (or be insignificant).
const OUTSIDE_SHARE: f64 = 0.2;

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
pub(super) fn outside_absent(f: &Found, margin: f64) -> bool {
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
