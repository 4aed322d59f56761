//! The joint fit of a subset with every link correction a physical body.
//!
//! The least-squares fit ([`Pool::solve`]) may ask a link for a change no
//! body has (a mass below zero, an inertia that breaks the triangle
//! inequalities) even after the combinations the data leave free are
//! filled in (`inertial::complete`). The fit's nearest physical one, in
//! the metric of the data, is the correction the data allow: the links'
//! determined coordinates are moved to the nearest point of the physical
//! set in the fit's curvature with the other terms profiled out
//! (`inertial::nearest_in_metric`), held there, and the other terms
//! fitted again.

use nalgebra::{DMatrix, DVector, SVector};

use super::{independent, Pool, Solution};
use crate::diagnose::candidates::{delta, LinkBasis};
use crate::inertial::{complete, nearest_in_metric, MetricLink};

/// Whether link correction `theta` along the link's determined
/// combinations `v` leaves the link with nominal parameters `nominal` a
/// physical body once the combinations the data leave free (`free`) are
/// moved, without projecting or scaling back the determined part.
pub(in crate::diagnose) fn leaves_a_body(
    nominal: &SVector<f64, 10>,
    change: &SVector<f64, 10>,
    free: &DMatrix<f64>,
) -> bool {
    match complete(nominal, change, free) {
        Some(c) => !c.projected && c.scale >= 1.0 - 1e-9,
        None => false,
    }
}

/// Whether link correction `theta` (combinations `b`) leaves the link with
/// nominal parameters `nominal` a physical body once the combinations the
/// data do not determine are moved ([`leaves_a_body`]; unknown nominal
/// parameters: assumed).
pub(in crate::diagnose) fn is_body(
    b: &LinkBasis,
    theta: &[f64],
    nominal: Option<&SVector<f64, 10>>,
) -> bool {
    nominal.is_none_or(|nom| leaves_a_body(nom, &delta(b, theta), &b.free_combinations()))
}

impl Pool {
    /// The joint fit of `set` ([`Pool::solve`]) with every link correction
    /// whose completion is not a physical body moved to the nearest
    /// physical one in the metric of the data; `nominal` the links'
    /// nominal inertial parameters (a link without them is left as
    /// fitted). The moved corrections keep the standard deviations of the
    /// free fit.
    pub fn solve_physical(&self, set: &[usize], nominal: &[SVector<f64, 10>]) -> Solution {
        let sol = self.solve(set);
        // (set position, link) of the corrections that leave no body.
        let bad: Vec<usize> = set
            .iter()
            .enumerate()
            .filter(|(i, &t)| {
                self.terms[t]
                    .link
                    .as_ref()
                    .is_some_and(|b| !is_body(b, &sol.theta[*i], nominal.get(b.link)))
            })
            .map(|(i, _)| i)
            .collect();
        if bad.is_empty() {
            return sol;
        }
        // Every free column of the set in the order `solve` takes them, and
        // which of them `solve` keeps (a column the ones before it span is
        // left out, at zero).
        let mut owner: Vec<(usize, usize)> = Vec::new();
        let mut cols: Vec<usize> = Vec::new();
        for (i, &t) in set.iter().enumerate() {
            for (m, &c) in self.terms[t].cols.iter().enumerate() {
                owner.push((i, m));
                cols.push(c);
            }
        }
        let active = independent(&self.gram, &cols);
        let (mut on_links, mut others) = (Vec::new(), Vec::new());
        for (f, &(i, _)) in owner.iter().enumerate() {
            if !active[f] {
                continue;
            }
            if bad.contains(&i) {
                on_links.push(f);
            } else {
                others.push(f);
            }
        }
        // The links' coordinates: each bad link's active combinations.
        let mut links = Vec::new();
        for &i in &bad {
            let Some(b) = &self.terms[set[i]].link else {
                continue;
            };
            let Some(nom) = nominal.get(b.link) else {
                continue;
            };
            let mine: Vec<usize> = on_links
                .iter()
                .filter(|&&f| owner[f].0 == i)
                .map(|&f| owner[f].1)
                .collect();
            links.push(MetricLink {
                nominal: *nom,
                determined: b.v.select_columns(&mine),
                free: b.free_combinations(),
            });
        }
        // The fit's curvature in the links' coordinates, the others
        // profiled out: the Schur complement of their block.
        let g = |a: &[usize], b: &[usize]| {
            DMatrix::from_fn(a.len(), b.len(), |r, c| self.gram[(cols[a[r]], cols[b[c]])])
        };
        let mut s = g(&on_links, &on_links);
        if !others.is_empty() {
            let goo = g(&others, &others);
            let d = goo.diagonal().map(|v| v.max(1e-300).sqrt());
            let scaled = DMatrix::from_fn(others.len(), others.len(), |r, c| {
                goo[(r, c)] / (d[r] * d[c]) + if r == c { 1e-12 } else { 0.0 }
            });
            let Some(ch) = scaled.cholesky() else {
                return sol;
            };
            let glo = g(&on_links, &others);
            let scaled_lo = DMatrix::from_fn(glo.nrows(), glo.ncols(), |r, c| glo[(r, c)] / d[c]);
            s -= &scaled_lo * ch.solve(&scaled_lo.transpose());
        }
        let s = (&s + s.transpose()) * 0.5;
        let x0 = DVector::from_iterator(
            on_links.len(),
            on_links.iter().map(|&f| sol.theta[owner[f].0][owner[f].1]),
        );
        let Some(x) = nearest_in_metric(&links, &s, &x0) else {
            return sol;
        };
        let preset: Vec<(usize, f64)> = on_links
            .iter()
            .zip(x.iter())
            .map(|(&f, &v)| (cols[f], v))
            .collect();
        let mut held = self.solve_held(set, &preset);
        for &i in &bad {
            held.std[i].clone_from(&sol.std[i]);
        }
        held
    }
}
