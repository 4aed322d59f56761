//! An sqlite3 bag on any bytes (written to a file of this process: SQLite
//! opens files).
#![no_main]

use libfuzzer_sys::fuzz_target;

#[global_allocator]
static ALLOC: dynamics_fuzz::Bounded = dynamics_fuzz::Bounded;

fuzz_target!(|data: &[u8]| {
    let path = std::env::temp_dir().join(format!("dynamics-fuzz-{}.db3", std::process::id()));
    if std::fs::write(&path, data).is_ok() {
        let _ = dynamics_sim2real::data::bag::read_bag(&path, &["j1", "j2", "j3"], "/joint_states");
    }
});
