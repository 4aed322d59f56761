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
/// the system when freed (glibc's own starting value).
#[cfg(all(target_os = "linux", target_env = "gnu"))]
const MMAP_THRESHOLD: libc::c_int = 128 * 1024;

/// Fixes glibc's mmap threshold at [`MMAP_THRESHOLD`] unless the
/// environment sets it (`MALLOC_MMAP_THRESHOLD_`). glibc raises the
/// threshold as large blocks are freed and then keeps later ones of that
/// size in its arenas; a diagnosis of a long log makes and drops many
/// per-record vectors of a few MB, and held in the arenas they add up to
/// a fifth of its peak memory (docs/long-logs.md). Where the values land
/// does not change them: the results are the same.
#[cfg(all(target_os = "linux", target_env = "gnu"))]
#[allow(unsafe_code)]
fn return_large_blocks() {
    if std::env::var_os("MALLOC_MMAP_THRESHOLD_").is_some() {
        return;
    }
    // SAFETY: `mallopt` sets one parameter of the C allocator and takes no
    // pointers; it is called first thing in `main`, before this program
    // starts another thread, and M_MMAP_THRESHOLD with a value below
    // glibc's maximum (32 MB on 64-bit) is a documented, valid setting.
    unsafe {
        libc::mallopt(libc::M_MMAP_THRESHOLD, MMAP_THRESHOLD);
    }
}

/// Other systems' allocators: left as they are.
#[cfg(not(all(target_os = "linux", target_env = "gnu")))]
fn return_large_blocks() {}
