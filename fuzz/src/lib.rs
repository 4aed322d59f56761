//! What every fuzz target shares: an allocator that refuses any single
//! allocation above [`LIMIT`], so a reader that believes a hostile length
//! field is caught at the request itself, with or without a sanitizer
//! (libFuzzer's `-malloc_limit_mb` needs a sanitizer's allocator hooks;
//! `-rss_limit_mb` sees only memory that is touched).

use std::alloc::{GlobalAlloc, Layout, System};

/// Lets panics unwind again, for a target whose reader catches a
/// dependency's panics at its own boundary (the Parquet reader's
/// `catch_unwind` around the `parquet` crate's decoder): libfuzzer-sys's
/// panic hook aborts at the panic itself, before any unwinding, so it would
/// report panics the reader catches and turns into errors. The hook set
/// here is silent; a panic that escapes the reader still reaches
/// libfuzzer-sys's own `catch_unwind` around the target, which aborts (a
/// crash, with its input).
pub fn panics_unwind() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| std::panic::set_hook(Box::new(|_| {})));
}

/// The largest single allocation a reader may make: 1 GiB.
pub const LIMIT: usize = 1 << 30;

/// The system allocator, aborting (a crash libFuzzer reports with the
/// input) on a request above [`LIMIT`].
pub struct Bounded;

fn refuse(size: usize) -> ! {
    eprintln!("==fuzz== allocation of {size} bytes exceeds the bound of {LIMIT} bytes");
    std::process::abort()
}

// SAFETY: every call is forwarded to `System` unchanged, or the process ends.
unsafe impl GlobalAlloc for Bounded {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if layout.size() > LIMIT {
            refuse(layout.size());
        }
        // SAFETY: the caller's contract is `System`'s.
        unsafe { System.alloc(layout) }
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        if layout.size() > LIMIT {
            refuse(layout.size());
        }
        // SAFETY: as above.
        unsafe { System.alloc_zeroed(layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        if new_size > LIMIT {
            refuse(new_size);
        }
        // SAFETY: as above.
        unsafe { System.realloc(ptr, layout, new_size) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: as above.
        unsafe { System.dealloc(ptr, layout) }
    }
}
