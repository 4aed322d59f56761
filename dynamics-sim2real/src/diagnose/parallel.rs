//! Work on all cores: a slice cut into one chunk per thread, results in
//! the slice's order; fitting every candidate that way, with progress
//! reported as each fit ends.

use std::sync::atomic::{AtomicUsize, Ordering};

use super::analysis::{self, Fit, Prepared};
use super::candidate::Candidate;
use dynamics_runtime::Robot;

/// `f` of every item, computed on `threads` threads (0: all cores), in the
/// order of `items`. A panic in `f` is passed on.
pub fn map<T: Sync, U: Send>(items: &[T], threads: usize, f: impl Fn(&T) -> U + Sync) -> Vec<U> {
    let threads = if threads == 0 {
        std::thread::available_parallelism().map_or(1, |n| n.get())
    } else {
        threads
    };
    let chunk = items.len().div_ceil(threads).max(1);
    let f = &f;
    std::thread::scope(|s| {
        let handles: Vec<_> = items
            .chunks(chunk)
            .map(|c| s.spawn(move || c.iter().map(f).collect::<Vec<_>>()))
            .collect();
        handles
            .into_iter()
            .flat_map(|h| match h.join() {
                Ok(v) => v,
                Err(e) => std::panic::resume_unwind(e),
            })
            .collect()
    })
}

/// Fits `candidates` to `p` on `threads` threads (0: all cores), calling
/// `progress(done, total)` after each fit.
pub fn fit_all<R: Robot<N> + Clone + Sync, const N: usize>(
    candidates: &[Candidate],
    p: &Prepared<N>,
    threads: usize,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Vec<Fit> {
    let total = candidates.len();
    let done = AtomicUsize::new(0);
    map(candidates, threads, |&c| {
        let f = analysis::fit::<R, N>(c, p);
        progress(done.fetch_add(1, Ordering::Relaxed) + 1, total);
        f
    })
}
