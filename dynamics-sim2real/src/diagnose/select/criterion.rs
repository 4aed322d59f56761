//! The information criterion's ties: criteria that differ by less than
//! the last bits of a sum are equal, and the pool's order decides.

/// Criteria closer than this (in the criterion's units, where margins are
/// several units) are a tie, broken by the pool's order of the terms: a
/// selection must not hang on the last bits of a sum, which differ from
/// build to build (the model's sums are fused multiply-adds where the CPU
/// has them, `dynamics_runtime::fma`).
pub const TIE: f64 = 1e-3;

/// The criterion `c` rounded to [`TIE`], for ordering.
pub fn tie_key(c: f64) -> i64 {
    if c.is_finite() {
        (c / TIE).round() as i64
    } else if c > 0.0 {
        i64::MAX
    } else {
        i64::MIN
    }
}
