#!/usr/bin/env bash
# Builds no-std-check/ (a `#![no_std]` crate with its own panic handler that
# declares robots with `robot!` and calls their outputs; its src/lib.rs says
# why a successful build proves that nothing in its graph links std): for the
# host, and for a Cortex-M4F (thumbv7em-none-eabihf, a target without std)
# where that target is installed or installable.
#
#   bash scripts/no-std.sh           the builds (what .ci/run runs)
#   bash scripts/no-std.sh --sizes   then the code size of each emitted output
#
# Sizes are read with `nm --size-sort` from the Cortex-M4F build (soft double
# precision: every f64 operation a call to the compiler's __aeabi_d*
# routines): each output's wrapper in no-std-check plus the emitted trait
# method where it was not inlined into it.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
MANIFEST=no-std-check/Cargo.toml
TARGET_DIR=target/no-std-check
BARE=thumbv7em-none-eabihf

# The runtime alone without its `std` feature (inside the workspace, only
# this package's own features count), then the crate outside it.
cargo clippy --release -p dynamics-runtime --no-default-features -- -D warnings
cargo fmt --manifest-path "$MANIFEST" -- --check
cargo clippy --manifest-path "$MANIFEST" --release --target-dir "$TARGET_DIR" -- -D warnings
cargo build --manifest-path "$MANIFEST" --release --target-dir "$TARGET_DIR"
echo "no-std: built for the host without std"

if ! rustup target list --installed 2>/dev/null | grep -qx "$BARE"; then
    rustup target add "$BARE" >/dev/null 2>&1 || true
fi
if rustup target list --installed 2>/dev/null | grep -qx "$BARE"; then
    # The workspace's `-C target-cpu=native` (.cargo/config.toml) is for the
    # host's CPU; RUSTFLAGS replaces it (empty: the target's own defaults).
    RUSTFLAGS="" cargo build --manifest-path "$MANIFEST" --release \
        --target-dir "$TARGET_DIR" --target "$BARE"
    echo "no-std: built for $BARE (no std exists for it)"
else
    echo "no-std: target $BARE is not installed and could not be added: host build only"
    [[ "${1:-}" == "--sizes" ]] && exit 1
fi

if [[ "${1:-}" == "--sizes" ]]; then
    RLIB="$TARGET_DIR/$BARE/release/libno_std_check.rlib"
    SYMBOLS="$(nm -C -S "$RLIB" 2>/dev/null)"
    size_of() { # bytes of the symbol whose demangled name is exactly $1 (0 if none)
        local hex
        hex="$(grep -F " $1" <<<"$SYMBOLS" | awk -v n="$1" '{ s = $0; sub(/^[^ ]+ [^ ]+ [^ ]+ /, "", s); if (s == n) print $2 }' | head -1)"
        echo $((16#${hex:-0}))
    }
    printf '%-8s %18s %12s %24s\n' robot inverse_dynamics mass_matrix perturbation_jacobians
    for spec in Arm3r:arm3r:3 Ur5:ur5:6 Panda:panda:7 Slide:slide:3; do
        IFS=: read -r ty module n <<<"$spec"
        row=()
        for f in inverse_dynamics mass_matrix perturbation_jacobians; do
            wrapper=$(size_of "no_std_check::$module::$f")
            method=$(size_of "<no_std_check::$ty as dynamics_runtime::robot::Robot<${n}_usize>>::$f")
            row+=($((wrapper + method)))
        done
        printf '%-8s %18s %12s %24s\n' "$module" "${row[@]}"
    done
fi
