//! The order the explanation is read in: by gain. Whichever search found
//! the set (the forward path adds the best term first, the search from the
//! full linear model keeps the pool's order, by joint), each effect in turn
//! is the one whose addition to those before it lowers the criterion of the
//! joint fit most. The gap left after 1, 2, 3, ... effects then falls as
//! fast as the set allows, and the first effects are the ones that matter.

use super::select::crit;
use crate::diagnose::select::criterion::tie_key;
use crate::diagnose::select::pool::Pool;

/// `set` in the order of its gains (greedy: each prefix refitted jointly;
/// ties by term index).
pub(super) fn by_gain(pool: &Pool, set: &[usize]) -> Vec<usize> {
    let mut left: Vec<usize> = set.to_vec();
    let mut ordered = Vec::with_capacity(set.len());
    while !left.is_empty() {
        let (at, _) = left
            .iter()
            .enumerate()
            .map(|(i, &t)| {
                let mut s = ordered.clone();
                s.push(t);
                (i, (tie_key(crit(pool, &pool.solve(&s))), t))
            })
            .min_by_key(|&(_, key)| key)
            .expect("a term left");
        ordered.push(left.remove(at));
    }
    ordered
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnose::candidates::Candidate;
    use crate::diagnose::select::pool::{test_pool, test_term};
    use nalgebra::{DMatrix, DVector};

    /// Three terms in the pool's order with effects 0.1, 3.0 and 1.0 on
    /// the data: read by gain, the large one comes first, then the middle
    /// one, and the gap after each prefix falls.
    #[test]
    fn the_largest_gain_comes_first() {
        let n = 400;
        let cols: Vec<Vec<f64>> = (0..3)
            .map(|c| {
                (0..n)
                    .map(|i| (i as f64 * (0.011 + 0.017 * c as f64)).sin())
                    .collect()
            })
            .collect();
        let mut rng = crate::synth::Rng::new(3);
        let y = DVector::from_fn(n, |r, _| {
            0.1 * cols[0][r] + 3.0 * cols[1][r] + 1.0 * cols[2][r] + 0.01 * rng.normal()
        });
        let x = DMatrix::from_fn(n, 3, |r, c| cols[c][r]);
        let terms = (0..3)
            .map(|c| test_term(Candidate::EffortOffset(c), vec![c], vec![false], None))
            .collect();
        let pool = test_pool(x, y, terms, 1);
        let ordered = by_gain(&pool, &[0, 1, 2]);
        assert_eq!(ordered, vec![1, 2, 0]);
        let sse = |k: usize| pool.solve(&ordered[..k]).sse;
        assert!(sse(1) > sse(2) && sse(2) > sse(3));
        // A set of one is itself; none is none.
        assert_eq!(by_gain(&pool, &[2]), vec![2]);
        assert!(by_gain(&pool, &[]).is_empty());
    }
}
