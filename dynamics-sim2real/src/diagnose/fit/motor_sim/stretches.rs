//! Which stretches of a record a motor-side search simulates, and the rows
//! it scores in each.
//!
//! A search (grid, compass refinement, spread) simulates the motor side
//! for a hundred guesses or more; over a whole hour of log that is most of
//! a diagnosis's time. A record no longer than [`SEARCH_SECONDS`] is
//! searched whole. A longer one is searched on [`SPANS`] stretches spread
//! evenly over it, [`SEARCH_SECONDS`] in all, each simulated from the
//! measured state at its start and scored after [`WARM_SECONDS`] (the
//! simulation starts at the static deflection of the measured effort; what
//! is left of the start has faded by then: the link is pulled back at
//! [`OBSERVER_HZ`](super::OBSERVER_HZ), and a motor side the searches
//! admit rings down within a few tenths of a second). The search's
//! optimum and its spread are then those of the stretches' data; the
//! optimum's fit (its error on every row) is simulated over the whole
//! record once.

use crate::diagnose::signals::Signals;

/// Longest record (its filtered range) a search simulates whole, s; also
/// what the stretches of a longer record add up to.
pub const SEARCH_SECONDS: f64 = 120.0;

/// Stretches a longer record is searched on.
pub const SPANS: usize = 6;

/// Time a stretch is simulated before its rows are scored, s.
pub const WARM_SECONDS: f64 = 1.0;

/// Stretches of a record, each `(first, end)` samples with the rows scored
/// in it (ascending; every one with its smoothing window inside the
/// stretch).
#[derive(Clone, Debug, PartialEq)]
pub struct Stretches {
    spans: Vec<(usize, usize, Vec<usize>)>,
    whole: bool,
}

impl Stretches {
    /// The record's whole filtered range, scored at `rows`.
    pub fn whole<const N: usize>(sig: &Signals<N>, rows: &[usize]) -> Self {
        let (a, z) = sig.range;
        Self {
            spans: vec![(a, z, rows.to_vec())],
            whole: true,
        }
    }

    /// What a search simulates: the whole range up to [`SEARCH_SECONDS`],
    /// else [`SPANS`] stretches spread evenly over it, scored at the rows
    /// of `rows` at least [`WARM_SECONDS`] into a stretch and a smoothing
    /// half-window before its end.
    pub fn search<const N: usize>(sig: &Signals<N>, rows: &[usize]) -> Self {
        let (a, z) = sig.range;
        let dt = sig.dt;
        let len = z.saturating_sub(a);
        if dt.is_nan() || dt <= 0.0 || len as f64 * dt <= SEARCH_SECONDS {
            return Self::whole(sig, rows);
        }
        let span = ((SEARCH_SECONDS / SPANS as f64 / dt) as usize).clamp(1, len);
        let warm = (WARM_SECONDS / dt).ceil() as usize;
        let half = sig.sg.half();
        let gap = (len - span) / (SPANS - 1);
        let spans = (0..SPANS)
            .map(|i| {
                let first = a + i * gap;
                let end = first + span;
                let scored = rows
                    .iter()
                    .copied()
                    .filter(|&k| k >= first + warm.max(half) && k + half < end)
                    .collect();
                (first, end, scored)
            })
            .collect();
        Self {
            spans,
            whole: false,
        }
    }

    /// Whether this is the record's whole range with all its rows.
    pub fn is_whole(&self) -> bool {
        self.whole
    }

    /// The stretches: first sample, one past the last, rows scored.
    pub fn spans(&self) -> impl Iterator<Item = (usize, usize, &[usize])> {
        self.spans.iter().map(|(a, z, r)| (*a, *z, r.as_slice()))
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::swinging;
    use super::*;

    #[test]
    fn a_short_record_is_searched_whole() {
        let sig = swinging(30.0);
        let rows: Vec<usize> = (100..29_000).step_by(40).collect();
        let s = Stretches::search(&sig, &rows);
        assert!(s.is_whole());
        assert_eq!(s.spans().next().map(|(_, _, r)| r.to_vec()), Some(rows));
    }

    #[test]
    fn a_long_record_is_searched_on_spread_stretches_of_the_bound() {
        let sig = swinging(600.0);
        let (a, z) = sig.range;
        let rows: Vec<usize> = (a + 20..z - 20).step_by(40).collect();
        let s = Stretches::search(&sig, &rows);
        assert!(!s.is_whole());
        let spans: Vec<_> = s.spans().collect();
        assert_eq!(spans.len(), SPANS);
        // The stretches add up to the bound, start at the range's start,
        // end near its end and do not overlap.
        let samples: usize = spans.iter().map(|(a, z, _)| z - a).sum();
        assert!((samples as f64 * sig.dt - SEARCH_SECONDS).abs() < 0.01);
        assert_eq!(spans[0].0, a);
        assert!(z - spans[SPANS - 1].1 < SPANS);
        for w in spans.windows(2) {
            assert!(w[0].1 <= w[1].0);
        }
        // Rows are scored only after the warm-up and with their window
        // inside the stretch, and they are rows of the record.
        let warm = (WARM_SECONDS / sig.dt).ceil() as usize;
        for (first, end, scored) in spans {
            assert!(!scored.is_empty());
            for &k in scored {
                assert!(k >= first + warm && k + sig.sg.half() < end);
                assert!(rows.contains(&k));
            }
        }
    }
}
