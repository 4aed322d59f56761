//! Sine and cosine together, for the generated code.
//!
//! Generated dynamics spend most of their time in trigonometric functions
//! (a 3-joint arm's inertia matrix is ~70 flops beside two `sin_cos`
//! calls). `std`'s `f64::sin_cos` calls libm's `sin` and `cos` one after
//! the other; this evaluates both from one argument reduction with the
//! fdlibm kernels (`__kernel_sin`, `__kernel_cos`: minimax polynomials on
//! [-pi/4, pi/4], error below 1 ulp, in Estrin's form with fused
//! multiply-adds where the target has them) and a Cody-Waite reduction (pi/2
//! in three doubles with FMA, in fdlibm's parts without), accurate for
//! |x| < 2^20 pi/2. Larger or non-finite arguments go to `std` (to `libm`
//! without it).

// The polynomial and reduction constants are written with fdlibm's digits
// so that they can be checked against it; the extra digits round away.
#![allow(clippy::excessive_precision)]

use core::f64::consts::FRAC_2_PI;

use crate::fma::mul_add;

// Without FMA: pi/2 in parts with trailing zero bits, so that n * part is
// exact for the quotients used here (fdlibm's pio2_1, pio2_2), and the rest.
#[cfg(not(any(target_feature = "fma", target_arch = "aarch64")))]
pub(crate) const PIO2_1: f64 = 1.570_796_326_734_125_614_17e+00;
#[cfg(not(any(target_feature = "fma", target_arch = "aarch64")))]
pub(crate) const PIO2_2: f64 = 6.077_100_506_303_965_976_60e-11;
/// pi/2 - PIO2_1 - PIO2_2 (fdlibm's pio2_2t).
#[cfg(not(any(target_feature = "fma", target_arch = "aarch64")))]
pub(crate) const PIO2_2T: f64 = 2.022_266_248_795_950_631_54e-21;
// With FMA: pi/2 = FRAC_PI_2 + PIO2_LO + PIO2_TAIL, each the double
// nearest the rest.
#[cfg(any(target_feature = "fma", target_arch = "aarch64"))]
pub(crate) const PIO2_LO: f64 = 6.123_233_995_736_766e-17;
#[cfg(any(target_feature = "fma", target_arch = "aarch64"))]
pub(crate) const PIO2_TAIL: f64 = -1.497_384_904_859_169_8e-33;

pub(crate) const S1: f64 = -1.666_666_666_666_663_243_48e-01;
pub(crate) const S2: f64 = 8.333_333_333_322_489_461_24e-03;
pub(crate) const S3: f64 = -1.984_126_982_985_794_931_34e-04;
pub(crate) const S4: f64 = 2.755_731_370_707_006_767_89e-06;
pub(crate) const S5: f64 = -2.505_076_025_340_686_341_95e-08;
pub(crate) const S6: f64 = 1.589_690_995_211_550_102_21e-10;

pub(crate) const C1: f64 = 4.166_666_666_666_660_190_37e-02;
pub(crate) const C2: f64 = -1.388_888_888_887_410_957_49e-03;
pub(crate) const C3: f64 = 2.480_158_728_947_672_941_78e-05;
pub(crate) const C4: f64 = -2.755_731_435_139_066_330_35e-07;
pub(crate) const C5: f64 = 2.087_572_321_298_174_827_90e-09;
pub(crate) const C6: f64 = -1.135_964_755_778_819_482_65e-11;

/// 1.5 * 2^52: adding it rounds any |y| < 2^51 to an integer.
pub(crate) const ROUNDER: f64 = 6_755_399_441_055_744.0;

/// Largest |x| reduced here; beyond it `std` (or `libm`) is used.
pub(crate) const REDUCE_LIMIT: f64 = 1_647_099.0; // 2^20 * pi/2

/// `(sin x, cos x)` from one argument reduction.
///
/// ```
/// let (s, c) = dynamics_runtime::trig::sin_cos(1.0);
/// assert!((s - 1.0f64.sin()).abs() <= 2e-16);
/// assert!((c - 1.0f64.cos()).abs() <= 2e-16);
/// ```
#[inline]
// `!(|x| < limit)` is also true for NaN, which must go to `std` too.
#[allow(clippy::neg_cmp_op_on_partial_ord)]
pub fn sin_cos(x: f64) -> (f64, f64) {
    if !(x.abs() < REDUCE_LIMIT) {
        return crate::math::sin_cos(x);
    }
    let (bits, s, c) = reduced(x);
    let quadrant = (bits & 3) as usize;
    // Quadrant 0..3: (s, c), (c, -s), (-s, -c), (-c, s), as s a + c b with
    // a, b in {0, 1, -1} (exact): the factors depend only on n, so they are
    // ready before s and c, and neither a jump (the quadrant of a joint
    // angle is random) nor a trip through integer registers is on the path.
    (
        mul_add(s, SIN_S[quadrant], c * SIN_C[quadrant]),
        mul_add(s, COS_S[quadrant], c * COS_C[quadrant]),
    )
}

/// Lanes of [`sin_cos_n`]: four f64, one AVX2 register.
const LANES: usize = 4;

/// `(sin x_i, cos x_i)` of several angles at once, as [`sin_cos`] computes
/// them (same results), four lanes at a time: the compiler turns each
/// operation into one vector instruction, so all the joint angles of a
/// robot cost about two scalar `sin_cos` in instructions.
///
/// ```
/// let (s, c) = dynamics_runtime::trig::sin_cos_n([0.5, -2.0, 3.0]);
/// assert_eq!((s[1], c[1]), dynamics_runtime::trig::sin_cos(-2.0));
/// assert!((c[2] - 3.0f64.cos()).abs() <= 2e-16);
/// ```
// Always inlined: as a call, its arguments and results go through memory
// and the call itself sits at the head of every output's critical path.
#[inline(always)]
#[allow(clippy::neg_cmp_op_on_partial_ord)] // NaN must take the slow path
pub fn sin_cos_n<const N: usize>(x: [f64; N]) -> ([f64; N], [f64; N]) {
    let mut sin = [0.0; N];
    let mut cos = [0.0; N];
    if x.iter().any(|v| !(v.abs() < REDUCE_LIMIT)) {
        return one_by_one(x);
    }
    let mut k = 0;
    while k < N {
        let mut lane = [0.0; LANES];
        for (j, l) in lane.iter_mut().enumerate() {
            *l = if k + j < N { x[k + j] } else { 0.0 };
        }
        let (s, c) = lanes(lane);
        // Element by element, as the test above is a negated `any`: the
        // clippy-preferred forms (`copy_from_slice` of ranges, `all`) made
        // UR5's inertia matrix 40 % slower (74 -> 104 ns).
        #[allow(clippy::manual_memcpy)]
        for j in 0..LANES.min(N - k) {
            sin[k + j] = s[j];
            cos[k + j] = c[j];
        }
        k += LANES;
    }
    (sin, cos)
}

/// [`sin_cos`] of each angle: the rare case of a huge or non-finite one,
/// kept out of line.
#[cold]
#[inline(never)]
fn one_by_one<const N: usize>(x: [f64; N]) -> ([f64; N], [f64; N]) {
    let mut sin = [0.0; N];
    let mut cos = [0.0; N];
    for i in 0..N {
        (sin[i], cos[i]) = sin_cos(x[i]);
    }
    (sin, cos)
}

/// [`sin_cos`] lane-wise, the quadrant applied with bit masks (vector
/// integer operations; a table lookup per lane would be a gather).
#[inline(always)]
fn lanes(x: [f64; LANES]) -> ([f64; LANES], [f64; LANES]) {
    let mut bits = [0u64; LANES];
    let mut s = [0.0; LANES];
    let mut c = [0.0; LANES];
    for j in 0..LANES {
        (bits[j], s[j], c[j]) = reduced(x[j]);
    }
    let mut sin = [0.0; LANES];
    let mut cos = [0.0; LANES];
    for j in 0..LANES {
        let swap = 0u64.wrapping_sub(bits[j] & 1);
        let (sb, cb) = (s[j].to_bits(), c[j].to_bits());
        let sin_sign = ((bits[j] >> 1) & 1) << 63;
        let cos_sign = ((bits[j].wrapping_add(1) >> 1) & 1) << 63;
        sin[j] = f64::from_bits(((cb & swap) | (sb & !swap)) ^ sin_sign);
        cos[j] = f64::from_bits(((sb & swap) | (cb & !swap)) ^ cos_sign);
    }
    (sin, cos)
}

/// For |x| < [`REDUCE_LIMIT`]: the bits whose last two are the quadrant n
/// mod 4 (x = n pi/2 + r, |r| <= pi/4), sin r and cos r.
#[inline(always)]
fn reduced(x: f64) -> (u64, f64, f64) {
    // Round x 2/pi to the nearest integer n by adding 1.5 * 2^52: the sum's
    // last mantissa bits are n itself (two's complement), so neither a libm
    // `round` call (baseline x86-64 has no rounding instruction) nor an
    // integer conversion is needed.
    let shifted = mul_add(x, FRAC_2_PI, ROUNDER);
    let n = shifted - ROUNDER;
    let r = reduce(x, n);
    let z = r * r;
    // The kernels' polynomials in Estrin's form (pairs, then z^2 and z^4),
    // whose chain of dependent operations is half of Horner's: joint angles
    // are the first values of the generated code, so their latency is on
    // its critical path.
    let z2 = z * z;
    let z4 = z2 * z2;
    let ps = mul_add(
        z4,
        mul_add(z, S6, S5),
        mul_add(z2, mul_add(z, S4, S3), mul_add(z, S2, S1)),
    );
    let pc = mul_add(
        z4,
        mul_add(z, C6, C5),
        mul_add(z2, mul_add(z, C4, C3), mul_add(z, C2, C1)),
    );
    let s = mul_add(r * z, ps, r);
    // cos r = 1 - z/2 + z^2 pc, with w = 1 - z/2 rounded and its rounding
    // error added back (fdlibm's __kernel_cos).
    let hz = 0.5 * z;
    let w = 1.0 - hz;
    let c = w + mul_add(z2, pc, (1.0 - w) - hz);
    (shifted.to_bits(), s, c)
}

/// Factors of s and c in sin x and cos x, by quadrant.
const SIN_S: [f64; 4] = [1.0, 0.0, -1.0, 0.0];
const SIN_C: [f64; 4] = [0.0, 1.0, 0.0, -1.0];
const COS_S: [f64; 4] = [0.0, -1.0, 0.0, 1.0];
const COS_C: [f64; 4] = [1.0, 0.0, -1.0, 0.0];

/// x - n pi/2 for an integer n with |n| < 2^20.
#[inline(always)]
fn reduce(x: f64, n: f64) -> f64 {
    // A fused multiply-add rounds x - n part once, after the exact
    // product, so the parts need no trailing zero bits: full doubles, whose
    // three terms hold pi/2 to 2^-160 (r to about an ulp of itself, also
    // near multiples of pi/2, where it is tiny). Without FMA, fdlibm's
    // parts keep every product exact, and the rounding error of the second
    // subtraction is carried into the third (fdlibm's rem_pio2 "2nd
    // iteration"), without which a tiny r loses most of its digits.
    #[cfg(any(target_feature = "fma", target_arch = "aarch64"))]
    {
        let r = mul_add(-n, core::f64::consts::FRAC_PI_2, x);
        mul_add(-n, PIO2_TAIL, mul_add(-n, PIO2_LO, r))
    }
    #[cfg(not(any(target_feature = "fma", target_arch = "aarch64")))]
    {
        let t = x - n * PIO2_1;
        let w = n * PIO2_2;
        let r = t - w;
        r - (n * PIO2_2T - ((t - r) - w))
    }
}

#[cfg(test)]
mod tests {
    use super::{sin_cos, sin_cos_n};

    fn ulps(a: f64, b: f64) -> f64 {
        (a - b).abs() / f64::EPSILON / b.abs().max(f64::MIN_POSITIVE)
    }

    #[test]
    fn agrees_with_std_to_a_few_ulp() {
        let mut worst: f64 = 0.0;
        let mut abs_worst: f64 = 0.0;
        let mut x = -1000.0;
        while x < 1000.0 {
            let (s, c) = sin_cos(x);
            let (es, ec) = x.sin_cos();
            abs_worst = abs_worst.max((s - es).abs()).max((c - ec).abs());
            if es.abs() > 1e-3 {
                worst = worst.max(ulps(s, es));
            }
            if ec.abs() > 1e-3 {
                worst = worst.max(ulps(c, ec));
            }
            x += 0.000_731;
        }
        assert!(abs_worst < 5e-16, "absolute error {abs_worst:e}");
        assert!(worst < 4.0, "{worst} ulp");
    }

    #[test]
    fn near_multiples_of_half_pi_keep_the_small_result_accurate() {
        // There the reduced argument is tiny and the result is all
        // cancellation: the reduction must give it to a few ulp of itself.
        let mut worst: f64 = 0.0;
        for k in -4000i32..=4000 {
            let centre = f64::from(k) * core::f64::consts::FRAC_PI_2;
            let mut x = centre;
            for _ in 0..3 {
                let (s, c) = sin_cos(x);
                let (es, ec) = x.sin_cos();
                worst = worst.max(ulps(s, es)).max(ulps(c, ec));
                x = x.next_up();
            }
        }
        assert!(worst < 4.0, "{worst} ulp");
    }

    #[test]
    fn lanes_give_the_scalar_results() {
        let mut x = -40.0;
        while x < 40.0 {
            let xs = [x, x + 0.37, -x * 1.9, x * 0.11, x - 2.5, x + 7.0, 0.5 * x];
            let (s, c) = sin_cos_n(xs);
            for i in 0..xs.len() {
                assert_eq!((s[i], c[i]), sin_cos(xs[i]), "x = {}", xs[i]);
            }
            x += 0.013;
        }
        let (s, c) = sin_cos_n([1.0, 1e12, f64::NAN]);
        assert_eq!((s[0], c[0]), sin_cos(1.0));
        assert_eq!((s[1], c[1]), 1e12f64.sin_cos());
        assert!(s[2].is_nan() && c[2].is_nan());
        assert_eq!(sin_cos_n::<0>([]), ([], []));
    }

    #[test]
    fn special_values() {
        assert_eq!(sin_cos(0.0), (0.0, 1.0));
        assert!(sin_cos(f64::NAN).0.is_nan());
        assert!(sin_cos(f64::INFINITY).1.is_nan());
        let big = 1e12;
        assert_eq!(sin_cos(big), big.sin_cos());
        let (s, c) = sin_cos(core::f64::consts::FRAC_PI_2);
        assert!((s - 1.0).abs() < 1e-16 && c.abs() < 1e-16);
    }
}
