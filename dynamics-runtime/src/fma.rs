//! Fused multiply-add for the generated code.
//!
//! rustc never contracts `a * b + c` into one instruction (C compilers do by
//! default), so the generated sums call [`mul_add`] for each scaled term.
//! Where the target has FMA (`-C target-cpu=native` on any x86-64 since
//! 2013, aarch64 always) it is one instruction with one rounding; elsewhere
//! it is the plain `a * b + c`, never the slow software `fma` of libm.
//!
//! Without `std` (`core` has no `f64::mul_add`), a target with FMA gets
//! `libm::fma`: the same correctly rounded result, by the instruction too,
//! but as a call (on x86-64 through a pointer chosen at the first call, so
//! not inlined); a Cortex-M4F or any target without FMA gets `a * b + c`
//! as with `std`.

/// `a * b + c`: fused (one rounding) where the target has FMA, else two
/// operations.
///
/// ```
/// assert_eq!(dynamics_runtime::fma::mul_add(2.0, 3.0, 1.0), 7.0);
/// ```
#[inline(always)]
pub fn mul_add(a: f64, b: f64, c: f64) -> f64 {
    #[cfg(all(any(target_feature = "fma", target_arch = "aarch64"), feature = "std"))]
    {
        a.mul_add(b, c)
    }
    #[cfg(all(
        any(target_feature = "fma", target_arch = "aarch64"),
        not(feature = "std")
    ))]
    {
        libm::fma(a, b, c)
    }
    #[cfg(not(any(target_feature = "fma", target_arch = "aarch64")))]
    {
        a * b + c
    }
}

#[cfg(test)]
mod tests {
    use super::mul_add;

    #[test]
    fn is_a_times_b_plus_c_to_one_rounding() {
        // 0.1 * 10 - 1 is 0 with two roundings and 2^-54 with one.
        let r = mul_add(0.1, 10.0, -1.0);
        if cfg!(any(target_feature = "fma", target_arch = "aarch64")) {
            assert_eq!(r, 0.1f64.mul_add(10.0, -1.0));
            assert!(r != 0.0);
        } else {
            assert_eq!(r, 0.0);
        }
        assert_eq!(mul_add(-1.5, 4.0, 0.5), -5.5);
    }
}
