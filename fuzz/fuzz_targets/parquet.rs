//! A Parquet file of the CSV's columns on any bytes.
#![no_main]

use libfuzzer_sys::fuzz_target;

#[global_allocator]
static ALLOC: dynamics_fuzz::Bounded = dynamics_fuzz::Bounded;

fuzz_target!(|data: &[u8]| {
    dynamics_fuzz::panics_unwind();
    let _ = dynamics_sim2real::data::parquet::read_parquet_bytes(
        data.to_vec(),
        &["j1", "j2", "j3"],
        "fuzz.parquet",
    );
});
