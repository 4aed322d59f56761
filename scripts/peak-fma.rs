//! The peak fused-multiply-add rate of one core, the arithmetic limit the
//! batch figures are compared with: 16 independent chains of vector FMAs
//! (more than the FMA latency times the FMA ports, so the ports never
//! wait), in thread CPU time. One lane-FMA is one fused multiply-add on one
//! f64 lane.
//!
//!   rustc -O -C target-cpu=native scripts/peak-fma.rs -o target/peak-fma
//!   taskset -c 1 target/peak-fma
#![allow(unsafe_code)]

use std::arch::x86_64::*;

fn cpu_seconds() -> f64 {
    let mut t = libc_timespec { tv_sec: 0, tv_nsec: 0 };
    // SAFETY: clock_gettime writes the struct it is given.
    unsafe { clock_gettime(3, &mut t) }; // CLOCK_THREAD_CPUTIME_ID
    t.tv_sec as f64 + t.tv_nsec as f64 * 1e-9
}

#[repr(C)]
struct libc_timespec {
    tv_sec: i64,
    tv_nsec: i64,
}

extern "C" {
    fn clock_gettime(clock: i32, t: *mut libc_timespec) -> i32;
}

#[target_feature(enable = "avx512f")]
fn chains512(n: u64) -> f64 {
    let mut acc = [_mm512_set1_pd(1.0); 16];
    let (a, b) = (_mm512_set1_pd(0.999_999_9), _mm512_set1_pd(1e-9));
    for _ in 0..n {
        for x in acc.iter_mut() {
            *x = _mm512_fmadd_pd(*x, a, b);
        }
    }
    acc.iter().map(|x| _mm512_reduce_add_pd(*x)).sum()
}

#[target_feature(enable = "avx2,fma")]
fn chains256(n: u64) -> f64 {
    let mut acc = [_mm256_set1_pd(1.0); 16];
    let (a, b) = (_mm256_set1_pd(0.999_999_9), _mm256_set1_pd(1e-9));
    for _ in 0..n {
        for x in acc.iter_mut() {
            *x = _mm256_fmadd_pd(*x, a, b);
        }
    }
    let mut out = [0.0; 4];
    let mut sum = _mm256_setzero_pd();
    for x in acc {
        sum = _mm256_add_pd(sum, x);
    }
    // SAFETY: `out` holds four f64.
    unsafe { _mm256_storeu_pd(out.as_mut_ptr(), sum) };
    out.iter().sum()
}

fn main() {
    let n = 100_000_000u64;
    for _ in 0..3 {
        if is_x86_feature_detected!("avx512f") {
            let t = cpu_seconds();
            // SAFETY: the CPU has AVX-512F (checked above).
            let s = unsafe { chains512(n) };
            let dt = cpu_seconds() - t;
            println!("AVX-512: {:.1} G lane-FMA/s (checksum {s:.3})", (n * 16 * 8) as f64 / dt / 1e9);
        }
        if is_x86_feature_detected!("avx2") && is_x86_feature_detected!("fma") {
            let t = cpu_seconds();
            // SAFETY: the CPU has AVX2 and FMA (checked above).
            let s = unsafe { chains256(n) };
            let dt = cpu_seconds() - t;
            println!("AVX2:    {:.1} G lane-FMA/s (checksum {s:.3})", (n * 16 * 4) as f64 / dt / 1e9);
        }
    }
}
