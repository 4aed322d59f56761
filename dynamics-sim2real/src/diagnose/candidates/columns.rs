//! A candidate's columns on the fit's rows, whitened by the noise floor,
//! and the least values of their coefficients: what the joint fits of the
//! compound explanation work on.

use nalgebra::SVector;

use super::candidate::Candidate;
use super::prepared::Prepared;

/// Whitened column of the rows of `p` from per-sample efforts `f`.
pub fn whitened<const N: usize>(p: &Prepared<N>, f: impl Fn(usize) -> SVector<f64, N>) -> Vec<f64> {
    whitened_rows(p, |_, k| f(k))
}

/// [`whitened`] of `f(i, k)` at row `i` (sample `k`) of `p`.
pub fn whitened_rows<const N: usize>(
    p: &Prepared<N>,
    f: impl Fn(usize, usize) -> SVector<f64, N>,
) -> Vec<f64> {
    let mut out = Vec::with_capacity(p.n());
    for (i, &k) in p.rows.iter().enumerate() {
        let v = f(i, k);
        for j in 0..N {
            let x = v[j] / p.sig.floor[j];
            out.push(if x.is_finite() { x } else { 0.0 });
        }
    }
    out
}

/// The free columns of a linear candidate on the rows of `p`.
pub fn linear_columns<const N: usize>(c: Candidate, p: &Prepared<N>) -> Vec<Vec<f64>> {
    (0..c.linear_parameters().len())
        .map(|i| whitened(p, |k| c.columns(&p.sig, &p.basis, k)[i]))
        .collect()
}

/// The least values of a linear candidate's parameters: none, or 0 for a
/// sign-constrained one, except that a friction correction may take away
/// the friction the nominal model carries at its joint (its Coulomb level
/// for Coulomb and Stribeck's `fc`, its viscous coefficient for viscous),
/// and a payload the mass of the body that carries the tip (`Basis::tip_mass`).
pub fn lower_bounds<const N: usize>(c: Candidate, p: &Prepared<N>) -> Vec<f64> {
    let (coulomb, viscous) = &p.basis.friction;
    c.linear_parameters()
        .iter()
        .enumerate()
        .map(|(i, &(_, nonneg))| match (c, i) {
            (Candidate::Payload | Candidate::PayloadCom(_), 0) => -p.basis.tip_mass,
            _ if !nonneg => f64::NEG_INFINITY,
            (Candidate::Coulomb(j, _) | Candidate::Stribeck(j, _), 0) => -coulomb[j],
            (Candidate::Viscous(j), 0) => -viscous[j],
            _ => 0.0,
        })
        .collect()
}
