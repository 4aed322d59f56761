//! What a fit is made against: a prepared record's residual and its
//! nominal model's efforts, or those with the efforts of other (linear,
//! fitted) effects moved into the model, which is how the compound
//! explanation searches a motor side again against the residual the
//! others leave.
//!
//! The others' efforts are made where they are read, not kept along the
//! record for every joint: at the fit's rows (every joint, once) and, for
//! a motor side's simulation, at its joint over the samples simulated (the
//! simulation's track, `motor_sim`), or along the record once for the
//! motor sides said to read a joint ([`Against::expect`]) and dropped when
//! the last of them is done. Each value is, to the bit, that of a copy of the
//! record with each other effect's effort added to the model and taken
//! from the residual in turn at every sample of the record's range (the
//! same sums in the same order; outside the range the record's own).

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex, MutexGuard};

use nalgebra::SVector;

use super::motor_sim::{Load, ALONG_APART};
use crate::diagnose::candidates::{Candidate, Prepared};
use crate::diagnose::signals::Signals;
use rayon::prelude::*;

/// Where each set of others' efforts is told from another (0: the
/// record's own model).
static NEXT_KEY: AtomicU64 = AtomicU64::new(1);

/// A record and the other effects whose efforts are moved into its model.
#[derive(Debug)]
pub struct Against<'a, const N: usize> {
    /// The record.
    pub p: &'a Prepared<N>,
    /// The other effects: each candidate with its fitted parameters, in the
    /// order their efforts are added to the model.
    others: Vec<(Candidate, &'a [f64])>,
    /// Tells these efforts from others on the same record (0 without
    /// others).
    key: u64,
    /// The residual at each row of the record with the others' efforts
    /// taken away (empty without others).
    rows: Vec<SVector<f64, N>>,
    /// Per joint, the model's effort along the record's range, made once
    /// for the motor sides that read it.
    kept: Vec<Mutex<Kept>>,
}

/// One joint's model effort along the record's range, while read.
#[derive(Debug, Default)]
struct Kept {
    /// Motor sides still to read it.
    readers: usize,
    /// The efforts over the range, once made.
    along: Option<Arc<Vec<f64>>>,
}

impl<'a, const N: usize> Against<'a, N> {
    /// The record's own residual and model.
    pub fn record(p: &'a Prepared<N>) -> Self {
        Against {
            p,
            others: Vec::new(),
            key: 0,
            rows: Vec::new(),
            kept: Vec::new(),
        }
    }

    /// The record with the efforts of `others` (candidates with their
    /// fitted parameters, added in this order) moved into its model; the
    /// residual at its rows made once.
    pub fn others(p: &'a Prepared<N>, others: Vec<(Candidate, &'a [f64])>) -> Self {
        if others.is_empty() {
            return Self::record(p);
        }
        let mut a = Against {
            p,
            others,
            key: NEXT_KEY.fetch_add(1, Ordering::Relaxed),
            rows: Vec::new(),
            kept: (0..N).map(|_| Mutex::default()).collect(),
        };
        // Term after term over the rows (a candidate's columns at the rows
        // are kept by the record's column cache).
        let mut rows: Vec<SVector<f64, N>> = p.rows.iter().map(|&k| p.sig.residual[k]).collect();
        for &(c, theta) in &a.others {
            for (r, &k) in rows.iter_mut().zip(&p.rows) {
                if a.within(k) {
                    *r -= a.effort(c, theta, k);
                }
            }
        }
        a.rows = rows;
        a
    }

    /// Joint `j`'s kept efforts (none without others).
    fn kept(&self, j: usize) -> Option<MutexGuard<'_, Kept>> {
        // A panic while holding the lock left the entry whole or empty.
        let m = self.kept.get(j)?;
        Some(m.lock().unwrap_or_else(|e| e.into_inner()))
    }

    /// Says that `readers` more motor sides will read joint `j`'s model
    /// along the record: it is made once for them (on the first reading)
    /// and kept until each has said it is [`Against::done`].
    pub fn expect(&self, j: usize, readers: usize) {
        if let Some(mut kept) = self.kept(j) {
            kept.readers += readers;
        }
    }

    /// One motor side said to read joint `j` ([`Against::expect`]) is done
    /// with it: dropped after the last.
    pub fn done(&self, j: usize) {
        if let Some(mut kept) = self.kept(j) {
            kept.readers = kept.readers.saturating_sub(1);
            if kept.readers == 0 {
                kept.along = None;
            }
        }
    }

    /// The model's effort at joint `j` over samples `a..z`, term after
    /// term along the samples (the column cache recomputes a candidate's
    /// columns a chunk at a time).
    fn made_along(&self, j: usize, a: usize, z: usize) -> Vec<f64> {
        let mut m: Vec<f64> = (a..z).map(|k| self.p.sig.model[k][j]).collect();
        let (lo, hi) = self.p.sig.range;
        let (from, to) = (a.max(lo), z.min(hi));
        for &(c, theta) in &self.others {
            for k in from..to {
                m[k - a] += self.effort_at(c, theta, k, j);
            }
        }
        m
    }

    /// [`Against::made_along`] made on the threads a piece of samples at a
    /// time where `a..z` is long (the same values: each sample's sum in the
    /// same order). Never under a joint's lock: the caller waits on other
    /// threads' pieces and meanwhile runs other work, which may take it.
    fn made_along_apart(&self, j: usize, a: usize, z: usize) -> Vec<f64> {
        if z.saturating_sub(a) < ALONG_APART {
            return self.made_along(j, a, z);
        }
        let pieces: Vec<(usize, usize)> = (a..z)
            .step_by(ALONG_APART)
            .map(|s| (s, (s + ALONG_APART).min(z)))
            .collect();
        let made: Vec<Vec<f64>> = pieces
            .into_par_iter()
            .map(|(s, e)| self.made_along(j, s, e))
            .collect();
        made.concat()
    }

    /// Whether sample `k` is in the record's range (where the others'
    /// efforts are moved).
    fn within(&self, k: usize) -> bool {
        let (a, z) = self.p.sig.range;
        k >= a && k < z
    }

    /// Effort of candidate `c` with parameters `theta` at sample `k`,
    /// every joint.
    fn effort(&self, c: Candidate, theta: &[f64], k: usize) -> SVector<f64, N> {
        let cols = c.columns(&self.p.sig, &self.p.basis, k);
        let mut e = SVector::<f64, N>::zeros();
        for (m, th) in theta.iter().enumerate() {
            e += cols[m] * *th;
        }
        e
    }

    /// [`Against::effort`] at joint `j` alone: the same sum (a candidate
    /// whose columns are zero at the joint adds its zeros without them
    /// being made).
    fn effort_at(&self, c: Candidate, theta: &[f64], k: usize, j: usize) -> f64 {
        let mut e = 0.0;
        if c.local_joint().is_some_and(|i| i != j) {
            for th in theta {
                e += 0.0 * *th;
            }
        } else {
            let cols = c.columns(&self.p.sig, &self.p.basis, k);
            for (m, th) in theta.iter().enumerate() {
                e += cols[m][j] * *th;
            }
        }
        e
    }

    /// The residual at row `i` of the record (sample `p.rows[i]`).
    pub fn residual_row(&self, i: usize) -> SVector<f64, N> {
        match self.rows.get(i) {
            Some(r) => *r,
            None => self.p.sig.residual[self.p.rows[i]],
        }
    }

    /// The residual at sample `k`, every joint.
    #[cfg(test)]
    pub fn residual_at(&self, k: usize) -> SVector<f64, N> {
        let mut r = self.p.sig.residual[k];
        if self.within(k) {
            for &(c, theta) in &self.others {
                r -= self.effort(c, theta, k);
            }
        }
        r
    }

    /// The model's effort at sample `k`, joint `j`.
    pub fn model_at(&self, k: usize, j: usize) -> f64 {
        let mut m = self.p.sig.model[k][j];
        if self.within(k) {
            for &(c, theta) in &self.others {
                m += self.effort_at(c, theta, k, j);
            }
        }
        m
    }
}

impl<const N: usize> Load<N> for Against<'_, N> {
    fn signals(&self) -> &Signals<N> {
        &self.p.sig
    }

    fn model_key(&self) -> u64 {
        self.key
    }

    fn model_along(&self, j: usize, a: usize, z: usize) -> Vec<f64> {
        let (lo, hi) = self.p.sig.range;
        // (Made under the joint's lock: a second reader waits for it.)
        let kept = self.kept(j).and_then(|mut kept| {
            (kept.readers > 0).then(|| {
                let along = kept
                    .along
                    .get_or_insert_with(|| Arc::new(self.made_along(j, lo, hi)));
                Arc::clone(along)
            })
        });
        let Some(along) = kept else {
            return self.made_along_apart(j, a, z);
        };
        // The kept efforts over the range, the record's own outside it.
        (a..z)
            .map(|k| match self.within(k) {
                true => along[k - lo],
                false => self.p.sig.model[k][j],
            })
            .collect()
    }
}
