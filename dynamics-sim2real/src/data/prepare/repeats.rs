//! Repeated samples: a logger that writes the previous values of a
//! quantity again (all joints' positions, velocities or efforts equal to
//! the row before, to the last digit) while that quantity otherwise changes
//! from row to row. A joint at rest behind a quantised encoder repeats its
//! position legitimately; a quantity counts as live only when at least one
//! of its joints changes on at least half of the rows.

use nalgebra::SVector;

/// Rows of `x` (one quantity, every joint) that repeat the row before
/// exactly, when the quantity is live; empty otherwise.
pub(super) fn repeated<const N: usize>(x: &[SVector<f64, N>]) -> Vec<usize> {
    let n = x.len();
    if n < 2 {
        return vec![];
    }
    let live = (0..N).any(|j| {
        let changes = x.windows(2).filter(|w| w[1][j] != w[0][j]).count();
        2 * changes >= n - 1
    });
    if !live {
        return vec![];
    }
    (1..n).filter(|&k| x[k] == x[k - 1]).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn repeats_of_a_live_quantity_only() {
        let mut x: Vec<SVector<f64, 2>> = (0..100).map(|k| [k as f64, 0.0].into()).collect();
        x[40] = x[39];
        x[41] = x[39];
        assert_eq!(repeated(&x), vec![40, 41]);
        // A joint at rest behind a quantised encoder: not live.
        let still: Vec<SVector<f64, 1>> = (0..100).map(|k| [(k / 30) as f64].into()).collect();
        assert!(repeated(&still).is_empty());
    }
}
