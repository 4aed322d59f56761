//! A time window of measured data: the samples whose time from the first
//! sample lies in `[start, end)`.

use super::Measured;

impl<const N: usize> Measured<N> {
    /// The samples at times `t - t[0]` in `[start, end)` s (velocities kept
    /// as they were, so a differentiated velocity stays central at the
    /// window's edges); the warnings are kept.
    ///
    /// ```
    /// use dynamics_sim2real::data::Measured;
    /// let m = Measured::<1> {
    ///     t: (0..10).map(|k| 5.0 + k as f64).collect(),
    ///     q: vec![[0.0].into(); 10],
    ///     qd: vec![[0.0].into(); 10],
    ///     tau: (0..10).map(|k| [k as f64].into()).collect(),
    ///     qd_measured: true,
    ///     warnings: vec![],
    ///     ..Default::default()
    /// };
    /// let w = m.window(2.0, 5.0);
    /// assert_eq!((w.len(), w.t[0], w.tau[2][0]), (3, 7.0, 4.0));
    /// ```
    pub fn window(&self, start: f64, end: f64) -> Measured<N> {
        let t0 = self.t.first().copied().unwrap_or(0.0);
        let keep: Vec<usize> = (0..self.len())
            .filter(|&k| {
                let s = self.t[k] - t0;
                s >= start && s < end
            })
            .collect();
        Measured {
            t: keep.iter().map(|&k| self.t[k]).collect(),
            q: keep.iter().map(|&k| self.q[k]).collect(),
            qd: keep.iter().map(|&k| self.qd[k]).collect(),
            tau: keep.iter().map(|&k| self.tau[k]).collect(),
            qd_measured: self.qd_measured,
            warnings: self.warnings.clone(),
            missing: if self.missing.is_empty() {
                Vec::new()
            } else {
                keep.iter().map(|&k| self.missing[k]).collect()
            },
            // The kept samples are one run of indices (times increase):
            // holes shift by its start and are clipped to it.
            holes: match (keep.first(), keep.last()) {
                (Some(&a), Some(&b)) => self
                    .holes
                    .iter()
                    .filter(|&&(s, e)| e > a && s <= b)
                    .map(|&(s, e)| (s.max(a) - a, e.min(b + 1) - a))
                    .collect(),
                _ => Vec::new(),
            },
            joints: self.joints.clone(),
            prepared: self.prepared,
            interpolation_variance: self.interpolation_variance,
        }
    }
}
