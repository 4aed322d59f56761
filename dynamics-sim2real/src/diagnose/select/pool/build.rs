//! Building the pool: every fitted candidate as whitened columns over the
//! fit's rows (free columns for the linear ones, a fixed column for a
//! motor side), each link correction as the combinations the data
//! determine, and the Gram matrix with the prior (`prior.rs`).
//!
//! A candidate whose single fit is limited in time (`fit/window`) is two
//! terms of one family: on all the time, and its columns times the
//! indicator of the training window (two more parameters). The window was
//! found on the residual the candidate meets alone; beside the other
//! effects that residual changes, and the explanation chooses between
//! them (a resistance of the environment on all the time under a delay of
//! the whole motion, fitted alone, fits best in a window).

use nalgebra::{DVector, SVector};
use rayon::prelude::*;

use super::prior;
use super::{penalised, Cols, Pool, Term};
use crate::diagnose::candidates::{
    combined, linear_columns, link_basis, lower_bounds, moment_basis, whitened, Candidate,
    Prepared, EFFORT_SCALE_LIMIT,
};
use crate::diagnose::fit::{fixed_column, inside, window_of, Fit, Windows};

impl Pool {
    /// The pool of `fits` on `p` (every single fit, grid variants too;
    /// those limited in time by `windows` also on all the time) and
    /// of the link corrections whose whitened regressor columns are `links`
    /// (`[link][parameter]`, see `links.rs`; empty: none), with the prior
    /// toward the links' `nominal` parameters (`prior.rs`; empty: none on
    /// the links).
    pub fn new<const N: usize>(
        fits: &[Fit],
        windows: &Windows,
        links: &[Vec<Vec<f64>>],
        nominal: &[SVector<f64, 10>],
        p: &Prepared<N>,
    ) -> Pool {
        // Each column kept as it comes (at its joint's rows alone where it
        // is zero off one joint: `cols.rs`).
        let n = p.n();
        let mut cols = Cols::new(n, N);
        let mut terms = Vec::new();
        // The fits' columns made on the threads a few fits at a time (a
        // motor side's is a simulation over the whole record), kept in the
        // fits' order; at most a batch's columns held beside the pool's.
        let threads = rayon::current_num_threads().max(1);
        for batch in fits.chunks(2 * threads) {
            let made: Vec<Option<Made>> = batch.par_iter().map(|f| made(f, p)).collect();
            for (f, made) in batch.iter().zip(made) {
                let c = f.candidate;
                match made {
                    None => {}
                    Some(Made::Fixed(col)) => {
                        cols.push(col);
                        terms.push(Term {
                            fit: f.clone(),
                            cols: vec![],
                            lower: vec![],
                            limit: vec![],
                            fixed: Some(cols.ncols() - 1),
                            k: f.k,
                            link: None,
                            window: None,
                        });
                    }
                    Some(Made::Free(new)) => {
                        let window = window_of(windows, c);
                        let term = |cols: std::ops::Range<usize>, fit: Fit, window| Term {
                            cols: cols.collect(),
                            lower: lower_bounds(c, p),
                            limit: c
                                .linear_parameters()
                                .iter()
                                .map(|_| match c {
                                    Candidate::EffortScale(_) => EFFORT_SCALE_LIMIT,
                                    _ => f64::INFINITY,
                                })
                                .collect(),
                            fixed: None,
                            k: fit.k,
                            fit,
                            link: None,
                            window,
                        };
                        let at = cols.ncols();
                        let Some(w) = window else {
                            for c in new {
                                cols.push(c);
                            }
                            terms.push(term(at..cols.ncols(), f.clone(), None));
                            continue;
                        };
                        // The fit limited in time counts the window's two
                        // bounds (`fit_windowed`); on all the time, not.
                        let always = Fit {
                            k: f.k.saturating_sub(2),
                            ..f.clone()
                        };
                        let m = inside(p, &w);
                        let limited: Vec<Vec<f64>> = new
                            .iter()
                            .map(|c| c.iter().zip(&m).map(|(x, m)| x * m).collect())
                            .collect();
                        for c in new {
                            cols.push(c);
                        }
                        terms.push(term(at..cols.ncols(), always, None));
                        let at = cols.ncols();
                        for c in limited {
                            cols.push(c);
                        }
                        // Limited to its window, the term counts the two
                        // bounds once more on top of its single fit's count.
                        let mut fit = f.clone();
                        fit.k += 2;
                        terms.push(term(at..cols.ncols(), fit, Some(w)));
                    }
                }
            }
        }
        // Link inertial corrections: the combinations the data determine,
        // of all ten parameters and of the mass and centre of mass alone
        // (a link other than the tip's: there the payload with its centre
        // of mass is that term).
        for (l, lc) in links.iter().enumerate() {
            let tip = l + 1 == links.len();
            let bases = [link_basis(l, lc), moment_basis(l, lc).filter(|_| !tip)];
            for mut basis in bases.into_iter().flatten() {
                basis.tip = tip;
                let new = combined(lc, &basis);
                let at = cols.ncols();
                let r = new.len();
                for c in new {
                    cols.push(c);
                }
                terms.push(Term {
                    fit: Fit {
                        candidate: Candidate::Inertial(l),
                        theta: vec![],
                        std: vec![],
                        motor: None,
                        motor_std: None,
                        sse: f64::NAN,
                        k: r,
                    },
                    cols: (at..cols.ncols()).collect(),
                    lower: vec![f64::NEG_INFINITY; r],
                    limit: vec![f64::INFINITY; r],
                    fixed: None,
                    k: r,
                    link: Some(basis),
                    window: None,
                });
            }
        }
        let m = cols.ncols();
        let mut x = cols;
        let y = DVector::from_vec(whitened(p, |k| p.sig.residual[k]));
        if !y.iter().all(|v| v.is_finite()) {
            x.keep_whole();
        }
        let xty = x.tr_mul(y.as_slice(), 0, y.len());
        let yy = y.norm_squared();
        let prior = prior::Prior::new(&terms, m, nominal);
        let strength = prior::STRENGTHS[0];
        let gram = penalised(&x, &prior, yy, strength);
        Pool {
            x,
            y,
            gram,
            xty,
            yy,
            terms,
            weights: vec![1.0; N],
            prior,
            strength,
            blocks: Default::default(),
        }
    }
}

/// A fit's columns on the pool's rows.
enum Made {
    /// A motor side's fixed column.
    Fixed(Vec<f64>),
    /// A linear candidate's free columns.
    Free(Vec<Vec<f64>>),
}

/// The columns of `f` on `p`; `None` for a fit that failed or whose
/// columns are zero (nothing the pool could use).
fn made<const N: usize>(f: &Fit, p: &Prepared<N>) -> Option<Made> {
    if !f.sse.is_finite() {
        return None;
    }
    if f.motor.is_some() {
        let col = fixed_column(f, p);
        (!col.iter().all(|x| *x == 0.0)).then_some(Made::Fixed(col))
    } else if !f.candidate.linear_parameters().is_empty() {
        let new = linear_columns(f.candidate, p);
        (!new.iter().all(|c| c.iter().all(|x| *x == 0.0))).then_some(Made::Free(new))
    } else {
        None
    }
}
