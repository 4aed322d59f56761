#!/usr/bin/env bash
# One benchmark sitting: the CasADi anchor, our generated dynamics, the CasADi
# anchor again and Pinocchio, back to back on one pinned core, then one table
# of medians and ratios (the machines are noisy: quote ratios from one sitting).
#
#   bash scripts/bench-sitting.sh [SHARED]     (SHARED defaults to ../shared)
#   ROBOTS=panda bash scripts/bench-sitting.sh  (a subset: ours and Pinocchio's
#                                               bench_native only, no CasADi; ~3 min)
#
# Needs the anchors of SHARED/anchors/pinocchio (their README: `bash build.sh`
# once, ~5 min, then this script reuses the binaries). Output: the table on
# stdout and the raw logs in target/sitting/. Takes about 12 minutes.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
SHARED="$(cd "${1:-$ROOT/../shared}" && pwd)"
ANCHOR="$SHARED/anchors/pinocchio"
OUT="$ROOT/target/sitting"
mkdir -p "$OUT"
PIN=""; command -v taskset >/dev/null && PIN="taskset -c 1"
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)" | tee "$OUT/load.txt"
ALL="arm3r rrp mar ur5 panda"
ROBOTS="${ROBOTS:-$ALL}"
BUILD="${BUILD:-/tmp/anchors/build}"
cd "$ROOT"
cargo bench -p robots --bench dynamics --no-run >/dev/null 2>&1
cargo bench -p robots --bench batch --no-run >/dev/null 2>&1
rm -f "$OUT"/casadi-*.log
[ "$ROBOTS" = "$ALL" ] && bash "$ANCHOR/build.sh" casadi > "$OUT/casadi-before.log" 2>&1
for r in $ROBOTS; do rm -rf "target/criterion/$r"; done
$PIN cargo bench -p robots --bench dynamics -- "^($(echo $ROBOTS | tr ' ' '|'))/" > "$OUT/ours.log" 2>&1
# The batch functions (1000 states a call) on the arms the batch bench covers.
BATCHED="$(for r in $ROBOTS; do case $r in ur5|panda) echo -n "$r ";; esac; done)"
for r in $BATCHED; do rm -rf "target/criterion/$r x1000"; done
[ -n "$BATCHED" ] && $PIN cargo bench -p robots --bench batch -- "^($(echo $BATCHED | tr ' ' '|')) x1000/" > "$OUT/ours-batch.log" 2>&1
if [ "$ROBOTS" = "$ALL" ]; then
  bash "$ANCHOR/build.sh" casadi > "$OUT/casadi-after.log" 2>&1
  bash "$ANCHOR/build.sh" run > "$OUT/pinocchio.log" 2>&1
  PIN_CSV="$BUILD/bench_native.csv"
else
  args=""; for r in $ROBOTS; do args="$args $r=$BUILD/models/$r.txt"; done
  PIN_CSV="$OUT/bench_native.csv"
  $PIN "$BUILD/bench_native" --calls "${CALLS:-200000}" --reps "${REPS:-7}" --csv "$PIN_CSV" $args \
    > "$OUT/pinocchio.log" 2>&1
fi
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)" | tee -a "$OUT/load.txt"
python3 - "$ROOT/target/criterion" "$OUT" "$PIN_CSV" $ROBOTS <<'PY'
import csv, glob, json, os, re, sys
crit, out, pin_csv = sys.argv[1:4]
robots = sys.argv[4:]
ours = {}
for f in glob.glob(os.path.join(crit, "*", "*", "new", "benchmark.json")):
    b = json.load(open(f))
    est = json.load(open(os.path.join(os.path.dirname(f), "estimates.json")))
    ours[(b["group_id"], b["function_id"].split(" ")[0])] = est["median"]["point_estimate"]
def casadi(log):
    d = {}
    for line in open(log):
        m = re.match(r"(\w+)_(crba|rnea) n=\d+ median ([\d.]+)", line)
        if m:
            d[(m.group(1), m.group(2))] = float(m.group(3))
    return d
pin = {r["robot"]: r for r in csv.DictReader(open(pin_csv))}
def row(cells): print("| " + " | ".join(cells) + " |")
def f(x): return f"{x:.1f}"
print("\nMedian ns per call, thread CPU time, pinned to core 1. CasADi before / after ours.\n")
has_casadi = os.path.exists(os.path.join(out, "casadi-after.log"))
if has_casadi:
    cb, ca = casadi(os.path.join(out, "casadi-before.log")), casadi(os.path.join(out, "casadi-after.log"))
    row(["robot", "A (ours)", "CasADi crba", "ratio", "tau (ours)", "CasADi rnea", "ratio", "Pin crba", "Pin rnea"])
    row(["---"] * 9)
for r in robots if has_casadi else []:
    a, t = ours[(r, "mass_matrix")], ours[(r, "inverse_dynamics")]
    cr = (cb[(r, "crba")], ca[(r, "crba")]); rn = (cb[(r, "rnea")], ca[(r, "rnea")])
    row([r, f(a), f"{f(cr[0])} / {f(cr[1])}", f"{a/max(cr):.2f}-{a/min(cr):.2f}",
         f(t), f"{f(rn[0])} / {f(rn[1])}", f"{t/max(rn):.2f}-{t/min(rn):.2f}",
         pin[r]["crba"], pin[r]["rnea"]])
print()
row(["robot", "A+Qqt+Q0 (ours)", "Pin crba+nle", "ratio", "K,D (ours)", "Pin rnea_derivs", "ratio", "fwd (ours)", "Pin aba", "ratio"])
row(["---"] * 10)
for r in robots:
    m = ours[(r, "motion_terms")]; cn = float(pin[r]["crba"]) + float(pin[r]["nle"])
    k = ours[(r, "perturbation_jacobians")]; d = float(pin[r]["rnea_derivs"])
    fw = ours[(r, "forward_dynamics")]; ab = float(pin[r]["aba"])
    row([r, f(m), f(cn), f"{m/cn:.3f}", f(k), f(d), f"{k/d:.2f}", f(fw), f(ab), f"{fw/ab:.2f}"])
print()
row(["robot", "fwd derivs (ours)", "Pin aba_derivs", "ratio", "A_c, B_c (ours)", "ratio", "ZOH h = 1 ms (ours)"])
row(["---"] * 7)
for r in robots:
    fd = ours[(r, "forward_dynamics_derivatives")]; ss = ours[(r, "state_space")]
    zoh = ours[(r, "zero_order_hold")]; ad = float(pin[r]["aba_derivs"])
    row([r, f(fd), f(ad), f"{fd/ad:.2f}", f(ss), f"{ss/ad:.2f}", f(zoh)])
batch = {}
for path in glob.glob(os.path.join(crit, "* x1000", "*", "new", "benchmark.json")):
    b = json.load(open(path))
    est = json.load(open(os.path.join(os.path.dirname(path), "estimates.json")))
    batch[(b["group_id"].split(" ")[0], b["function_id"])] = est["median"]["point_estimate"] / 1000.0
batched = [r for r in robots if (r, "inverse_dynamics: scalar calls") in batch]
if batched:
    print("\nPer state, batches of 1000 states (ns; ours: best lane level this CPU has, and the")
    print("scalar methods called once per state; Pinocchio: its loop over 1000 states, one call each).\n")
    row(["robot", "output", "ours batch", "ours scalar", "speed-up", "Pinocchio", "ratio batch", "ratio single call"])
    row(["---"] * 8)
    for r in batched:
        for name, pin_key in [("inverse_dynamics", "rnea"), ("mass_matrix", "crba"),
                              ("perturbation_jacobians", "rnea_derivs"),
                              ("forward_dynamics_derivatives", "aba_derivs")]:
            levels = [v for (rr, fid), v in batch.items() if rr == r and fid.startswith(name + ": batch")]
            if not levels:
                continue
            b, sc = min(levels), batch[(r, name + ": scalar calls")]
            p = float(pin[r][pin_key])
            row([r, name, f(b), f(sc), f"{sc/b:.2f}", f(p), f"{b/p:.3f}", f"{sc/p:.3f}"])
PY
