#!/usr/bin/env bash
# rustc time of the code `robot!` emits, apart from the expansion (which
# `cargo bench -p dynamics-codegen --bench expand` times): the expansion of
# each robot of the `robots` crate, every output, is written to a file by the
# `expanded` example and compiled alone as a library against dynamics-runtime,
# at opt-level 0 and 3, with the workspace's `-C target-cpu=native`. The
# `#[inline]` attributes are removed first: otherwise a library compiles none
# of the methods (a user's crate compiles those it calls), and this measures
# what a crate calling every method pays. Lints are capped: rustc does not
# run them on macro-generated code in a real build.
#   bash dynamics-codegen/scripts/rustc_time.sh [DIR]   (default target/expanded)
# Prints one line per robot and level: wall seconds, CPU seconds, peak memory.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
OUT="${1:-$ROOT/target/expanded}"
cd "$ROOT"
cargo run --release -q -p dynamics-codegen --example expanded -- "$OUT" >/dev/null
RLIB="$(cargo build --release -p dynamics-runtime --message-format=json 2>/dev/null |
  grep -o '"[^"]*/libdynamics_runtime[^"]*\.rlib"' | tail -1 | tr -d '"')"
[ -f "$RLIB" ] || { echo "no dynamics-runtime rlib found" >&2; exit 1; }
DEPS="$ROOT/target/release/deps"
printf '%-6s %-5s %8s %8s %9s %9s\n' robot opt wall_s cpu_s max_MB source_KB
for r in arm3r rrp mar ur5 panda; do
  sed 's/# \[inline\]//g' "$OUT/$r.rs" >"$OUT/${r}_all.rs"
  for o in 0 3; do
    /usr/bin/time -f "%e %U %S %M" -o "$OUT/time" \
      rustc --edition 2021 --crate-type lib --crate-name "emitted_$r" \
      -C opt-level=$o -C target-cpu=native --cap-lints allow \
      --extern dynamics_runtime="$RLIB" -L dependency="$DEPS" \
      --out-dir "$OUT/o$o" "$OUT/${r}_all.rs"
    read -r wall user sys mem <"$OUT/time"
    printf '%-6s %-5s %8s %8.2f %9d %9d\n' "$r" "$o" "$wall" "$(echo "$user + $sys" | bc)" \
      $((mem / 1024)) $(($(stat -c %s "$OUT/$r.rs") / 1024))
  done
done
