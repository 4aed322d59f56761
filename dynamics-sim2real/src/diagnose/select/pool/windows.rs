//! Effects limited in time within the pool: their columns multiplied by
//! the indicator of the window found on the training record.

use super::Pool;
use crate::diagnose::candidates::Prepared;
use crate::diagnose::fit::{inside, window_of, Windows};

impl Pool {
    /// The pool's columns of the windowed terms limited to their windows (two
    /// more parameters each).
    pub fn limit_to_windows<const N: usize>(&mut self, windows: &Windows, p: &Prepared<N>) {
        let pool = self;
        // (The windowed kinds, `windowable`, carry no prior: their rows of the
        // Gram matrix are their columns' products alone.)
        for t in 0..pool.terms.len() {
            let Some(w) = window_of(windows, pool.terms[t].fit.candidate) else {
                continue;
            };
            if pool.terms[t].fixed.is_some() || pool.terms[t].link.is_some() {
                continue;
            }
            let m = inside(p, &w);
            for &c in &pool.terms[t].cols.clone() {
                let col: Vec<f64> = pool
                    .x
                    .column(c)
                    .iter()
                    .zip(&m)
                    .map(|(x, m)| x * m)
                    .collect();
                pool.x.set(c, col);
                let v = pool.x.against(c);
                pool.gram.set_column(c, &v);
                pool.gram.set_row(c, &v.transpose());
                pool.xty[c] = pool.x.dot_with(c, pool.y.as_slice(), 0, pool.y.len());
            }
            pool.terms[t].k += 2;
            pool.terms[t].fit.k = pool.terms[t].k;
        }
        pool.changed();
    }
}
