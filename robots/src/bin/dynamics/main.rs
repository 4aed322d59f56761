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
    return_large_blocks();
    dynamics_cli::run_set("dynamics", &robots::builtin::Builtin)
}

/// Bytes from which glibc's allocator maps a block on its own, returned to
/// the system when freed. Below it a block comes from the allocator's
/// arenas and its pages are used again by later blocks.
#[cfg(all(target_os = "linux", target_env = "gnu"))]
const MMAP_THRESHOLD: libc::c_int = 2 * 1024 * 1024;

/// Free bytes at the top of an arena from which glibc's allocator returns
/// them to the system.
#[cfg(all(target_os = "linux", target_env = "gnu"))]
const TRIM_THRESHOLD: libc::c_int = 256 * 1024 * 1024;

/// Fixes glibc's mmap threshold at [`MMAP_THRESHOLD`] and its trim
/// threshold at [`TRIM_THRESHOLD`], each unless the environment sets it
/// (`MALLOC_MMAP_THRESHOLD_`, `MALLOC_TRIM_THRESHOLD_`, which glibc reads
/// instead). Left to itself glibc raises the mmap threshold as large
/// blocks are freed and then keeps later ones of that size in its arenas,
/// where the per-record vectors a diagnosis of a long log makes and drops
/// add up to a fifth of its peak memory; vectors of 2 MB and more (a
/// record's series from some four minutes of a 1 kHz log) are mapped on
/// their own and returned when dropped. Below that size the arenas keep
/// the pages a block leaves for the next blocks instead of returning them
/// and having the system map and zero them afresh, which costs a diagnosis
/// of an hour's log some 20 s of system time (docs/long-logs.md). Where
/// the values land does not change them: the results are the same.
#[cfg(all(target_os = "linux", target_env = "gnu"))]
#[allow(unsafe_code)]
fn return_large_blocks() {
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
    ] {
        if std::env::var_os(variable).is_some() {
            continue;
        }
        // SAFETY: `mallopt` sets one parameter of the C allocator and takes
        // no pointers; it is called first thing in `main`, before this
        // program starts another thread, with M_MMAP_THRESHOLD below
        // glibc's maximum (32 MB on 64-bit) and M_TRIM_THRESHOLD positive:
        // documented, valid settings.
        unsafe {
            libc::mallopt(parameter, value);
        }
    }
}

/// Other systems' allocators: left as they are.
#[cfg(not(all(target_os = "linux", target_env = "gnu")))]
fn return_large_blocks() {}
