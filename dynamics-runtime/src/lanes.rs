//! Several states in one value: the lane types the emitted dynamics run
//! over for the batch functions of [`crate::batch`].
//!
//! `robot!` emits every batch-capable output twice: once over `f64` (the
//! methods of [`Robot`](crate::Robot)), once generic over [`Lanes`] (the
//! `*_lanes` methods), the same straight-line code with each `f64` a lane
//! value. Over [`F64x4`] (AVX2) or [`F64x8`] (AVX-512) each operation is
//! one vector instruction for four or eight states.
//!
//! The lane types are plain arrays with element-wise operations, which
//! LLVM turns into vector instructions where the code is compiled for a
//! CPU that has them: [`crate::batch`] runs them inside functions compiled
//! for AVX2 or AVX-512 (`#[target_feature]`), chosen at run time, so a
//! binary built for baseline x86-64 still uses the vector units. Arrays
//! rather than `core::arch` intrinsics: the same code builds for every
//! target and without `std`, and needs no `unsafe` per operation.
//!
//! Over `f64` every function here is the scalar code's own (the results
//! are those of the scalar methods, bit for bit). Over the lane types the
//! multiply-adds are fused (one rounding) also where the scalar code's are
//! not (a build without FMA): there results agree to a few ulp.

use core::ops::{Add, Div, Mul, Neg, Sub};

use nalgebra::{SMatrix, SVector};

use crate::{fma, math, trig};

/// The widest lane type.
const MAX_WIDTH: usize = 8;

mod sealed {
    /// Only the lane types of this module are [`super::Lanes`] (their
    /// width is at most [`super::MAX_WIDTH`]).
    pub trait Sealed {}
    impl Sealed for f64 {}
    impl Sealed for super::F64x4 {}
    impl Sealed for super::F64x8 {}
}

/// A value of one or more states: `f64` (one), [`F64x4`], [`F64x8`].
///
/// ```
/// use dynamics_runtime::lanes::{F64x4, Lanes};
/// let x = F64x4::from_fn(|i| i as f64);
/// let y = dynamics_runtime::lanes::mul_add(x, F64x4::splat(2.0), F64x4::splat(1.0));
/// assert_eq!((y.lane(0), y.lane(3)), (1.0, 7.0));
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
}

/// The lane types: `[f64; W]` with element-wise operations.
macro_rules! lane_type {
    ($(#[$doc:meta])* $name:ident, $width:literal, $align:literal) => {
        $(#[$doc])*
        #[derive(Debug, Clone, Copy, PartialEq)]
        #[repr(C, align($align))]
        pub struct $name(pub [f64; $width]);

        impl $name {
            #[inline(always)]
            fn map(self, f: impl Fn(f64) -> f64) -> Self {
                let mut out = [0.0; $width];
                for i in 0..$width {
                    out[i] = f(self.0[i]);
                }
                Self(out)
            }
            #[inline(always)]
            fn zip(self, other: Self, f: impl Fn(f64, f64) -> f64) -> Self {
                let mut out = [0.0; $width];
                for i in 0..$width {
                    out[i] = f(self.0[i], other.0[i]);
                }
                Self(out)
            }
        }

        impl Add for $name {
            type Output = Self;
            #[inline(always)]
            fn add(self, rhs: Self) -> Self {
                self.zip(rhs, |a, b| a + b)
            }
        }
        impl Sub for $name {
            type Output = Self;
            #[inline(always)]
            fn sub(self, rhs: Self) -> Self {
                self.zip(rhs, |a, b| a - b)
            }
        }
        impl Mul for $name {
            type Output = Self;
            #[inline(always)]
            fn mul(self, rhs: Self) -> Self {
                self.zip(rhs, |a, b| a * b)
            }
        }
        impl Div for $name {
            type Output = Self;
            #[inline(always)]
            fn div(self, rhs: Self) -> Self {
                self.zip(rhs, |a, b| a / b)
            }
        }
        impl Neg for $name {
            type Output = Self;
            #[inline(always)]
            fn neg(self) -> Self {
                self.map(|a| -a)
            }
        }

        impl Lanes for $name {
            const WIDTH: usize = $width;
            const NAN: Self = Self([f64::NAN; $width]);
            const INFINITY: Self = Self([f64::INFINITY; $width]);
            #[inline(always)]
            fn splat(x: f64) -> Self {
                Self([x; $width])
            }
            #[inline(always)]
            fn from_fn(mut f: impl FnMut(usize) -> f64) -> Self {
                let mut out = [0.0; $width];
                for (i, o) in out.iter_mut().enumerate() {
                    *o = f(i);
                }
                Self(out)
            }
            #[inline(always)]
            fn lane(self, i: usize) -> f64 {
                self.0[i]
            }
            #[inline(always)]
            fn abs(self) -> Self {
                self.map(f64::abs)
            }
            #[inline(always)]
            fn mul_add(self, b: Self, c: Self) -> Self {
                let mut out = [0.0; $width];
                for i in 0..$width {
                    out[i] = trig::mul_add_by::<true>(self.0[i], b.0[i], c.0[i]);
                }
                Self(out)
            }
            #[inline(always)]
            fn sin_cos(self) -> (Self, Self) {
                if trig::all_reducible(&self.0) {
                    let (s, c) = trig::lanes_by::<$width, true>(self.0);
                    (Self(s), Self(c))
                } else {
                    let (s, c) = trig::sin_cos_n(self.0);
                    (Self(s), Self(c))
                }
            }
            #[inline(always)]
            fn sin_cos_n<const K: usize>(x: [Self; K]) -> ([Self; K], [Self; K]) {
                let mut s = [Self::splat(0.0); K];
                let mut c = [Self::splat(0.0); K];
                for k in 0..K {
                    (s[k], c[k]) = x[k].sin_cos();
                }
                (s, c)
            }
            #[inline(always)]
            fn sqrt(self) -> Self {
                self.map(math::sqrt)
            }
            #[inline(always)]
            fn tanh(self) -> Self {
                self.map(math::tanh)
            }
            #[inline(always)]
            fn powi(self, n: i32) -> Self {
                self.map(|x| math::powi(x, n))
            }
        }
    };
}

lane_type!(
    /// Four states: one AVX2 register.
    ///
    /// ```
    /// use dynamics_runtime::lanes::{F64x4, Lanes};
    /// let (s, c) = F64x4::splat(0.5).sin_cos();
    /// assert_eq!((s.lane(2), c.lane(2)), dynamics_runtime::trig::sin_cos(0.5));
    /// ```
    F64x4,
    4,
    32
);
lane_type!(
    /// Eight states: one AVX-512 register.
    ///
    /// ```
    /// use dynamics_runtime::lanes::{F64x8, Lanes};
    /// let x = F64x8::from_fn(|i| i as f64) / F64x8::splat(2.0);
    /// assert_eq!(x.lane(7), 3.5);
    /// ```
    F64x8,
    8,
    64
);

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
/// use dynamics_runtime::lanes::{state, F64x4, Lanes};
/// let x = [F64x4::from_fn(|i| i as f64), F64x4::splat(5.0)];
/// assert_eq!(state(&x, 2), nalgebra::Vector2::new(2.0, 5.0));
/// ```
#[inline(always)]
pub fn state<L: Lanes, const N: usize>(x: &[L; N], i: usize) -> SVector<f64, N> {
    SVector::from_fn(|j, _| x[j].lane(i))
}

/// A vector in lanes whose state `i` is `f(i)`.
///
/// ```
/// use dynamics_runtime::lanes::{from_states, F64x4, Lanes};
/// let x: [F64x4; 2] = from_states(|i| nalgebra::Vector2::new(i as f64, 1.0));
/// assert_eq!((x[0].lane(3), x[1].lane(3)), (3.0, 1.0));
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

/// A row-major matrix in lanes whose state `i` is `f(i)`.
///
/// ```
/// use dynamics_runtime::lanes::{matrix_from_states, F64x4, Lanes};
/// let m: [[F64x4; 2]; 2] = matrix_from_states(|i| nalgebra::Matrix2::new(1.0, 2.0, 3.0, i as f64));
/// assert_eq!((m[0][1].lane(0), m[1][1].lane(2)), (2.0, 2.0));
/// ```
#[inline(always)]
pub fn matrix_from_states<L: Lanes, const N: usize>(
    mut f: impl FnMut(usize) -> SMatrix<f64, N, N>,
) -> [[L; N]; N] {
    let mut states = [SMatrix::<f64, N, N>::zeros(); MAX_WIDTH];
    for (i, s) in states.iter_mut().enumerate().take(L::WIDTH) {
        *s = f(i);
    }
    core::array::from_fn(|r| core::array::from_fn(|c| L::from_fn(|i| states[i][(r, c)])))
}

#[cfg(test)]
mod tests {
    use super::{F64x4, F64x8, Lanes};
    use crate::trig;

    #[test]
    fn lanes_compute_what_the_scalar_kernels_do() {
        let xs = [0.3, -2.0, 7.5, 1e-9, -3.1, 100.0, 0.0, 1.2];
        let x8 = F64x8(xs);
        let (s, c) = x8.sin_cos();
        for i in 0..8 {
            let (es, ec) = trig::sin_cos(xs[i]);
            // Fused or not, a few ulp of the scalar kernel.
            assert!((s.lane(i) - es).abs() <= 4.0 * f64::EPSILON, "{i}");
            assert!((c.lane(i) - ec).abs() <= 4.0 * f64::EPSILON, "{i}");
            if cfg!(target_feature = "fma") {
                assert_eq!((s.lane(i), c.lane(i)), (es, ec), "{i}");
            }
        }
        // A huge or non-finite lane takes the scalar path for the value.
        let (s, _) = F64x4([1.0, 1e12, f64::NAN, 2.0]).sin_cos();
        assert_eq!(s.lane(1), 1e12f64.sin());
        assert!(s.lane(2).is_nan());
        assert_eq!(s.lane(3), trig::sin_cos(2.0).0);
        let y = F64x4::splat(3.0).powi(-2) - F64x4::splat(1.0 / 9.0);
        assert_eq!(y, F64x4::splat(0.0));
        assert_eq!((-F64x4::splat(2.25)).abs().sqrt(), F64x4::splat(1.5));
    }
}
