//! Several states in one value: the lane types the emitted dynamics run
//! over for the batch functions of [`crate::batch`].
//!
//! `robot!` emits every batch-capable output twice: once over `f64` (the
//! methods of [`Robot`](crate::Robot)), once generic over [`Lanes`] (the
//! `*_lanes` methods), the same straight-line code with each `f64` a lane
//! value. Over the x86-64 lane types (four states in an AVX2 register,
//! eight in an AVX-512 one; `x86.rs`) each operation is one vector
//! instruction.
//!
//! Those types are `core::arch` vectors, their operations the intrinsics
//! (`_mm256_fmadd_pd`, ...): values of them exist only inside the batch
//! functions compiled for AVX2 or AVX-512 (`#[target_feature]`), which
//! [`crate::batch`] calls after the run-time CPU check, so a binary built
//! for baseline x86-64 still uses the vector units. Intrinsics rather than
//! arrays of `f64` that LLVM might vectorise: over the thousands of
//! operations of a 7-joint arm's outputs, arrays came out mostly scalar
//! (inverse dynamics of 1000 Panda states 94 us in arrays of four, 98 us
//! one state at a time), intrinsics are one instruction each by
//! construction. The types are private to the crate: no code outside can
//! make a value of them on a CPU without the instructions.
//!
//! Over `f64` every function here is the scalar code's own (the results
//! are those of the scalar methods, bit for bit). Over the vector types the
//! multiply-adds are fused (one rounding) also where the scalar code's are
//! not (a build without FMA): there results agree to a few ulp.

use core::ops::{Add, Div, Mul, Neg, Sub};

use nalgebra::{SMatrix, SVector};

use crate::{fma, math, trig};

/// The widest lane type.
pub(crate) const MAX_WIDTH: usize = 8;

#[cfg(target_arch = "x86_64")]
mod x86;
#[cfg(target_arch = "x86_64")]
pub(crate) use x86::{F64x4, F64x8};

mod sealed {
    /// Only the lane types of this crate are [`super::Lanes`] (their
    /// width is at most [`super::MAX_WIDTH`]).
    pub trait Sealed {}
    impl Sealed for f64 {}
    #[cfg(target_arch = "x86_64")]
    impl Sealed for super::F64x4 {}
    #[cfg(target_arch = "x86_64")]
    impl Sealed for super::F64x8 {}
}

/// A value of one or more states: `f64` (one) here, four or eight inside
/// the batch functions (see the module doc).
///
/// ```
/// use dynamics_runtime::lanes::Lanes;
/// let y = dynamics_runtime::lanes::mul_add(2.0, f64::splat(3.0), f64::from_fn(|_| 1.0));
/// assert_eq!((y.lane(0), <f64 as Lanes>::WIDTH), (7.0, 1));
/// ```
pub trait Lanes:
    sealed::Sealed
    + Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// States in one value.
    const WIDTH: usize;
    /// NaN in every lane.
    const NAN: Self;
    /// Infinity in every lane.
    const INFINITY: Self;
    /// `x` in every lane.
    fn splat(x: f64) -> Self;
    /// Lane `i` is `f(i)`.
    fn from_fn(f: impl FnMut(usize) -> f64) -> Self;
    /// The value of lane `i` (`i < WIDTH`).
    fn lane(self, i: usize) -> f64;
    /// `|x|` lane-wise.
    fn abs(self) -> Self;
    /// `self * b + c` lane-wise (see [`mul_add`]).
    fn mul_add(self, b: Self, c: Self) -> Self;
    /// `(sin x, cos x)` lane-wise (see [`sin_cos`]).
    fn sin_cos(self) -> (Self, Self);
    /// [`Lanes::sin_cos`] of several values.
    fn sin_cos_n<const K: usize>(x: [Self; K]) -> ([Self; K], [Self; K]);
    /// Square root lane-wise.
    fn sqrt(self) -> Self;
    /// Hyperbolic tangent lane-wise.
    fn tanh(self) -> Self;
    /// `x^n` lane-wise.
    fn powi(self, n: i32) -> Self;
    /// `(sin x, cos x)` from the parts of the reduction
    /// (`trig::reduced_lanes`): the quadrant in the last two mantissa bits
    /// of `shifted` selects and signs `s` and `c`, with bit masks.
    #[doc(hidden)]
    fn by_quadrant(shifted: Self, s: Self, c: Self) -> (Self, Self);
    /// Writes lane `i` of every value of `values` into `field(&mut
    /// states[i])` (the same shape), for the first `states.len()` lanes
    /// (at most `WIDTH`). The shapes are types, so that the bounds of
    /// every write are known when the function is compiled.
    #[doc(hidden)]
    fn store_states<T, const R: usize, const C: usize>(
        values: &[[Self; R]; C],
        states: &mut [T],
        field: impl Fn(&mut T) -> &mut [[f64; R]; C],
    );
    /// The values `field(&states[i])` in lanes: lane `i` of value `j` is
    /// entry `j` of state `i`, for the first `states.len()` lanes (at
    /// least one, at most `WIDTH`); lanes past them repeat the last state.
    #[doc(hidden)]
    fn load_states<T, const N: usize>(states: &[T], field: impl Fn(&T) -> &[f64; N]) -> [Self; N];
}

impl Lanes for f64 {
    const WIDTH: usize = 1;
    const NAN: Self = f64::NAN;
    const INFINITY: Self = f64::INFINITY;
    #[inline(always)]
    fn splat(x: f64) -> Self {
        x
    }
    #[inline(always)]
    fn from_fn(mut f: impl FnMut(usize) -> f64) -> Self {
        f(0)
    }
    #[inline(always)]
    fn lane(self, _: usize) -> f64 {
        self
    }
    #[inline(always)]
    fn abs(self) -> Self {
        f64::abs(self)
    }
    #[inline(always)]
    fn mul_add(self, b: Self, c: Self) -> Self {
        fma::mul_add(self, b, c)
    }
    #[inline(always)]
    fn sin_cos(self) -> (Self, Self) {
        trig::sin_cos(self)
    }
    #[inline(always)]
    fn sin_cos_n<const K: usize>(x: [Self; K]) -> ([Self; K], [Self; K]) {
        trig::sin_cos_n(x)
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        math::sqrt(self)
    }
    #[inline(always)]
    fn tanh(self) -> Self {
        math::tanh(self)
    }
    #[inline(always)]
    fn powi(self, n: i32) -> Self {
        math::powi(self, n)
    }
    #[inline(always)]
    fn by_quadrant(shifted: Self, s: Self, c: Self) -> (Self, Self) {
        let bits = shifted.to_bits();
        let swap = 0u64.wrapping_sub(bits & 1);
        let (sb, cb) = (s.to_bits(), c.to_bits());
        let sin_sign = ((bits >> 1) & 1) << 63;
        let cos_sign = ((bits.wrapping_add(1) >> 1) & 1) << 63;
        (
            f64::from_bits(((cb & swap) | (sb & !swap)) ^ sin_sign),
            f64::from_bits(((sb & swap) | (cb & !swap)) ^ cos_sign),
        )
    }
    #[inline(always)]
    fn store_states<T, const R: usize, const C: usize>(
        values: &[[Self; R]; C],
        states: &mut [T],
        field: impl Fn(&mut T) -> &mut [[f64; R]; C],
    ) {
        if let [state] = states {
            *field(state) = *values;
        }
    }
    #[inline(always)]
    fn load_states<T, const N: usize>(states: &[T], field: impl Fn(&T) -> &[f64; N]) -> [Self; N] {
        states.first().map_or([0.0; N], |s| *field(s))
    }
}

/// The scalar sine/cosine kernel's reduction (`trig::reduced`) over lanes
/// (the same operations in the same order, with
/// the lane type's multiply-add): the rounded quotient's bits as a float
/// (`shifted`, whose last two mantissa bits are the quadrant), sin r and
/// cos r. The caller checks that every lane is below `trig::REDUCE_LIMIT`.
#[inline(always)]
#[cfg(target_arch = "x86_64")]
fn reduced<L: Lanes>(x: L) -> (L, L, L) {
    use core::f64::consts::FRAC_2_PI;
    use trig::*;
    let k = L::splat;
    let shifted = x.mul_add(k(FRAC_2_PI), k(ROUNDER));
    let n = shifted - k(ROUNDER);
    #[cfg(any(target_feature = "fma", target_arch = "aarch64"))]
    let r = {
        let r = (-n).mul_add(k(core::f64::consts::FRAC_PI_2), x);
        (-n).mul_add(k(PIO2_TAIL), (-n).mul_add(k(PIO2_LO), r))
    };
    #[cfg(not(any(target_feature = "fma", target_arch = "aarch64")))]
    let r = {
        let t = x - n * k(PIO2_1);
        let w = n * k(PIO2_2);
        let r = t - w;
        r - (n * k(PIO2_2T) - ((t - r) - w))
    };
    let z = r * r;
    let z2 = z * z;
    let z4 = z2 * z2;
    let ps = z4.mul_add(
        z.mul_add(k(S6), k(S5)),
        z2.mul_add(z.mul_add(k(S4), k(S3)), z.mul_add(k(S2), k(S1))),
    );
    let pc = z4.mul_add(
        z.mul_add(k(C6), k(C5)),
        z2.mul_add(z.mul_add(k(C4), k(C3)), z.mul_add(k(C2), k(C1))),
    );
    let s = (r * z).mul_add(ps, r);
    let hz = k(0.5) * z;
    let w = k(1.0) - hz;
    let c = w + z2.mul_add(pc, (k(1.0) - w) - hz);
    (shifted, s, c)
}

/// `a * b + c` lane-wise: over `f64` the scalar code's
/// [`fma::mul_add`], over the lane types fused.
///
/// ```
/// assert_eq!(dynamics_runtime::lanes::mul_add(2.0, 3.0, 1.0), 7.0);
/// ```
#[inline(always)]
pub fn mul_add<L: Lanes>(a: L, b: L, c: L) -> L {
    a.mul_add(b, c)
}

/// `(sin x, cos x)` lane-wise, by the kernels of [`trig`].
///
/// ```
/// assert_eq!(dynamics_runtime::lanes::sin_cos(1.0), dynamics_runtime::trig::sin_cos(1.0));
/// ```
#[inline(always)]
pub fn sin_cos<L: Lanes>(x: L) -> (L, L) {
    x.sin_cos()
}

/// [`sin_cos`] of several values (over `f64`, [`trig::sin_cos_n`]).
///
/// ```
/// let (s, c) = dynamics_runtime::lanes::sin_cos_n([0.5, 1.0]);
/// assert_eq!((s[1], c[1]), dynamics_runtime::trig::sin_cos(1.0));
/// ```
#[inline(always)]
pub fn sin_cos_n<L: Lanes, const K: usize>(x: [L; K]) -> ([L; K], [L; K]) {
    L::sin_cos_n(x)
}

/// Square root lane-wise ([`math::sqrt`] in each lane).
///
/// ```
/// assert_eq!(dynamics_runtime::lanes::sqrt(2.25), 1.5);
/// ```
#[inline(always)]
pub fn sqrt<L: Lanes>(x: L) -> L {
    x.sqrt()
}

/// Hyperbolic tangent lane-wise ([`math::tanh`] in each lane).
///
/// ```
/// assert_eq!(dynamics_runtime::lanes::tanh(0.5), dynamics_runtime::math::tanh(0.5));
/// ```
#[inline(always)]
pub fn tanh<L: Lanes>(x: L) -> L {
    x.tanh()
}

/// `x^n` lane-wise ([`math::powi`] in each lane).
///
/// ```
/// assert_eq!(dynamics_runtime::lanes::powi(2.0, -3), 0.125);
/// ```
#[inline(always)]
pub fn powi<L: Lanes>(x: L, n: i32) -> L {
    x.powi(n)
}

/// State `i` of a vector in lanes.
///
/// ```
/// use dynamics_runtime::lanes::state;
/// assert_eq!(state(&[2.0, 5.0], 0), nalgebra::Vector2::new(2.0, 5.0));
/// ```
#[inline(always)]
pub fn state<L: Lanes, const N: usize>(x: &[L; N], i: usize) -> SVector<f64, N> {
    SVector::from_fn(|j, _| x[j].lane(i))
}

/// A vector in lanes whose state `i` is `f(i)`.
///
/// ```
/// use dynamics_runtime::lanes::from_states;
/// let x: [f64; 2] = from_states(|i| nalgebra::Vector2::new(i as f64 + 3.0, 1.0));
/// assert_eq!(x, [3.0, 1.0]);
/// ```
#[inline(always)]
pub fn from_states<L: Lanes, const N: usize>(
    mut f: impl FnMut(usize) -> SVector<f64, N>,
) -> [L; N] {
    let mut states = [SVector::<f64, N>::zeros(); MAX_WIDTH];
    for (i, s) in states.iter_mut().enumerate().take(L::WIDTH) {
        *s = f(i);
    }
    core::array::from_fn(|j| L::from_fn(|i| states[i][j]))
}

/// A matrix in lanes, column-major as nalgebra's (`m[column][row]`),
/// whose state `i` is `f(i)`.
///
/// ```
/// use dynamics_runtime::lanes::matrix_from_states;
/// let m: [[f64; 2]; 2] = matrix_from_states(|_| nalgebra::Matrix2::new(1.0, 2.0, 3.0, 4.0));
/// assert_eq!(m, [[1.0, 3.0], [2.0, 4.0]]);
/// ```
#[inline(always)]
pub fn matrix_from_states<L: Lanes, const N: usize>(
    mut f: impl FnMut(usize) -> SMatrix<f64, N, N>,
) -> [[L; N]; N] {
    let mut states = [SMatrix::<f64, N, N>::zeros(); MAX_WIDTH];
    for (i, s) in states.iter_mut().enumerate().take(L::WIDTH) {
        *s = f(i);
    }
    core::array::from_fn(|c| core::array::from_fn(|r| L::from_fn(|i| states[i][(r, c)])))
}

#[cfg(all(test, target_arch = "x86_64"))]
mod tests {
    use super::{F64x4, F64x8, Lanes};
    use crate::trig;

    /// `f` at each level this CPU has (the vector types only in code
    /// compiled for their features).
    fn on_this_cpu(f4: fn(), f8: fn()) {
        if std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("fma") {
            f4();
        }
        if std::is_x86_feature_detected!("avx512f") {
            f8();
        }
    }

    #[test]
    fn lanes_compute_what_the_scalar_kernels_do() {
        #[target_feature(enable = "avx2,fma")]
        fn four() {
            let xs = [0.3, -2.0, 7.5, 1e-9];
            let (s, c) = F64x4::from_fn(|i| xs[i]).sin_cos();
            for i in 0..4 {
                let (es, ec) = trig::sin_cos(xs[i]);
                assert!((s.lane(i) - es).abs() <= 4.0 * f64::EPSILON, "{i}");
                assert!((c.lane(i) - ec).abs() <= 4.0 * f64::EPSILON, "{i}");
                if cfg!(target_feature = "fma") {
                    assert_eq!((s.lane(i), c.lane(i)), (es, ec), "{i}");
                }
            }
            // A huge or non-finite lane takes the scalar path for the value.
            let big = [1.0, 1e12, f64::NAN, 2.0];
            let (s, _) = F64x4::from_fn(|i| big[i]).sin_cos();
            assert_eq!(s.lane(1), 1e12f64.sin());
            assert!(s.lane(2).is_nan());
            assert_eq!(s.lane(3), trig::sin_cos(2.0).0);
            let y = F64x4::splat(3.0).powi(-2) - F64x4::splat(1.0 / 9.0);
            assert_eq!(y.lane(2), 0.0);
            assert_eq!((-F64x4::splat(2.25)).abs().sqrt().lane(3), 1.5);
            let f = F64x4::splat(0.1).mul_add(F64x4::splat(10.0), F64x4::splat(-1.0));
            assert_eq!(f.lane(0), 0.1f64.mul_add(10.0, -1.0));
        }
        #[target_feature(enable = "avx512f,avx2,fma")]
        fn eight() {
            let xs = [0.3, -2.0, 7.5, 1e-9, -3.1, 100.0, 0.0, 1.2];
            let x = F64x8::from_fn(|i| xs[i]);
            let (s, c) = x.sin_cos();
            for i in 0..8 {
                let (es, ec) = trig::sin_cos(xs[i]);
                assert!((s.lane(i) - es).abs() <= 4.0 * f64::EPSILON, "{i}");
                assert!((c.lane(i) - ec).abs() <= 4.0 * f64::EPSILON, "{i}");
            }
            let q = (x / F64x8::splat(2.0) + F64x8::splat(1.0)) * F64x8::splat(4.0) - x;
            assert_eq!(q.lane(5), (100.0 / 2.0 + 1.0) * 4.0 - 100.0);
            assert_eq!((-x).abs().lane(1), 2.0);
        }
        // SAFETY: each runs only where the CPU has its features.
        #[allow(unsafe_code)]
        on_this_cpu(|| unsafe { four() }, || unsafe { eight() });
    }

    #[test]
    fn stores_of_whole_and_partial_lanes_give_each_state_its_values() {
        fn check<L: Lanes, const R: usize, const C: usize>() {
            // R x C values, for 1..=WIDTH states.
            let values: [[L; R]; C] = core::array::from_fn(|c| {
                core::array::from_fn(|k| L::from_fn(|i| (1000 * c + 100 * k + i) as f64))
            });
            for m in 1..=L::WIDTH {
                let mut states = vec![[[0.0; R]; C]; m];
                L::store_states(&values, &mut states, |s| s);
                for (i, s) in states.iter().enumerate() {
                    for (c, column) in s.iter().enumerate() {
                        for (k, x) in column.iter().enumerate() {
                            let expected = (1000 * c + 100 * k + i) as f64;
                            assert_eq!(*x, expected, "{m} states, state {i}, value {c} {k}");
                        }
                    }
                }
            }
        }
        // Fewer values than lanes, whole blocks only, and blocks with
        // tails of one to seven values.
        fn all<L: Lanes>() {
            check::<L, 3, 1>();
            check::<L, 4, 4>();
            check::<L, 11, 2>();
            check::<L, 4, 3>();
            check::<L, 6, 6>();
            check::<L, 7, 7>();
            check::<L, 5, 3>();
        }
        #[target_feature(enable = "avx2,fma")]
        fn four() {
            all::<F64x4>();
        }
        #[target_feature(enable = "avx512f,avx2,fma")]
        fn eight() {
            all::<F64x8>();
        }
        all::<f64>();
        // SAFETY: each runs only where the CPU has its features.
        #[allow(unsafe_code)]
        on_this_cpu(|| unsafe { four() }, || unsafe { eight() });
    }
    #[test]
    fn loads_of_whole_and_partial_lanes_take_each_state_and_repeat_the_last() {
        fn check<L: Lanes, const N: usize>() {
            // N values a state, for 1..=WIDTH states: lane i of value j is
            // state min(i, states - 1)'s entry j.
            for m in 1..=L::WIDTH {
                let states: Vec<[f64; N]> = (0..m)
                    .map(|i| core::array::from_fn(|j| (100 * j + i) as f64 + 0.5))
                    .collect();
                let values: [L; N] = L::load_states(&states, |s| s);
                for (j, v) in values.iter().enumerate() {
                    for i in 0..L::WIDTH {
                        let expected = (100 * j + i.min(m - 1)) as f64 + 0.5;
                        assert_eq!(v.lane(i), expected, "{m} states, value {j}, lane {i}");
                    }
                }
            }
        }
        // Fewer values than lanes, a whole block, blocks and an overlapping tail.
        fn all<L: Lanes>() {
            check::<L, 3>();
            check::<L, 4>();
            check::<L, 6>();
            check::<L, 7>();
            check::<L, 8>();
            check::<L, 11>();
        }
        #[target_feature(enable = "avx2,fma")]
        fn four() {
            all::<F64x4>();
        }
        #[target_feature(enable = "avx512f,avx2,fma")]
        fn eight() {
            all::<F64x8>();
        }
        all::<f64>();
        // SAFETY: each runs only where the CPU has its features.
        #[allow(unsafe_code)]
        on_this_cpu(|| unsafe { four() }, || unsafe { eight() });
    }
}
