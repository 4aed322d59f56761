//! The float functions the generated code calls beside `+ - * /`: with
//! `std`, std's own (so the results are those of `x.sqrt()`, `x.tanh()`,
//! `x.powi(n)`, bit for bit); without it, `libm`'s (sqrt, tanh) and
//! compiler-rt's algorithm for `powi`. `core` has `abs` but none of these.

/// Square root (IEEE, correctly rounded either way).
///
/// ```
/// assert_eq!(dynamics_runtime::math::sqrt(2.25), 1.5);
/// ```
#[inline(always)]
pub fn sqrt(x: f64) -> f64 {
    #[cfg(feature = "std")]
    {
        x.sqrt()
    }
    #[cfg(not(feature = "std"))]
    {
        libm::sqrt(x)
    }
}

/// Hyperbolic tangent (the smoothed Coulomb friction `Fc tanh(qd / eps)`).
///
/// ```
/// let t = dynamics_runtime::math::tanh(0.5);
/// assert!((t - (1.0 - (-1.0f64).exp()) / (1.0 + (-1.0f64).exp())).abs() < 1e-16);
/// ```
#[inline(always)]
pub fn tanh(x: f64) -> f64 {
    #[cfg(feature = "std")]
    {
        x.tanh()
    }
    #[cfg(not(feature = "std"))]
    {
        libm::tanh(x)
    }
}

/// `x^n` for an integer `n` (`x.powi(n)`): repeated squaring.
///
/// ```
/// assert_eq!(dynamics_runtime::math::powi(2.0, -3), 0.125);
/// ```
#[inline(always)]
pub fn powi(x: f64, n: i32) -> f64 {
    #[cfg(feature = "std")]
    {
        x.powi(n)
    }
    #[cfg(not(feature = "std"))]
    {
        powi_by_squaring(x, n)
    }
}

/// compiler-rt's `__powidf2`, which `f64::powi` calls: the same products
/// in the same order, so the same result.
#[cfg(any(test, not(feature = "std")))]
#[inline]
fn powi_by_squaring(mut x: f64, n: i32) -> f64 {
    let mut e = n.unsigned_abs();
    let mut r = 1.0;
    loop {
        if e & 1 == 1 {
            r *= x;
        }
        e >>= 1;
        if e == 0 {
            break;
        }
        x *= x;
    }
    if n < 0 {
        1.0 / r
    } else {
        r
    }
}

/// `(sin x, cos x)` by the platform's functions: the rare arguments that
/// [`crate::trig`] does not reduce itself (huge or not finite).
#[inline]
pub(crate) fn sin_cos(x: f64) -> (f64, f64) {
    #[cfg(feature = "std")]
    {
        x.sin_cos()
    }
    #[cfg(not(feature = "std"))]
    {
        libm::sincos(x)
    }
}

#[cfg(test)]
mod tests {
    use super::powi_by_squaring;

    #[test]
    fn powi_kernel_is_std_powi_bit_for_bit() {
        let mut x = -3.7;
        while x < 3.7 {
            for n in [
                -9,
                -7,
                -5,
                -4,
                -1,
                0,
                1,
                4,
                5,
                7,
                13,
                31,
                i32::MIN,
                i32::MAX,
            ] {
                let n = core::hint::black_box(n);
                let (ours, std) = (powi_by_squaring(x, n), x.powi(n));
                assert!(
                    ours.to_bits() == std.to_bits() || (ours.is_nan() && std.is_nan()),
                    "{x}^{n}: {ours:e} vs {std:e}"
                );
            }
            x += 0.0137;
        }
        assert_eq!(powi_by_squaring(0.0, -2), f64::INFINITY);
    }
}
