//! Fitting every candidate on all cores: the candidates in one chunk per
//! thread, progress reported as each fit ends.

use std::sync::atomic::{AtomicUsize, Ordering};

use super::analysis::{self, Fit, Prepared};
use super::candidate::Candidate;
use crate::Robot;

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
    let threads = if threads == 0 {
        std::thread::available_parallelism()
            .map(|n| n.get())
            .unwrap_or(1)
    } else {
        threads
    };
    let chunk = total.div_ceil(threads.max(1)).max(1);
    std::thread::scope(|s| {
        let handles: Vec<_> = candidates
            .chunks(chunk)
            .map(|cs| {
                let done = &done;
                s.spawn(move || {
                    cs.iter()
                        .map(|&c| {
                            let f = analysis::fit::<R, N>(c, p);
                            progress(done.fetch_add(1, Ordering::Relaxed) + 1, total);
                            f
                        })
                        .collect::<Vec<_>>()
                })
            })
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
