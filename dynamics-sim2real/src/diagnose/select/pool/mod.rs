//! The pool of candidate terms of a compound explanation, as whitened
//! regressor columns over the fit's rows, and joint least-squares fits of
//! any subset of them through one Gram matrix.
//!
//! An effect linear in its parameters is one or two free columns. A
//! motor-side effect (elasticity, backlash, the stiff-rotor variant of
//! armature) is a fixed column: what its simulation changes in the
//! residual (measured minus transmitted effort at its joint), coefficient
//! 1, searched again with the other effects' effort removed once chosen
//! (`compound.rs`). Every subset is then solved from the Gram matrix
//! `X^T X`, `X^T y` and `y^T y` built once, without touching the rows
//! again (`solve.rs`); the pool is built in `build.rs`.

use std::sync::{Mutex, MutexGuard};

use nalgebra::{DMatrix, DVector};

use crate::diagnose::candidates::{Candidate, LinkBasis};
use crate::diagnose::fit::Fit;
use crate::effects::Window;
use cols::Cols;
use prior::{weight, Prior};

mod build;
mod carrier;
mod cols;
mod physical;
pub mod prior;
mod solve;
mod split;
pub(in crate::diagnose) use carrier::payload_leaves_no_body;
pub use carrier::Carrier;
pub(in crate::diagnose) use physical::is_body;
#[cfg(test)]
use physical::leaves_a_body;
pub(in crate::diagnose) use solve::independent;
pub use split::{helps, model_lag, whole_scale, Parts};

/// One term of the pool: a fitted single candidate and its columns.
#[derive(Debug, Clone)]
pub struct Term {
    /// The candidate's single fit (its motor-side parameters for a fixed
    /// term).
    pub fit: Fit,
    /// Free columns (linear parameters), indices into the pool.
    pub cols: Vec<usize>,
    /// Per free column, the least value its parameter may take (0: a
    /// sign-constrained one; a friction correction's the nominal model's
    /// own level negated, `nominal_friction.rs`; `-inf`: none).
    pub lower: Vec<f64>,
    /// Per free column, the largest magnitude its parameter may take
    /// (infinite: none; an effort scale's [`EFFORT_SCALE_LIMIT`]).
    pub limit: Vec<f64>,
    /// The fixed column of a motor-side term.
    pub fixed: Option<usize>,
    /// Parameters counted by the information criterion.
    pub k: usize,
    /// A link correction's determined combinations.
    pub link: Option<LinkBasis>,
    /// The training window a term limited in time acts in (its columns
    /// zero outside it); `None`: on all the time.
    pub window: Option<Window>,
}

impl Term {
    /// Exclusive family: at most one term of a family per place (Coulomb
    /// and Stribeck; armature, elasticity and backlash; effort offset and
    /// joint spring; the grid variants of one kind; a payload at the tip
    /// and a correction of the link that carries the tip, which is the same
    /// body: one statement about it, the richer nesting the simpler).
    pub fn family(&self) -> (u8, Option<usize>) {
        let c = self.fit.candidate;
        let f = match c {
            Candidate::Coulomb(..) | Candidate::Stribeck(..) => 0,
            Candidate::Armature(_) | Candidate::Elasticity(_) | Candidate::Backlash(_) => 1,
            Candidate::Viscous(_) => 2,
            Candidate::Payload | Candidate::PayloadCom(_) => 3,
            Candidate::Environment(_) => 4,
            Candidate::EncoderOffset(_) => 5,
            Candidate::TimeDelay(_) | Candidate::LatePositions | Candidate::LateEffort(_) => 6,
            Candidate::EffortScale(_) => 7,
            // A spring nests the offset (stiffness 0).
            Candidate::EffortOffset(_) | Candidate::Spring(_) => 8,
            Candidate::Inertial(_) if self.link.as_ref().is_some_and(|b| b.tip) => 3,
            Candidate::Inertial(l) => return (9, Some(l)),
        };
        (f, c.joint())
    }
}

/// Whitened columns, the Gram matrix and the terms.
#[derive(Debug, Clone)]
pub struct Pool {
    /// Columns (rows x joints, whitened by the noise floor; those zero
    /// off one joint kept at its rows alone, `cols.rs`).
    x: Cols,
    /// The whitened residual.
    y: DVector<f64>,
    /// `X^T X`.
    gram: DMatrix<f64>,
    /// `X^T y`.
    xty: DVector<f64>,
    /// `y^T y`.
    yy: f64,
    /// The terms.
    pub terms: Vec<Term>,
    /// Per joint, the weight of its rows on top of the whitening by the
    /// noise floor (1: the floor alone; `reweight`).
    weights: Vec<f64>,
    /// The prior toward the nominal model (`prior.rs`), added to the Gram
    /// matrix at its weight ([`weight`](crate::diagnose::select::pool::prior::weight)).
    prior: Prior,
    /// How many rows of the nominal gap one spread of the links' prior is
    /// worth ([`STRENGTHS`](crate::diagnose::select::pool::prior::STRENGTHS), chosen by cross-validation:
    /// `strength.rs`).
    strength: f64,
    /// The Gram matrices of blocks of rows formed so far
    /// ([`Pool::rows_gram`]) of the columns and residual as they are.
    blocks: Blocks,
}

/// Most blocks' Gram matrices a pool keeps (the cross-validation's
/// folds ask for the same four blocks every time).
const BLOCKS: usize = 8;

/// Gram matrices of blocks of rows `(a, z)` already formed, emptied
/// whenever the columns or the residual change (`Pool::changed`): the
/// cross-validation's folds are cut afresh at every step of the selection
/// from the same rows.
#[derive(Debug, Default)]
struct Blocks(Mutex<Vec<(usize, usize, RowsGram)>>);

impl Blocks {
    fn held(&self) -> MutexGuard<'_, Vec<(usize, usize, RowsGram)>> {
        // A panic while holding the lock left whole entries or none.
        self.0.lock().unwrap_or_else(|e| e.into_inner())
    }
}

impl Clone for Blocks {
    fn clone(&self) -> Self {
        Blocks(Mutex::new(self.held().clone()))
    }
}

/// The Gram matrix of a block of rows: `X_b^T X_b`, `X_b^T y_b`,
/// `y_b^T y_b`.
#[derive(Debug, Clone)]
pub struct RowsGram {
    /// `X_b^T X_b`.
    pub gram: DMatrix<f64>,
    /// `X_b^T y_b`.
    pub xty: DVector<f64>,
    /// `y_b^T y_b`.
    pub yy: f64,
}

/// A joint fit of a subset of terms.
#[derive(Debug, Clone)]
pub struct Solution {
    /// Per term of the subset (in its order), its free parameters.
    pub theta: Vec<Vec<f64>>,
    /// Their standard deviations.
    pub std: Vec<Vec<f64>>,
    /// Whitened residual sum of squares.
    pub sse: f64,
    /// Parameters counted.
    pub k: usize,
}

impl Pool {
    /// Weighs the rows of joint `j` by `w[j]` on top of the whitening by
    /// the floor (replacing the weights before): the fitted parameters keep
    /// their units, the residual sums of squares are in the new weights.
    pub fn reweight(&mut self, w: &[f64]) {
        let joints = self.weights.len();
        if w.len() != joints || joints == 0 {
            return;
        }
        let s: Vec<f64> = (0..joints).map(|j| w[j] / self.weights[j]).collect();
        self.x.scale(&s);
        for (i, y) in self.y.iter_mut().enumerate() {
            *y *= s[i % joints];
        }
        self.finite_residual();
        self.xty = self.x.tr_mul(self.y.as_slice(), 0, self.y.len());
        self.yy = self.y.norm_squared();
        self.gram = penalised(&self.x, &self.prior, self.yy, self.strength);
        self.weights = w.to_vec();
        self.changed();
    }

    /// Keeps every column whole once the residual is not finite (a
    /// column kept at one joint's rows leaves out products of zeros with
    /// it: `cols.rs`).
    fn finite_residual(&mut self) {
        if !self.y.iter().all(|y| y.is_finite()) {
            self.x.keep_whole();
        }
    }

    /// Forgets the blocks' Gram matrices once the columns or the residual
    /// changed.
    fn changed(&mut self) {
        self.blocks
            .0
            .get_mut()
            .unwrap_or_else(|e| e.into_inner())
            .clear();
    }

    /// Per joint RMS of the residual `r` (of this pool's rows) in units of
    /// the noise floor (the weights taken out).
    pub fn floor_rms(&self, r: &DVector<f64>) -> Vec<f64> {
        let joints = self.weights.len().max(1);
        let rows = (r.len() / joints).max(1);
        (0..joints)
            .map(|j| {
                let ms: f64 = (0..rows).map(|i| r[i * joints + j].powi(2)).sum::<f64>();
                (ms / rows as f64).sqrt() / self.weights[j]
            })
            .collect()
    }

    /// Replaces the fixed column of term `t` (a motor side searched again).
    pub fn set_fixed(&mut self, t: usize, fit: Fit, col: Vec<f64>) {
        let Some(c) = self.terms[t].fixed else { return };
        let joints = self.weights.len().max(1);
        let col: Vec<f64> = col
            .iter()
            .enumerate()
            .map(|(i, x)| x * self.weights.get(i % joints).copied().unwrap_or(1.0))
            .collect();
        self.x.set(c, col);
        let v = self.x.against(c);
        self.gram.set_column(c, &v);
        self.gram.set_row(c, &v.transpose());
        self.xty[c] = self.x.dot_with(c, self.y.as_slice(), 0, self.y.len());
        self.terms[t].fit = fit;
        self.changed();
    }

    /// The weights and the prior's strength the pool was made with, as
    /// before a selection (the motor sides' columns stay as last searched).
    pub fn restart(&mut self) {
        let joints = self.weights.len();
        self.reweight(&vec![1.0; joints]);
        self.set_strength(prior::STRENGTHS[0]);
    }

    /// Sets the prior's strength (the Gram matrix follows).
    pub fn set_strength(&mut self, strength: f64) {
        // Only the links' part changes: `X^T X` is not formed again.
        if self.prior.links.shape() == self.gram.shape() {
            let n = self.x.nrows();
            let change = weight(self.yy, n, strength) - weight(self.yy, n, self.strength);
            self.gram += &self.prior.links * change;
        }
        self.strength = strength;
    }

    /// `X^T X` with the prior.
    pub fn gram(&self) -> &DMatrix<f64> {
        &self.gram
    }

    /// `X^T y`.
    pub fn xty(&self) -> &DVector<f64> {
        &self.xty
    }

    /// `y^T y`: the nominal model's whitened sum of squares.
    pub fn yy(&self) -> f64 {
        self.yy
    }

    /// Per joint, the weight of its rows on top of the whitening.
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }

    /// The prior toward the nominal model.
    pub fn prior(&self) -> &Prior {
        &self.prior
    }

    /// The prior's strength.
    pub fn strength(&self) -> f64 {
        self.strength
    }

    /// The Gram matrix of rows `a..z` (formed once for the columns and
    /// residual as they are, then kept).
    pub fn rows_gram(&self, a: usize, z: usize) -> RowsGram {
        if let Some((.., g)) = self.blocks.held().iter().find(|b| (b.0, b.1) == (a, z)) {
            return g.clone();
        }
        let yb = self.y.rows(a, z - a);
        let g = RowsGram {
            gram: self.x.gram(a, z),
            xty: self.x.tr_mul(self.y.as_slice(), a, z),
            yy: yb.norm_squared(),
        };
        let mut held = self.blocks.held();
        if held.len() >= BLOCKS {
            held.remove(0);
        }
        held.push((a, z, g.clone()));
        g
    }

    /// The pool of every row but those of `rows` (`n - removed` rows), from
    /// the Gram matrices alone: what a fit on the other blocks of time
    /// solves.
    pub fn without(&self, rows: &RowsGram, removed: usize) -> Pool {
        Pool {
            x: Cols::new(0, self.weights.len()),
            y: DVector::zeros(self.n() - removed),
            gram: &self.gram - &rows.gram,
            xty: &self.xty - &rows.xty,
            yy: self.yy - rows.yy,
            terms: self.terms.clone(),
            weights: self.weights.clone(),
            prior: self.prior.clone(),
            strength: self.strength,
            blocks: Blocks::default(),
        }
    }

    /// Makes `rest` (this pool [`without`](Pool::without) `rows`) follow a
    /// change of this pool's prior strength.
    pub fn follow_without(&self, rest: &mut Pool, rows: &RowsGram) {
        rest.gram = &self.gram - &rows.gram;
        rest.strength = self.strength;
    }

    /// Replaces the prior (the Gram matrix follows).
    #[cfg(test)]
    pub fn set_prior(&mut self, prior: Prior) {
        self.prior = prior;
        self.gram = penalised(&self.x, &self.prior, self.yy, self.strength);
    }

    /// Rows in the fit.
    pub fn n(&self) -> usize {
        self.y.len()
    }

    /// The whitened residual left by `set` with parameters `sol`.
    pub fn residual(&self, set: &[usize], sol: &Solution) -> DVector<f64> {
        let mut r = self.y.clone();
        for (i, &t) in set.iter().enumerate() {
            let term = &self.terms[t];
            for (c, th) in term.cols.iter().zip(&sol.theta[i]) {
                self.x.axpy(*c, -th, &mut r);
            }
            if let Some(f) = term.fixed {
                self.x.sub_from(f, &mut r);
            }
        }
        r
    }
}

/// `X^T X` plus the prior's matrix at its weight for a residual of sum of
/// squares `yy` and a prior of `strength` (`prior.rs`).
fn penalised(x: &Cols, p: &Prior, yy: f64, strength: f64) -> DMatrix<f64> {
    let mut g = x.gram(0, x.nrows());
    p.add_to(&mut g, yy, x.nrows(), strength);
    g
}

/// A term of `cols` for unit tests (`nonneg`: which are held >= 0;
/// `fixed`: a column of its own searched fit).
#[cfg(test)]
pub(crate) fn test_term(
    c: Candidate,
    cols: Vec<usize>,
    nonneg: Vec<bool>,
    fixed: Option<usize>,
) -> Term {
    let k = cols.len().max(fixed.map_or(0, |_| 3));
    Term {
        fit: Fit {
            candidate: c,
            theta: vec![],
            std: vec![],
            motor: None,
            motor_std: None,
            sse: 0.0,
            k,
        },
        limit: vec![f64::INFINITY; cols.len()],
        lower: nonneg
            .iter()
            .map(|&n| if n { 0.0 } else { f64::NEG_INFINITY })
            .collect(),
        cols,
        fixed,
        k,
        link: None,
        window: None,
    }
}

/// The pool of columns `x` against `y` for unit tests: no prior, `joints`
/// joints of weight 1.
#[cfg(test)]
pub(crate) fn test_pool(x: DMatrix<f64>, y: DVector<f64>, terms: Vec<Term>, joints: usize) -> Pool {
    Pool {
        gram: x.tr_mul(&x),
        xty: x.tr_mul(&y),
        yy: y.norm_squared(),
        x: Cols::from_matrix(&x, joints),
        y,
        terms,
        weights: vec![1.0; joints],
        prior: Prior::none(),
        strength: crate::diagnose::select::pool::prior::STRENGTHS[0],
        blocks: Blocks::default(),
    }
}

#[cfg(test)]
mod tests;
