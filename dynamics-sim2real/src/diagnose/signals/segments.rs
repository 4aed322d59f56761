//! Which samples a fit may use when the record has holes and filled
//! samples (`data::prepare`): a row needs its own sample measured and no
//! hole within two smoothing half-widths (the efforts and the regressor
//! columns are smoothed, and some columns smoothed once more); a
//! simulation started from the data (the prediction horizons) needs no
//! hole over its span and a half-width either side.

use crate::data::Measured;

/// Per-sample usability of one prepared record.
#[derive(Debug, Clone, Default)]
pub struct Mask {
    /// Whether sample `k` may be a row of a fit.
    usable: Vec<bool>,
    /// `holes[k]`: hole samples before `k` (prefix count).
    holes: Vec<usize>,
    /// The smoothing half-width, samples.
    half: usize,
}

impl Mask {
    /// The mask of `m` for a smoother of half-width `half` whose full
    /// windows cover `range`.
    pub fn new<const N: usize>(m: &Measured<N>, half: usize, range: (usize, usize)) -> Mask {
        let n = m.len();
        let mut hole = vec![false; n];
        for &(a, b) in &m.holes {
            for h in hole.iter_mut().take(b.min(n)).skip(a) {
                *h = true;
            }
        }
        let mut holes = Vec::with_capacity(n + 1);
        holes.push(0);
        for h in &hole {
            holes.push(holes.last().copied().unwrap_or(0) + usize::from(*h));
        }
        let mut mask = Mask {
            usable: vec![false; n],
            holes,
            half,
        };
        for k in range.0..range.1.min(n) {
            mask.usable[k] =
                m.measured(k) && mask.clear_raw(k.saturating_sub(2 * half), k + 2 * half + 1);
        }
        mask
    }

    /// Whether sample `k` may be a row.
    pub fn usable(&self, k: usize) -> bool {
        self.usable.get(k).copied().unwrap_or(false)
    }

    /// Whether no hole lies in `[a, b)` or a half-width either side.
    pub fn clear(&self, a: usize, b: usize) -> bool {
        self.clear_raw(a.saturating_sub(self.half), b + self.half)
    }

    fn clear_raw(&self, a: usize, b: usize) -> bool {
        let n = self.holes.len() - 1;
        let (a, b) = (a.min(n), b.min(n));
        self.holes[b] == self.holes[a]
    }

    /// Whether the record has holes.
    pub fn has_holes(&self) -> bool {
        self.holes.last().copied().unwrap_or(0) > 0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_keep_two_half_widths_from_a_hole() {
        let m = Measured::<1> {
            t: (0..100).map(|k| k as f64).collect(),
            q: vec![[0.0].into(); 100],
            qd: vec![[0.0].into(); 100],
            tau: vec![[0.0].into(); 100],
            missing: (0..100).map(|k| (50..55).contains(&k) || k == 80).collect(),
            holes: vec![(50, 55)],
            ..Default::default()
        };
        let mask = Mask::new(&m, 3, (3, 97));
        let usable: Vec<usize> = (0..100).filter(|&k| mask.usable(k)).collect();
        let expect: Vec<usize> = (3..97)
            .filter(|&k| !(44..61).contains(&k) && k != 80)
            .collect();
        assert_eq!(usable, expect);
        assert!(mask.clear(10, 40) && !mask.clear(40, 48) && mask.clear(58, 90));
    }
}
