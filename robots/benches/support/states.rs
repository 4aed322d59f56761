//! The states the benches evaluate (`dynamics`, `batch`, `batch_min`):
//! deterministic, in the reference sampling box (q in [-3.1, 3.1], v and a
//! in [-2, 2]).

use nalgebra::SVector;

/// States per batch call.
pub const STATES: usize = 1000;

/// `STATES` positions, velocities and accelerations (xorshift, fixed seed).
pub fn states<const N: usize>() -> [Vec<SVector<f64, N>>; 3] {
    let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut next = move |lo: f64, hi: f64| {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        lo + (hi - lo) * ((x >> 11) as f64 / (1u64 << 53) as f64)
    };
    let mut out: [Vec<SVector<f64, N>>; 3] = Default::default();
    for _ in 0..STATES {
        out[0].push(SVector::from_fn(|_, _| next(-3.1, 3.1)));
        out[1].push(SVector::from_fn(|_, _| next(-2.0, 2.0)));
        out[2].push(SVector::from_fn(|_, _| next(-2.0, 2.0)));
    }
    out
}
