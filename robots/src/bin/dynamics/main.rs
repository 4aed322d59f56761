//! `dynamics`: the generic command-line program of `dynamics-cli` over the
//! built-in robots (`robots::builtin::Builtin`), chosen with `--robot`.
//!
//! ```text
//! dynamics                      # diagnose a built-in case (arm3r with a withheld effect)
//! dynamics check                # every robot of the source works against the shipped Pinocchio values
//! dynamics synth --robot NAME --effect KIND --joint J --out FILE.csv
//! dynamics diagnose --robot NAME --train A.csv --holdout B.csv [--json OUT.json] [--report DIR] [--baseline OLD.json]
//! dynamics simulate --robot NAME [--motion sines|chirp|pick-place|FILE.csv] [--effects FILE.json]
//! dynamics identify --robot NAME --train A.csv --holdout B.csv [--json OUT.json]
//! dynamics eval --robot NAME [--states FILE.json] [--out FILE.json] [--set NAME=VALUE]...
//! dynamics list                 # the robots it knows
//! dynamics new DIR --urdf FILE  # a crate for your own robot
//! ```

fn main() -> std::process::ExitCode {
    tune_allocator();
    dynamics_cli::run_set("dynamics", &robots::builtin::Builtin)
}

/// Bytes from which glibc's allocator maps a block on its own, returned to
/// the system when freed: glibc's largest (32 MB on 64-bit). Below it a
/// block comes from the allocator's arenas and its pages are used again by
/// later blocks.
#[cfg(all(target_os = "linux", target_env = "gnu"))]
const MMAP_THRESHOLD: libc::c_int = 32 * 1024 * 1024;

/// Free bytes at the top of an arena from which glibc's allocator returns
/// them to the system.
#[cfg(all(target_os = "linux", target_env = "gnu"))]
const TRIM_THRESHOLD: libc::c_int = 256 * 1024 * 1024;

/// Arenas glibc's allocator keeps: one, shared by the threads.
#[cfg(all(target_os = "linux", target_env = "gnu"))]
const ARENA_MAX: libc::c_int = 1;

/// Fixes glibc's mmap threshold at [`MMAP_THRESHOLD`], its trim threshold
/// at [`TRIM_THRESHOLD`] and its arenas at [`ARENA_MAX`], each unless the
/// environment sets it (`MALLOC_MMAP_THRESHOLD_`, `MALLOC_TRIM_THRESHOLD_`,
/// `MALLOC_ARENA_MAX`, which glibc reads instead). A diagnosis of a long
/// log makes and drops many per-record vectors of a few MB (a record's
/// series of an hour's log at 1 kHz is 14 MB); kept in the arenas, their
/// pages serve the next vectors instead of being returned and mapped and
/// zeroed afresh by the system, which costs a diagnosis of an hour's log
/// some 40 s of system time at glibc's starting threshold of 128 kB, 20 s
/// at 2 MB and 3 s here. One arena for both threads reuses a block one
/// thread frees for the other's next blocks: with an arena a thread the
/// hour's peak memory is some 7 % more (docs/long-logs.md). Where the
/// values land does not change them: the results are the same.
#[cfg(all(target_os = "linux", target_env = "gnu"))]
#[allow(unsafe_code)]
fn tune_allocator() {
    for (variable, parameter, value) in [
        (
            "MALLOC_MMAP_THRESHOLD_",
            libc::M_MMAP_THRESHOLD,
            MMAP_THRESHOLD,
        ),
        (
            "MALLOC_TRIM_THRESHOLD_",
            libc::M_TRIM_THRESHOLD,
            TRIM_THRESHOLD,
        ),
        ("MALLOC_ARENA_MAX", libc::M_ARENA_MAX, ARENA_MAX),
    ] {
        if std::env::var_os(variable).is_some() {
            continue;
        }
        // SAFETY: `mallopt` sets one parameter of the C allocator and takes
        // no pointers; it is called first thing in `main`, before this
        // program starts another thread, with M_MMAP_THRESHOLD at most
        // glibc's maximum (32 MB on 64-bit), M_TRIM_THRESHOLD and
        // M_ARENA_MAX positive: documented, valid settings.
        unsafe {
            libc::mallopt(parameter, value);
        }
    }
}

/// Other systems' allocators: left as they are.
#[cfg(not(all(target_os = "linux", target_env = "gnu")))]
fn tune_allocator() {}
