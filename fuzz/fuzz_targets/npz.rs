//! A NumPy archive (or one .npy, or a text matrix) through a column map, on
//! any bytes.
#![no_main]

use dynamics_sim2real::data::import::{import_bytes, ColumnMap};
use libfuzzer_sys::fuzz_target;

#[global_allocator]
static ALLOC: dynamics_fuzz::Bounded = dynamics_fuzz::Bounded;

fuzz_target!(|data: &[u8]| {
    let archive: ColumnMap = "t=times,q=positions,qd=velocities,tau=torques"
        .parse()
        .expect("a column map");
    let single: ColumnMap = "t=:1,q=:2-3,tau=:4-5".parse().expect("a column map");
    let map = if data.starts_with(b"PK") { archive } else { single };
    let _ = import_bytes(data, "fuzz.npz", &map, &["a", "b"], None);
});
