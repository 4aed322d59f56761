//! The matrix exponential of a block matrix, by scaling and squaring with a
//! diagonal Pade approximant (Golub & Van Loan, Matrix Computations,
//! Algorithm 11.3.1), on the stack, with no transcendental function.

use super::blocks::{solve, BlockMatrix};

/// Degree of the diagonal Pade approximant. With `||X||_inf <= 1/2` after
/// scaling, the (6, 6) approximant is the exponential of `X + E` with
/// `||E|| <= 3.4e-16 ||X||` (Golub & Van Loan's bound
/// `2^(3 - 2q) (q!)^2 / ((2q)! (2q + 1)!)`): exact to double precision.
const DEGREE: usize = 6;

/// `exp(x)`, or `None` when `x` is not finite or the result overflows.
pub(crate) fn expm<const N: usize, const B: usize>(
    x: &BlockMatrix<N, B, B>,
) -> Option<BlockMatrix<N, B, B>> {
    let norm = x.norm_inf();
    if !norm.is_finite() {
        return None;
    }
    // Smallest j with ||x / 2^j|| <= 1/2 (scaling by a power of two is exact).
    let (mut squarings, mut scale) = (0u32, 1.0f64);
    while norm * scale > 0.5 {
        squarings += 1;
        scale *= 0.5;
    }
    let a = x.scale(scale);
    let identity = BlockMatrix::<N, B, B>::identity();
    let (mut numer, mut denom) = (identity, identity);
    let (mut power, mut c) = (identity, 1.0);
    for k in 1..=DEGREE {
        c *= (DEGREE - k + 1) as f64 / (k * (2 * DEGREE - k + 1)) as f64;
        power = a * power;
        let term = power.scale(c);
        numer = numer + term;
        denom = if k % 2 == 0 {
            denom + term
        } else {
            denom - term
        };
    }
    let mut e = solve(denom, numer)?;
    for _ in 0..squarings {
        e = e * e;
    }
    match e.first_non_finite() {
        Some(_) => None,
        None => Some(e),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{DMatrix, Matrix2};

    #[test]
    fn exponential_of_a_rotation_generator_is_a_rotation() {
        // exp([[0, -w], [w, 0]] t) = [[cos wt, -sin wt], [sin wt, cos wt]], any size of wt.
        for wt in [1e-3, 0.4, 3.0, 40.0] {
            let mut x = BlockMatrix::<2, 1, 1>::zeros();
            x.blocks[0][0] = Matrix2::new(0.0, -wt, wt, 0.0);
            let e = expm(&x).expect("finite");
            let want = Matrix2::new(wt.cos(), -wt.sin(), wt.sin(), wt.cos());
            let err = (e.blocks[0][0] - want).abs().max();
            assert!(err < 1e-14 * wt.max(1.0), "wt = {wt}: {err:e}");
        }
    }

    #[test]
    fn exponential_agrees_with_nalgebra_on_a_full_matrix() {
        let mut x = BlockMatrix::<3, 2, 2>::zeros();
        for i in 0..6 {
            for j in 0..6 {
                x[(i, j)] = (1.3 * i as f64 - 0.7 * j as f64 + 0.2).sin() * 2.0;
            }
        }
        let ours = expm(&x).expect("finite");
        let theirs = DMatrix::from_fn(6, 6, |i, j| x[(i, j)]).exp();
        let scale = theirs.abs().max();
        let err = (0..6)
            .flat_map(|i| (0..6).map(move |j| (i, j)))
            .map(|(i, j)| (ours[(i, j)] - theirs[(i, j)]).abs())
            .fold(0.0, f64::max);
        assert!(err < 1e-13 * scale, "{err:e} of {scale}");
    }

    #[test]
    fn non_finite_input_gives_none() {
        let mut x = BlockMatrix::<1, 1, 1>::zeros();
        x[(0, 0)] = f64::NAN;
        assert!(expm(&x).is_none());
        x[(0, 0)] = 1e300; // e^(1e300) overflows
        assert!(expm(&x).is_none());
    }
}
