//! The explanation on the held-out record: the chosen set's columns on
//! its rows (windowed effects limited to the windows found there), the
//! residual any subset of the set leaves with given parameters, and the
//! measures of a gap (above the noise floor, plain RMS).
//!
//! An encoder offset acts on the held-out residual as it does on the
//! robot: the model evaluated at the positions it corrects, not its
//! first-order column (the column the fit on the training record is
//! linear in). At a few milliradians the two agree to a thousandth; at a
//! radian the column is no longer the effect, and the held-out record
//! judges the effect.

use nalgebra::{DVector, SVector};

use crate::diagnose::candidates::{combined, linear_columns, whitened, Candidate, Prepared};
use crate::diagnose::fit::{fixed_column_against, holdout_window_in, inside};
use crate::diagnose::select::{against_others, Explanation, Pool};
use dynamics_runtime::Robot;

/// One effect's held-out columns: its free ones and its fixed one.
type Columns = (Vec<DVector<f64>>, Option<DVector<f64>>);

/// The whitened effort change an encoder offset makes at a joint, by its
/// value (the model at the corrected positions less the model).
type Acts<'a> = Box<dyn Fn(usize, f64) -> DVector<f64> + 'a>;

/// The explanation's held-out side: the set's columns on the held-out rows.
pub struct Holdout<'a, const N: usize> {
    h: &'a Prepared<N>,
    /// Per effect of the set: its free columns and its fixed one.
    cols: Vec<Columns>,
    y: DVector<f64>,
    /// Per effect of the set, the joint of an encoder offset.
    offsets: Vec<Option<usize>>,
    /// Per effect of the set, the rows it acts on where it is limited to
    /// a window (1 inside, 0 outside).
    windows: Vec<Option<DVector<f64>>>,
    /// What an encoder offset does to the residual as it acts.
    acts: Acts<'a>,
}

/// The whitened change of the model's effort on the rows of `h` that an
/// encoder offset `d` at joint `j` makes: the model at the positions it
/// corrects (`q - d e_j`: the encoder reads `q + d`) less the model. Its
/// first-order part is `d` times the offset's column `-K e_j`.
pub fn offset_effort<R: Robot<N>, const N: usize>(
    robot: &R,
    h: &Prepared<N>,
    j: usize,
    d: f64,
) -> DVector<f64> {
    DVector::from_vec(whitened(h, |k| {
        let (q, qd, qdd) = (h.sig.q(k), h.sig.qd(k), h.sig.qdd(k));
        let mut moved = q;
        moved[j] -= d;
        robot.inverse_dynamics(&moved, &qd, &qdd) - robot.inverse_dynamics(&q, &qd, &qdd)
    }))
}

/// The joint of an encoder offset.
pub fn offset_joint(c: Candidate) -> Option<usize> {
    match c {
        Candidate::EncoderOffset(j) => Some(j),
        _ => None,
    }
}

/// The free columns of pool term `t` on the held-out record `h` (`links`:
/// its link regressor columns); a motor side's are none (its column is
/// simulated against the others, [`Holdout::new`]).
pub fn free_columns<const N: usize>(
    h: &Prepared<N>,
    links: &[Vec<Vec<f64>>],
    pool: &Pool,
    t: usize,
) -> Vec<DVector<f64>> {
    let term = &pool.terms[t];
    if let Some(b) = &term.link {
        let cols = links
            .get(b.link)
            .map(|lc| combined(lc, b))
            .unwrap_or_else(|| vec![vec![0.0; h.n()]; b.v.ncols()]);
        return cols.into_iter().map(DVector::from_vec).collect();
    }
    if term.fixed.is_some() {
        return Vec::new();
    }
    linear_columns(term.fit.candidate, h)
        .into_iter()
        .map(DVector::from_vec)
        .collect()
}

/// Effort scale of the plain measure (noise included): the raw effort
/// minus the model, per row and joint.
fn raw_residual<const N: usize>(h: &Prepared<N>) -> Vec<f64> {
    let mut out = Vec::with_capacity(h.n());
    for &k in &h.rows {
        for j in 0..N {
            let x = h.sig.tau_raw()[k][j] - h.sig.model[k][j];
            out.push(if x.is_finite() { x } else { 0.0 });
        }
    }
    out
}

impl<'a, const N: usize> Holdout<'a, N> {
    /// The columns of the chosen set on `h` (`robot`: the nominal model,
    /// which encoder offsets act through).
    pub fn new<R: Robot<N>>(
        robot: &'a R,
        h: &'a Prepared<N>,
        links: &[Vec<Vec<f64>>],
        pool: &Pool,
        e: &Explanation,
    ) -> Self {
        // The record with the others' effort in its model, which a motor
        // side's column is simulated against (the others' effort made at
        // the rows and at the motor side's joint along the record), when
        // the set has one.
        let fixed = e.set.iter().any(|&t| {
            let term = &pool.terms[t];
            term.link.is_none() && term.fixed.is_some()
        });
        let hm = fixed.then(|| against_others(h, pool, &e.set, &e.sol));
        // (One term after another: a motor side's simulation over the
        // whole record uses the threads itself, and would otherwise be
        // held beside the link terms' columns.)
        let cols = e
            .set
            .iter()
            .map(|&t| {
                let term = &pool.terms[t];
                match (term.fixed.as_ref(), hm.as_ref()) {
                    (Some(_), Some(hm)) if term.link.is_none() => (
                        vec![],
                        Some(DVector::from_vec(fixed_column_against(&term.fit, hm))),
                    ),
                    _ => (free_columns(h, links, pool, t), None),
                }
            })
            .collect();
        let y = DVector::from_vec(crate::diagnose::candidates::whitened(h, |k| {
            h.sig.residual[k]
        }));
        let offsets = e
            .set
            .iter()
            .map(|&t| offset_joint(pool.terms[t].fit.candidate))
            .collect();
        Holdout {
            h,
            windows: vec![None; e.set.len()],
            cols,
            y,
            offsets,
            acts: Box::new(move |j, d| offset_effort(robot, h, j, d)),
        }
    }

    /// The whitened effort change of an encoder offset `d` at joint `j`
    /// as it acts ([`offset_effort`]).
    pub fn offset_acts(&self, j: usize, d: f64) -> DVector<f64> {
        (self.acts)(j, d)
    }

    /// The nominal model's whitened held-out residual.
    pub fn observed(&self) -> &DVector<f64> {
        &self.y
    }

    /// Limits the effect at position `i` of the set to the rows where
    /// `inside` is 1 (a window found on the held-out record).
    pub fn limit(&mut self, i: usize, inside: DVector<f64>) {
        for col in &mut self.cols[i].0 {
            col.component_mul_assign(&inside);
        }
        self.windows[i] = Some(inside);
    }

    /// The whitened held-out residual of the effects at positions `which`
    /// of the set, with parameters `theta` (one per position); an encoder
    /// offset as it acts.
    pub fn residual(&self, which: &[usize], theta: &[Vec<f64>]) -> DVector<f64> {
        let mut r = self.y.clone();
        for (i, &w) in which.iter().enumerate() {
            if let (Some(j), Some(&d)) = (self.offsets[w], theta[i].first()) {
                if d.is_finite() {
                    let mut acts = self.offset_acts(j, d);
                    if let Some(inside) = &self.windows[w] {
                        acts.component_mul_assign(inside);
                    }
                    r -= acts;
                }
                continue;
            }
            let (free, fixed) = &self.cols[w];
            for (c, th) in free.iter().zip(&theta[i]) {
                if th.is_finite() {
                    r.axpy(-th, c, 1.0);
                }
            }
            if let Some(f) = fixed {
                r -= f;
            }
        }
        r
    }

    /// [`residual`](Self::residual) with further free columns taken off,
    /// each with its parameters (terms outside the set).
    pub fn residual_with(
        &self,
        which: &[usize],
        theta: &[Vec<f64>],
        extra: &[(&[DVector<f64>], &[f64])],
    ) -> DVector<f64> {
        let mut r = self.residual(which, theta);
        for (cols, th) in extra {
            for (c, th) in cols.iter().zip(th.iter()) {
                if th.is_finite() {
                    r.axpy(-th, c, 1.0);
                }
            }
        }
        r
    }

    /// Per joint RMS of a whitened residual, in effort units.
    pub fn joint_rms(&self, r: &DVector<f64>) -> SVector<f64, N> {
        let rows = (r.len() / N).max(1);
        SVector::from_fn(|j, _| {
            let ms: f64 = (0..rows).map(|i| r[i * N + j].powi(2)).sum::<f64>() / rows as f64;
            ms.sqrt() * self.h.sig.floor[j]
        })
    }

    /// The above-noise torque gap (sum over joints of the squared RMS above
    /// the floor, in floor units) of a residual.
    pub fn gap(&self, r: &DVector<f64>) -> f64 {
        let rms = self.joint_rms(r);
        (0..N)
            .map(|j| {
                let f = self.h.sig.floor[j];
                (rms[j] * rms[j] - f * f).max(0.0) / (f * f)
            })
            .sum()
    }

    /// The plain RMS of the raw effort residual over all joints once the
    /// whitened smoothed residual `r` is left (what the effects removed is
    /// taken from the raw residual).
    pub fn plain(&self, r: &DVector<f64>) -> f64 {
        let raw = raw_residual(self.h);
        let mut s = 0.0;
        for (i, x) in raw.iter().enumerate() {
            let j = i % N;
            let removed = (self.y[i] - r[i]) * self.h.sig.floor[j];
            s += (x - removed).powi(2);
        }
        (s / raw.len().max(1) as f64).sqrt()
    }
}

/// 1 - after / before, zero when there was nothing before.
pub fn fraction(before: f64, after: f64) -> f64 {
    if before > 0.0 && before.is_finite() && after.is_finite() {
        1.0 - after / before
    } else {
        0.0
    }
}

/// The explanation's windowed effects limited to their held-out windows on
/// the held-out side (found there by the same search, the training fit's
/// sign kept). The search runs on the held-out residual that the
/// explanation's effects on all the time leave (with their training
/// parameters): on the nominal model's residual, an unexplained friction
/// on every joint moved the window of a payload and left friction that
/// the training record shows unconfirmed on the held-out one.
pub fn limit_to_windows<const N: usize>(
    hold: &mut Holdout<N>,
    h: &Prepared<N>,
    pool: &Pool,
    e: &Explanation,
) {
    let windowed = |i: usize| pool.terms[e.set[i]].window.is_some();
    let always: Vec<usize> = (0..e.set.len()).filter(|&i| !windowed(i)).collect();
    let theta: Vec<Vec<f64>> = always.iter().map(|&i| e.sol.theta[i].clone()).collect();
    let left = hold.residual(&always, &theta);
    for (i, &t) in e.set.iter().enumerate() {
        let c = pool.terms[t].fit.candidate;
        if !windowed(i) {
            continue;
        }
        let theta = e.sol.theta[i].first().copied().unwrap_or(0.0);
        let m = match holdout_window_in(c, h, theta, left.as_slice()) {
            Some(w) => DVector::from_vec(inside(h, &w)),
            None => DVector::zeros(h.n()),
        };
        hold.limit(i, m);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synth::{synthesize, SynthOptions};
    use crate::test_robots::Pendulum;

    /// An encoder offset's column is its first-order effect: the model at
    /// the corrected positions departs from it by the offset's square (at
    /// a milliradian by a thousandth of the column's effect), and at a
    /// radian by a large part of it (the gravity torque `m g c cos(q - d)`
    /// is no line in `d`).
    #[test]
    fn an_encoder_offset_acts_through_the_model() {
        let arm = Pendulum::default();
        let opts = SynthOptions {
            duration: 2.0,
            seed: 3,
            ..Default::default()
        };
        let m = synthesize(&arm, &[], &opts).expect("synthesizes");
        let h = Prepared::new(&arm, &m);
        let col = DVector::from_vec(whitened(&h, |k| {
            Candidate::EncoderOffset(0).columns(&h.sig, &h.basis, k)[0]
        }));
        let beyond =
            |d: f64| (offset_effort(&arm, &h, 0, d) - &col * d).norm() / (col.norm() * d.abs());
        assert!(beyond(1e-3) < 2e-3, "{}", beyond(1e-3));
        assert!(beyond(-1e-3) < 2e-3, "{}", beyond(-1e-3));
        assert!(beyond(1.0) > 0.2, "{}", beyond(1.0));
    }
}
