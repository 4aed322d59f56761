//! Work on all cores: the items of a slice shared among threads, results
//! in the slice's order; fitting every candidate that way, with progress
//! reported as each fit ends.

use std::sync::atomic::{AtomicUsize, Ordering};

use super::analysis::{self, Fit, Prepared};
use super::candidate::Candidate;
use dynamics_runtime::Robot;

/// `f` of every item, computed on `threads` threads (0: all cores), in the
/// order of `items`. Each thread takes the next item not yet taken, so
/// that items of very different cost (a motor-side search against a
/// linear fit) share the cores evenly. A panic in `f` is passed on.
pub fn map<T: Sync, U: Send>(items: &[T], threads: usize, f: impl Fn(&T) -> U + Sync) -> Vec<U> {
    let threads = if threads == 0 {
        std::thread::available_parallelism().map_or(1, |n| n.get())
    } else {
        threads
    }
    .clamp(1, items.len().max(1));
    let next = AtomicUsize::new(0);
    let work = || {
        let mut done = Vec::new();
        loop {
            let i = next.fetch_add(1, Ordering::Relaxed);
            let Some(item) = items.get(i) else {
                return done;
            };
            done.push((i, f(item)));
        }
    };
    let mut all: Vec<(usize, U)> = if threads == 1 {
        work()
    } else {
        std::thread::scope(|s| {
            let handles: Vec<_> = (0..threads).map(|_| s.spawn(work)).collect();
            handles
                .into_iter()
                .flat_map(|h| match h.join() {
                    Ok(v) => v,
                    Err(e) => std::panic::resume_unwind(e),
                })
                .collect()
        })
    };
    all.sort_by_key(|(i, _)| *i);
    all.into_iter().map(|(_, u)| u).collect()
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
