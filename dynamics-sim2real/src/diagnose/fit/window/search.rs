//! The change-point search of a window: the one-column fit of a
//! candidate's column on `[first, last)` over every pair of fit rows from
//! prefix sums (a long record's over blocks of rows, then at the row),
//! then each edge refined at the full sample rate where the
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

/// Most fit rows searched pair by pair; a longer record is searched on
/// blocks of rows first ([`coarse_to_fine`]), so the search's cost stays
/// linear in the record's length.
const EXACT_ROWS: usize = 4096;

/// The best window of column `x` against `y` (both whitened, `n` values a
/// row): every pair of rows `[first, last)` with at least [`MIN_ROWS`]
/// inside and outside; the coefficient's sign kept to `sign` when given
/// (`Some(1.0)`: >= 0). Over more than [`EXACT_ROWS`] rows the pairs are
/// those of blocks of rows, each edge then searched at the row.
pub fn search<const N: usize>(x: &[f64], y: &[f64], sign: Option<f64>) -> Option<Found> {
    search_up_to::<N>(x, y, sign, EXACT_ROWS)
}

/// [`search`] with every pair of rows scored up to `exact` rows.
fn search_up_to<const N: usize>(
    x: &[f64],
    y: &[f64],
    sign: Option<f64>,
    exact: usize,
) -> Option<Found> {
    let rows = x.len() / N;
    if rows < 2 * MIN_ROWS {
        return None;
    }
    let sums = Sums::new::<N>(x, y, sign);
    if rows <= exact {
        return sums.best(0..=rows - MIN_ROWS, |first| first + MIN_ROWS..=rows);
    }
    coarse_to_fine(&sums, rows.div_ceil(exact))
}

/// Prefix sums of `x y` and `x x` over the rows: the one-column fit of
/// any window from two differences.
struct Sums {
    /// `sum x y` over rows `0..r`, at `r`.
    a: Vec<f64>,
    /// `sum x x` over rows `0..r`, at `r`.
    b: Vec<f64>,
    /// The coefficient's sign, when kept.
    sign: Option<f64>,
}

impl Sums {
    fn new<const N: usize>(x: &[f64], y: &[f64], sign: Option<f64>) -> Self {
        let rows = x.len() / N;
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
        Sums { a, b, sign }
    }

    fn rows(&self) -> usize {
        self.a.len() - 1
    }

    /// The gain of window `[first, last)` and its coefficient, when it is a
    /// window (enough rows inside and outside, a column there, the sign
    /// kept).
    fn gain(&self, first: usize, last: usize) -> Option<(f64, f64)> {
        let rows = self.rows();
        if last > rows || last < first + MIN_ROWS || rows - (last - first) < MIN_ROWS {
            return None;
        }
        let (s, c) = (self.a[last] - self.a[first], self.b[last] - self.b[first]);
        if c <= 0.0 {
            return None;
        }
        let theta = s / c;
        if self.sign.is_some_and(|g| theta * g < 0.0) {
            return None;
        }
        Some((s * s / c, theta))
    }

    /// The window `[first, last)` found, with its fit outside.
    fn found(&self, first: usize, last: usize, gain: f64, theta: f64) -> Found {
        let rows = self.rows();
        let (so, co) = (
            self.a[rows] - (self.a[last] - self.a[first]),
            self.b[rows] - (self.b[last] - self.b[first]),
        );
        let (outside_theta, outside_gain) = if co > 0.0 {
            (so / co, so * so / co)
        } else {
            (0.0, 0.0)
        };
        Found {
            first,
            last,
            theta,
            gain,
            outside_gain,
            outside_theta,
        }
    }

    /// The best window with its first row in `firsts` and its last in
    /// `lasts(first)` (the first best in that order).
    fn best<F, L>(&self, firsts: F, lasts: impl Fn(usize) -> L) -> Option<Found>
    where
        F: IntoIterator<Item = usize>,
        L: IntoIterator<Item = usize>,
    {
        let mut best: Option<Found> = None;
        for first in firsts {
            for last in lasts(first) {
                if let Some((gain, theta)) = self.gain(first, last) {
                    if best.is_none_or(|f| gain > f.gain) {
                        best = Some(self.found(first, last, gain, theta));
                    }
                }
            }
        }
        best
    }
}

/// The best window on the edges of blocks of `block` rows, then every
/// pair of rows within a block of its edges, then each edge moved alone
/// over the whole record while that gains (each step gains, so it stops):
/// about `(rows / block)^2 / 2 + 4 block^2` pairs and a few passes over
/// the rows instead of `rows^2 / 2`. A window spanning a few blocks or
/// more is found where the exact search finds it; a shorter one where its
/// block's gain stands out.
fn coarse_to_fine(sums: &Sums, block: usize) -> Option<Found> {
    let rows = sums.rows();
    let edges: Vec<usize> = (0..=rows.div_ceil(block))
        .map(|i| (i * block).min(rows))
        .collect();
    let coarse = sums.best(edges.iter().copied(), |first| {
        edges.iter().copied().filter(move |&l| l > first)
    })?;
    let near = |e: usize| e.saturating_sub(block)..=(e + block).min(rows);
    let mut f = sums
        .best(near(coarse.first), |_| near(coarse.last))
        .unwrap_or(coarse);
    loop {
        let moved = sums
            .best(0..=rows, |_| f.last..=f.last)
            .and_then(|g| sums.best(g.first..=g.first, |_| 0..=rows))
            .filter(|g| g.gain > f.gain);
        match moved {
            Some(g) => f = g,
            None => return Some(f),
        }
    }
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

    /// A step column on rows `on` of `rows`, with noise of seed `seed`.
    fn step(rows: usize, on: std::ops::Range<usize>, seed: u64) -> (Vec<f64>, Vec<f64>) {
        let x: Vec<f64> = (0..rows).map(|r| 1.0 + (r as f64 * 0.37).sin()).collect();
        let mut rng = crate::synth::Rng::new(seed);
        let y = (0..rows)
            .map(|r| if on.contains(&r) { 0.8 } else { 0.0 } * x[r] + 0.1 * rng.normal())
            .collect();
        (x, y)
    }

    /// Over blocks of rows, then at the row, the search finds the rows of
    /// a step where every pair of rows does: long and short windows, at
    /// the record's ends and inside, of either sign kept.
    #[test]
    fn blocks_then_rows_find_the_step_every_pair_finds() {
        let rows = 1500;
        for (k, on) in [300..1100, 0..700, 900..1500, 613..641, 1210..1223, 5..1495]
            .into_iter()
            .enumerate()
        {
            let (x, y) = step(rows, on.clone(), k as u64 + 1);
            let every = search_up_to::<1>(&x, &y, Some(1.0), usize::MAX).unwrap();
            let blocks = search_up_to::<1>(&x, &y, Some(1.0), 100).unwrap();
            assert_eq!(blocks, every, "window {on:?}");
            let off = every.first.abs_diff(on.start) + every.last.abs_diff(on.end);
            assert!(off <= 2, "window {on:?}: {every:?}");
        }
        // A long record goes through the blocks by default.
        let (x, y) = step(20_000, 7013..13999, 9);
        let f = search::<1>(&x, &y, Some(1.0)).unwrap();
        assert!(
            f.first.abs_diff(7013) + f.last.abs_diff(13999) <= 2,
            "{f:?}"
        );
    }
}
