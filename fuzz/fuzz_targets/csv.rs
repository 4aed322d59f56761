//! The CSV reader (plain or gzip) on any bytes: an error or samples, never
//! a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;

#[global_allocator]
static ALLOC: dynamics_fuzz::Bounded = dynamics_fuzz::Bounded;

fuzz_target!(|data: &[u8]| {
    let _ = dynamics_sim2real::data::read_csv_bytes(data, &["j1", "j2", "j3"], "fuzz.csv");
});
