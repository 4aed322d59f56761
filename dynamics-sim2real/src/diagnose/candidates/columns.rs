//! A candidate's columns on the fit's rows, whitened by the noise floor:
//! what the joint fits of the compound explanation work on.

use nalgebra::SVector;

use super::candidate::Candidate;
use super::prepared::Prepared;

/// Whitened column of the rows of `p` from per-sample efforts `f`.
pub fn whitened<const N: usize>(p: &Prepared<N>, f: impl Fn(usize) -> SVector<f64, N>) -> Vec<f64> {
    let mut out = Vec::with_capacity(p.n());
    for &k in &p.rows {
        let v = f(k);
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
