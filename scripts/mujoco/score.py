#!/usr/bin/env python3
"""Score `dynamics diagnose` on the MuJoCo cases of generate.py against their truth.

For every case folder (train.csv, holdout.csv, truth.json; or train.csv.gz and
holdout.csv.gz) it runs

    dynamics diagnose --robot R --train train.csv --holdout holdout.csv --json report.json

(the program's printed report goes to diagnose.txt beside it, or under --reports) and compares the
report's compound explanation, `which.effects[]`, with truth.json's `effects`.

Matching rules (both sides are reduced to *units*, and a unit counts once):

- friction: a true `coulomb_friction` or `viscous_friction` on joint J is the
  unit "friction at J"; a named `coulomb_friction`, `viscous_friction` or
  `stribeck_friction` at J matches it (any of the three, one or several).
- `payload_mass`: matched by kind alone (wherever the report puts it).
- `time_delay`: matched by kind alone (its channel is not required to agree;
  the truth's is `effort`).
- every other kind (`armature`, `joint_spring`, `effort_scale`, and anything the
  truth does not hold, e.g. `inertial_parameters` at a link or
  `encoder_offset`): kind and place (joint, or point/link) must both agree.

Per case: recall = true units named / true units; precision = named units that
are true / named units (undefined when nothing is named); a control is clean
when `which.effects` is empty. Totals: mean recall over effect cases (and the
same for the units other than friction), mean precision over the cases that
name something (a control that names something scores 0), precision pooled
over all named units, controls clean, and the median held-out shrink
(`shrink.fraction`) over the effect cases. The list of false units is printed
by kind with the cases it appears on.

    python scripts/mujoco/score.py out/mujoco --jobs 1 --summary out/mujoco/summary.json

Only the Python standard library (and the `dynamics` program).
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))

FRICTION = {"coulomb_friction", "viscous_friction", "stribeck_friction"}
BY_KIND = {"payload_mass", "time_delay"}


def unit(effect: dict) -> str:
    """The unit an effect (of the truth or of a report) counts as."""
    kind = effect["kind"]
    if kind in FRICTION:
        return f"friction@{effect.get('joint')}"
    if kind in BY_KIND:
        return kind
    place = effect.get("joint") or effect.get("point") or effect.get("link") or ""
    return f"{kind}@{place}" if place else kind


def diagnose(binary: str, case_dir: str, robot: str, reuse: bool, out_dir: str) -> tuple:
    """Run the diagnosis of one case, writing report.json and diagnose.txt to
    `out_dir`; returns (report or None, seconds, error)."""
    os.makedirs(out_dir, exist_ok=True)
    report = os.path.join(out_dir, "report.json")
    if reuse and os.path.exists(report):
        with open(report) as f:
            return json.load(f), float("nan"), ""
    def data(part):
        plain = os.path.join(case_dir, f"{part}.csv")
        return plain if os.path.exists(plain) else plain + ".gz"

    cmd = [binary, "diagnose", "--robot", robot, "--train", data("train"),
           "--holdout", data("holdout"), "--json", report]
    t0 = time.time()
    p = subprocess.run(cmd, capture_output=True, text=True)
    seconds = time.time() - t0
    with open(os.path.join(out_dir, "diagnose.txt"), "w") as f:
        f.write(p.stdout)
        f.write(p.stderr)
    if p.returncode != 0:
        return None, seconds, (p.stderr.strip().splitlines() or ["exit %d" % p.returncode])[-1]
    with open(report) as f:
        return json.load(f), seconds, ""


def score_case(truth: dict, report: dict | None) -> dict:
    true_units = sorted({unit(e) for e in truth["effects"]})
    named = [] if report is None else report["which"]["effects"]
    named_units = sorted({unit(e) for e in named})
    hit = [u for u in true_units if u in named_units]
    false = [u for u in named_units if u not in true_units]
    other_true = [u for u in true_units if not u.startswith("friction@")]
    shrink = None if report is None else report["shrink"].get("fraction")
    return {
        "case": truth["case"],
        "robot": truth["robot"],
        "control": truth["control"],
        "rate": truth["rate"],
        "jitter": truth["jitter"],
        "repeats": truth["repeats"],
        "true": true_units,
        "named": named_units,
        "missed": [u for u in true_units if u not in named_units],
        "false": false,
        "recall": len(hit) / len(true_units) if true_units else None,
        "recall_other": (sum(u in named_units for u in other_true) / len(other_true)
                         if other_true else None),
        "precision": (len(named_units) - len(false)) / len(named_units) if named_units else None,
        "clean": (not named_units) if truth["control"] else None,
        "shrink": shrink,
        "rms_shrink": None if report is None else report["shrink"].get("rms_fraction"),
        "failed": report is None,
    }


def mean(xs):
    xs = [x for x in xs if x is not None]
    return sum(xs) / len(xs) if xs else None


def totals(rows: list) -> dict:
    mixes = [r for r in rows if not r["control"]]
    controls = [r for r in rows if r["control"]]
    naming = [r for r in rows if r["named"]]
    named = sum(len(r["named"]) for r in rows)
    false = sum(len(r["false"]) for r in rows)
    false_by_kind: dict = {}
    for r in rows:
        for u in r["false"]:
            false_by_kind.setdefault(u.split("@")[0], []).append(f"{r['case']}:{u}")
    shrinks = [r["shrink"] for r in mixes if r["shrink"] is not None]
    return {
        "cases": len(rows),
        "effect_cases": len(mixes),
        "controls": len(controls),
        "failed": sum(r["failed"] for r in rows),
        "mean_recall": mean(r["recall"] for r in mixes),
        "mean_recall_other_than_friction": mean(r["recall_other"] for r in mixes),
        "mean_precision": mean(r["precision"] for r in naming),
        "pooled_precision": (named - false) / named if named else None,
        "controls_clean": sum(bool(r["clean"]) for r in controls),
        "median_shrink": statistics.median(shrinks) if shrinks else None,
        "false_by_kind": false_by_kind,
    }


def fmt(x, spec=".2f"):
    return "-" if x is None else format(x, spec)


def table(rows: list, tot: dict) -> str:
    lines = [f"{'case':22s} {'rate':>5s} {'jit':>4s} {'rep':>4s} {'recall':>6s} {'other':>5s} "
             f"{'prec':>5s} {'clean':>5s} {'shrink':>6s} {'time':>5s}  true (besides friction) | false named | missed"]
    for r in rows:
        other = [u for u in r["true"] if not u.startswith("friction@")]
        lines.append(
            f"{r['case']:22s} {r['rate']:5.0f} {r['jitter']:4.1f} {r['repeats']:4.2f} "
            f"{fmt(r['recall']):>6s} {fmt(r['recall_other']):>5s} {fmt(r['precision']):>5s} "
            f"{('yes' if r['clean'] else 'NO') if r['control'] else '':>5s} {fmt(r['shrink']):>6s} "
            f"{fmt(r.get('seconds'), '.1f'):>5s}  {', '.join(other) or '-'} | "
            f"{', '.join(r['false']) or '-'} | {', '.join(r['missed']) or '-'}"
            + ("  (diagnosis failed: " + r.get("error", "") + ")" if r["failed"] else ""))
    lines.append("")
    lines.append(f"cases {tot['cases']} ({tot['effect_cases']} effect mixes, {tot['controls']} controls, "
                 f"{tot['failed']} failed)")
    lines.append(f"mean recall {fmt(tot['mean_recall'], '.3f')} (units other than friction "
                 f"{fmt(tot['mean_recall_other_than_friction'], '.3f')})")
    lines.append(f"mean precision {fmt(tot['mean_precision'], '.3f')} over cases naming something; "
                 f"pooled {fmt(tot['pooled_precision'], '.3f')}")
    lines.append(f"controls clean {tot['controls_clean']} of {tot['controls']}")
    lines.append(f"median held-out shrink {fmt(tot['median_shrink'], '.3f')} (effect cases)")
    lines.append("false units by kind:")
    for kind, where in sorted(tot["false_by_kind"].items(), key=lambda kv: -len(kv[1])):
        lines.append(f"  {kind:22s} {len(where):3d}: {', '.join(where)}")
    return "\n".join(lines)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("cases", help="folder of case folders (generate.py --out)")
    ap.add_argument("--dynamics", default=os.path.join(ROOT, "target", "release", "dynamics"),
                    help="the dynamics program")
    ap.add_argument("--jobs", type=int, default=1, help="diagnoses run at once")
    ap.add_argument("--summary", default="", help="JSON summary (default: CASES/summary.json)")
    ap.add_argument("--reuse", action="store_true", help="score existing report.json files")
    ap.add_argument("--reports", default="",
                    help="folder for each case's report.json and diagnose.txt (default: the case folders)")
    a = ap.parse_args(argv)
    dirs = sorted(d for d in os.listdir(a.cases)
                  if os.path.exists(os.path.join(a.cases, d, "truth.json")))
    truths = []
    for d in dirs:
        with open(os.path.join(a.cases, d, "truth.json")) as f:
            truths.append((os.path.join(a.cases, d), json.load(f)))

    def one(item):
        case_dir, truth = item
        out_dir = os.path.join(a.reports, os.path.basename(case_dir)) if a.reports else case_dir
        report, seconds, error = diagnose(a.dynamics, case_dir, truth["robot"], a.reuse, out_dir)
        row = score_case(truth, report)
        row["seconds"] = seconds
        row["error"] = error
        return row

    t0 = time.time()
    with ThreadPoolExecutor(max_workers=max(1, a.jobs)) as pool:
        rows = list(pool.map(one, truths))
    tot = totals(rows)
    tot["wall_seconds"] = time.time() - t0
    print(table(rows, tot))
    print(f"wall time {tot['wall_seconds']:.0f} s with {a.jobs} job(s)")
    summary = a.summary or os.path.join(a.cases, "summary.json")
    with open(summary, "w") as f:
        json.dump({"totals": tot, "cases": rows}, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
