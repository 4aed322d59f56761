//! An MCAP file's JointState messages on any bytes.
#![no_main]

use libfuzzer_sys::fuzz_target;

#[global_allocator]
static ALLOC: dynamics_fuzz::Bounded = dynamics_fuzz::Bounded;

fuzz_target!(|data: &[u8]| {
    let _ = dynamics_sim2real::data::bag::read_mcap_bytes(
        data,
        &["j1", "j2", "j3"],
        "/joint_states",
        "fuzz.mcap",
    );
});
