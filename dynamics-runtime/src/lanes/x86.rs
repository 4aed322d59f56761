//! The x86-64 lane types: four states in an AVX2 register, eight in an
//! AVX-512 one, each operation an intrinsic.
//!
//! Every intrinsic here is compiled for the CPU features of the function
//! it is inlined into: everything is `#[inline(always)]` down to the
//! `#[target_feature]` functions of `batch/dispatch.rs`, the only code
//! that makes values of these types, and only after the run-time check
//! that the CPU has those features. That check is what makes the `unsafe`
//! calls below sound; the types are private to the crate so that no other
//! code can make a value of them.
#![allow(unsafe_code)]

use core::arch::x86_64::*;
use core::ops::{Add, Div, Mul, Neg, Sub};

use super::Lanes;
use crate::{math, trig};

/// The lane type `$name` over the vector `$v` and its intrinsics.
macro_rules! vector_lanes {
    (
        $(#[$doc:meta])*
        $name:ident, $width:literal, $v:ty, $vi:ty,
        set1: $set1:ident, add: $add:ident, sub: $sub:ident, mul: $mul:ident, div: $div:ident,
        fmadd: $fmadd:ident, sqrt: $sqrt:ident,
        to_int: $to_int:ident, to_float: $to_float:ident,
        and: $and:ident, or: $or:ident, andnot: $andnot:ident, xor: $xor:ident,
        add64: $add64:ident, sub64: $sub64:ident, srli: $srli:ident, slli: $slli:ident,
        set1_64: $set1_64:ident, zero_int: $zero_int:ident,
        all_below: |$a:ident, $b:ident| $all_below:block,
        transpose: |$vs:ident| $transpose:block
    ) => {
        $(#[$doc])*
        #[derive(Clone, Copy)]
        #[repr(transparent)]
        pub(crate) struct $name($v);

        impl $name {
            /// The lanes as an array (a reinterpretation, no instruction).
            #[inline(always)]
            fn to_array(self) -> [f64; $width] {
                // SAFETY: both are $width f64 with no invalid bit patterns.
                unsafe { core::mem::transmute::<$v, [f64; $width]>(self.0) }
            }
            #[inline(always)]
            fn from_array(a: [f64; $width]) -> Self {
                // SAFETY: as above.
                Self(unsafe { core::mem::transmute::<[f64; $width], $v>(a) })
            }
            /// Whether every lane of `a` is below that of `b` (false for NaN).
            // Methods, not closures: a closure would be a function of its
            // own, compiled without the lanes' CPU features.
            #[inline(always)]
            fn all_below($a: Self, $b: Self) -> bool $all_below

            /// `$width` vectors of `$width` lanes transposed: lane `i` of
            /// vector `k` becomes lane `k` of vector `i`.
            #[inline(always)]
            fn transpose($vs: &[Self]) -> [Self; $width] $transpose

            /// The sign bit alone in every lane.
            #[inline(always)]
            fn sign() -> $vi {
                // SAFETY: see the module doc.
                unsafe { $set1_64(i64::MIN) }
            }
        }

        impl Add for $name {
            type Output = Self;
            #[inline(always)]
            fn add(self, rhs: Self) -> Self {
                // SAFETY: see the module doc.
                Self(unsafe { $add(self.0, rhs.0) })
            }
        }
        impl Sub for $name {
            type Output = Self;
            #[inline(always)]
            fn sub(self, rhs: Self) -> Self {
                // SAFETY: see the module doc.
                Self(unsafe { $sub(self.0, rhs.0) })
            }
        }
        impl Mul for $name {
            type Output = Self;
            #[inline(always)]
            fn mul(self, rhs: Self) -> Self {
                // SAFETY: see the module doc.
                Self(unsafe { $mul(self.0, rhs.0) })
            }
        }
        impl Div for $name {
            type Output = Self;
            #[inline(always)]
            fn div(self, rhs: Self) -> Self {
                // SAFETY: see the module doc.
                Self(unsafe { $div(self.0, rhs.0) })
            }
        }
        impl Neg for $name {
            type Output = Self;
            #[inline(always)]
            fn neg(self) -> Self {
                // SAFETY: see the module doc.
                Self(unsafe { $to_float($xor($to_int(self.0), Self::sign())) })
            }
        }

        impl Lanes for $name {
            const WIDTH: usize = $width;
            // SAFETY: $width f64 reinterpreted, no instruction.
            const NAN: Self =
                Self(unsafe { core::mem::transmute::<[f64; $width], $v>([f64::NAN; $width]) });
            // SAFETY: as above.
            const INFINITY: Self =
                Self(unsafe { core::mem::transmute::<[f64; $width], $v>([f64::INFINITY; $width]) });
            #[inline(always)]
            fn splat(x: f64) -> Self {
                // SAFETY: see the module doc.
                Self(unsafe { $set1(x) })
            }
            #[inline(always)]
            fn from_fn(mut f: impl FnMut(usize) -> f64) -> Self {
                let mut a = [0.0; $width];
                for (i, x) in a.iter_mut().enumerate() {
                    *x = f(i);
                }
                Self::from_array(a)
            }
            #[inline(always)]
            fn lane(self, i: usize) -> f64 {
                self.to_array()[i]
            }
            #[inline(always)]
            fn abs(self) -> Self {
                // SAFETY: see the module doc.
                Self(unsafe { $to_float($andnot(Self::sign(), $to_int(self.0))) })
            }
            #[inline(always)]
            fn mul_add(self, b: Self, c: Self) -> Self {
                // SAFETY: see the module doc.
                Self(unsafe { $fmadd(self.0, b.0, c.0) })
            }
            #[inline(always)]
            fn sin_cos(self) -> (Self, Self) {
                let limit = Self::splat(trig::REDUCE_LIMIT);
                if !Self::all_below(self.abs(), limit) {
                    return Self::cold_sin_cos(self);
                }
                let (shifted, s, c) = super::reduced(self);
                Self::by_quadrant(shifted, s, c)
            }
            #[inline(always)]
            fn sin_cos_n<const K: usize>(x: [Self; K]) -> ([Self; K], [Self; K]) {
                // One test of every lane of every value, one branch.
                let limit = Self::splat(trig::REDUCE_LIMIT);
                let mut below = true;
                for v in &x {
                    below &= Self::all_below(v.abs(), limit);
                }
                if !below {
                    return Self::cold_sin_cos_n(x);
                }
                let mut s = [Self::splat(0.0); K];
                let mut c = [Self::splat(0.0); K];
                for k in 0..K {
                    let (shifted, sk, ck) = super::reduced(x[k]);
                    (s[k], c[k]) = Self::by_quadrant(shifted, sk, ck);
                }
                (s, c)
            }
            #[inline(always)]
            fn sqrt(self) -> Self {
                // SAFETY: see the module doc.
                Self(unsafe { $sqrt(self.0) })
            }
            #[inline(always)]
            fn tanh(self) -> Self {
                Self::from_array(self.to_array().map(math::tanh))
            }
            #[inline(always)]
            fn powi(self, n: i32) -> Self {
                Self::from_array(self.to_array().map(|x| math::powi(x, n)))
            }
            #[inline(always)]
            fn by_quadrant(shifted: Self, s: Self, c: Self) -> (Self, Self) {
                // SAFETY: see the module doc.
                unsafe {
                    let bits = $to_int(shifted.0);
                    let one = $set1_64(1);
                    let swap = $sub64($zero_int(), $and(bits, one));
                    let sin_sign = $slli::<63>($and($srli::<1>(bits), one));
                    let cos_sign = $slli::<63>($and($srli::<1>($add64(bits, one)), one));
                    let (sb, cb) = ($to_int(s.0), $to_int(c.0));
                    let sin = $xor($or($and(cb, swap), $andnot(swap, sb)), sin_sign);
                    let cos = $xor($or($and(sb, swap), $andnot(swap, cb)), cos_sign);
                    (Self($to_float(sin)), Self($to_float(cos)))
                }
            }
            #[inline(always)]
            fn store_states<T, const R: usize, const C: usize>(
                values: &[[Self; R]; C],
                states: &mut [T],
                field: impl Fn(&mut T) -> &mut [[f64; R]; C],
            ) {
                // A whole group by code whose every index is a constant, so
                // that the values stay in registers; a last group of fewer
                // states out of line.
                match <&mut [T; $width]>::try_from(&mut *states) {
                    Ok(whole) => Self::store_whole(values, whole, field),
                    Err(_) => Self::store_part(*values, states, field),
                }
            }
            #[inline(always)]
            fn load_states<T, const N: usize>(
                states: &[T],
                field: impl Fn(&T) -> &[f64; N],
            ) -> [Self; N] {
                if states.len() == $width && N >= $width {
                    return Self::load_whole(states, field);
                }
                let last = states.len() - 1;
                core::array::from_fn(|j| Self::from_fn(|i| field(&states[i.min(last)])[j]))
            }
        }

        impl $name {
            /// [`Lanes::load_states`] of a whole group of at least
            /// `$width` values: blocks of `$width` entries, one vector
            /// load per state, turned into lanes by a register transpose
            /// (not `$width` scalar loads per value); the last block ends
            /// at the last entry and overlaps the one before.
            #[inline(always)]
            fn load_whole<T, const N: usize>(
                states: &[T],
                field: impl Fn(&T) -> &[f64; N],
            ) -> [Self; N] {
                let mut out = [Self::splat(0.0); N];
                let mut k = 0;
                loop {
                    let k0 = k.min(N - $width);
                    let rows: [Self; $width] = core::array::from_fn(|i| {
                        let x = field(&states[i]);
                        Self::from_array(core::array::from_fn(|m| x[k0 + m]))
                    });
                    for (m, v) in Self::transpose(&rows).into_iter().enumerate() {
                        out[k0 + m] = v;
                    }
                    if k0 + $width >= N {
                        return out;
                    }
                    k += $width;
                }
            }

            /// [`Lanes::store_states`] of a whole group: blocks of `$width`
            /// values turned by a register transpose into `$width` runs of
            /// one state each, one vector store per state (not `$width`
            /// scalar stores per value); the values past the last block by
            /// `store_tail`.
            #[inline(always)]
            fn store_whole<T, const R: usize, const C: usize>(
                values: &[[Self; R]; C],
                states: &mut [T; $width],
                field: impl Fn(&mut T) -> &mut [[f64; R]; C],
            ) {
                let values = values.as_flattened();
                let blocks = values.len() / $width;
                for b in 0..blocks {
                    let k = b * $width;
                    let rows = Self::transpose(&values[k..k + $width]);
                    for (state, row) in states.iter_mut().zip(rows) {
                        field(state).as_flattened_mut()[k..k + $width]
                            .copy_from_slice(&row.to_array());
                    }
                }
                Self::store_tail(values, blocks * $width, states, field);
            }

            /// [`Lanes::store_states`] of fewer than `$width` states: each
            /// value lane by lane.
            #[cold]
            #[inline(never)]
            fn store_part<T, const R: usize, const C: usize>(
                values: [[Self; R]; C],
                states: &mut [T],
                field: impl Fn(&mut T) -> &mut [[f64; R]; C],
            ) {
                for (j, v) in values.as_flattened().iter().enumerate() {
                    for (state, x) in states.iter_mut().zip(v.to_array()) {
                        field(state).as_flattened_mut()[j] = x;
                    }
                }
            }

            /// Values `from..` of a whole group, each lane by lane.
            #[inline(always)]
            fn store_lanes<T, const R: usize, const C: usize>(
                values: &[Self],
                from: usize,
                states: &mut [T; $width],
                field: impl Fn(&mut T) -> &mut [[f64; R]; C],
            ) {
                for (j, v) in values.iter().enumerate().skip(from) {
                    for (state, x) in states.iter_mut().zip(v.to_array()) {
                        field(state).as_flattened_mut()[j] = x;
                    }
                }
            }

            /// `sin_cos` when a lane is huge or not finite: each lane by
            /// the scalar kernel (which sends those to `std` or `libm`).
            #[cold]
            #[inline(never)]
            fn cold_sin_cos(x: Self) -> (Self, Self) {
                let (s, c) = trig::sin_cos_n(x.to_array());
                (Self::from_array(s), Self::from_array(c))
            }

            /// `sin_cos_n` when a lane of a value is huge or not finite:
            /// every lane by the scalar kernel (no vector instruction, as
            /// this function is compiled without the lanes' features).
            #[cold]
            #[inline(never)]
            fn cold_sin_cos_n<const K: usize>(x: [Self; K]) -> ([Self; K], [Self; K]) {
                let mut s = [[0.0; $width]; K];
                let mut c = [[0.0; $width]; K];
                for k in 0..K {
                    (s[k], c[k]) = trig::sin_cos_n(x[k].to_array());
                }
                (s.map(Self::from_array), c.map(Self::from_array))
            }
        }
    };
}

vector_lanes!(
    /// Four states: one AVX2 register.
    F64x4, 4, __m256d, __m256i,
    set1: _mm256_set1_pd, add: _mm256_add_pd, sub: _mm256_sub_pd, mul: _mm256_mul_pd,
    div: _mm256_div_pd, fmadd: _mm256_fmadd_pd, sqrt: _mm256_sqrt_pd,
    to_int: _mm256_castpd_si256, to_float: _mm256_castsi256_pd,
    and: _mm256_and_si256, or: _mm256_or_si256, andnot: _mm256_andnot_si256, xor: _mm256_xor_si256,
    add64: _mm256_add_epi64, sub64: _mm256_sub_epi64, srli: _mm256_srli_epi64, slli: _mm256_slli_epi64,
    set1_64: _mm256_set1_epi64x, zero_int: _mm256_setzero_si256,
    // SAFETY: see the module doc.
    // SAFETY: see the module doc.
    all_below: |a, b| { unsafe { _mm256_movemask_pd(_mm256_cmp_pd::<_CMP_LT_OQ>(a.0, b.0)) == 0b1111 } },
    // 4 x 4: pairs of 64-bit lanes interleaved, then 128-bit halves.
    // SAFETY: see the module doc.
    transpose: |v| { unsafe {
        let t0 = _mm256_unpacklo_pd(v[0].0, v[1].0);
        let t1 = _mm256_unpackhi_pd(v[0].0, v[1].0);
        let t2 = _mm256_unpacklo_pd(v[2].0, v[3].0);
        let t3 = _mm256_unpackhi_pd(v[2].0, v[3].0);
        [
            F64x4(_mm256_permute2f128_pd::<0x20>(t0, t2)),
            F64x4(_mm256_permute2f128_pd::<0x20>(t1, t3)),
            F64x4(_mm256_permute2f128_pd::<0x31>(t0, t2)),
            F64x4(_mm256_permute2f128_pd::<0x31>(t1, t3)),
        ]
    } }
);

vector_lanes!(
    /// Eight states: one AVX-512 register.
    F64x8, 8, __m512d, __m512i,
    set1: _mm512_set1_pd, add: _mm512_add_pd, sub: _mm512_sub_pd, mul: _mm512_mul_pd,
    div: _mm512_div_pd, fmadd: _mm512_fmadd_pd, sqrt: _mm512_sqrt_pd,
    to_int: _mm512_castpd_si512, to_float: _mm512_castsi512_pd,
    and: _mm512_and_si512, or: _mm512_or_si512, andnot: _mm512_andnot_si512, xor: _mm512_xor_si512,
    add64: _mm512_add_epi64, sub64: _mm512_sub_epi64, srli: _mm512_srli_epi64, slli: _mm512_slli_epi64,
    set1_64: _mm512_set1_epi64, zero_int: _mm512_setzero_si512,
    // SAFETY: see the module doc.
    // SAFETY: see the module doc.
    all_below: |a, b| { unsafe { _mm512_cmp_pd_mask::<_CMP_LT_OQ>(a.0, b.0) == 0xff } },
    // 8 x 8: pairs of 64-bit lanes interleaved, then 128-bit blocks
    // gathered twice (blocks 0, 2 with 0x88; 1, 3 with 0xdd).
    // SAFETY: see the module doc.
    transpose: |v| { unsafe {
        let t = [
            _mm512_unpacklo_pd(v[0].0, v[1].0),
            _mm512_unpackhi_pd(v[0].0, v[1].0),
            _mm512_unpacklo_pd(v[2].0, v[3].0),
            _mm512_unpackhi_pd(v[2].0, v[3].0),
            _mm512_unpacklo_pd(v[4].0, v[5].0),
            _mm512_unpackhi_pd(v[4].0, v[5].0),
            _mm512_unpacklo_pd(v[6].0, v[7].0),
            _mm512_unpackhi_pd(v[6].0, v[7].0),
        ];
        let u = [
            _mm512_shuffle_f64x2::<0x88>(t[0], t[2]),
            _mm512_shuffle_f64x2::<0x88>(t[1], t[3]),
            _mm512_shuffle_f64x2::<0xdd>(t[0], t[2]),
            _mm512_shuffle_f64x2::<0xdd>(t[1], t[3]),
            _mm512_shuffle_f64x2::<0x88>(t[4], t[6]),
            _mm512_shuffle_f64x2::<0x88>(t[5], t[7]),
            _mm512_shuffle_f64x2::<0xdd>(t[4], t[6]),
            _mm512_shuffle_f64x2::<0xdd>(t[5], t[7]),
        ];
        [
            F64x8(_mm512_shuffle_f64x2::<0x88>(u[0], u[4])),
            F64x8(_mm512_shuffle_f64x2::<0x88>(u[1], u[5])),
            F64x8(_mm512_shuffle_f64x2::<0x88>(u[2], u[6])),
            F64x8(_mm512_shuffle_f64x2::<0x88>(u[3], u[7])),
            F64x8(_mm512_shuffle_f64x2::<0xdd>(u[0], u[4])),
            F64x8(_mm512_shuffle_f64x2::<0xdd>(u[1], u[5])),
            F64x8(_mm512_shuffle_f64x2::<0xdd>(u[2], u[6])),
            F64x8(_mm512_shuffle_f64x2::<0xdd>(u[3], u[7])),
        ]
    } }
);

impl F64x4 {
    /// The values past the last block of four: lane by lane.
    #[inline(always)]
    fn store_tail<T, const R: usize, const C: usize>(
        values: &[Self],
        from: usize,
        states: &mut [T; 4],
        field: impl Fn(&mut T) -> &mut [[f64; R]; C],
    ) {
        Self::store_lanes(values, from, states, field);
    }
}

impl F64x8 {
    /// Lanes 0-3 and 4-7.
    #[inline(always)]
    fn halves(self) -> (F64x4, F64x4) {
        // SAFETY: see the module doc.
        unsafe {
            (
                F64x4(_mm512_castpd512_pd256(self.0)),
                F64x4(_mm512_extractf64x4_pd::<1>(self.0)),
            )
        }
    }

    /// The values past the last block of eight: four of them (if there
    /// are) by the 4 x 4 transposes of their halves, one 256-bit store per
    /// state, the rest lane by lane.
    #[inline(always)]
    fn store_tail<T, const R: usize, const C: usize>(
        values: &[Self],
        from: usize,
        states: &mut [T; 8],
        field: impl Fn(&mut T) -> &mut [[f64; R]; C],
    ) {
        let mut k = from;
        if k + 4 <= values.len() {
            let halves: [(F64x4, F64x4); 4] = core::array::from_fn(|m| values[k + m].halves());
            let low = F64x4::transpose(&halves.map(|h| h.0));
            let high = F64x4::transpose(&halves.map(|h| h.1));
            for (state, row) in states.iter_mut().zip(low.into_iter().chain(high)) {
                field(state).as_flattened_mut()[k..k + 4].copy_from_slice(&row.to_array());
            }
            k += 4;
        }
        Self::store_lanes(values, k, states, field);
    }
}
