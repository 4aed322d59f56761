#!/usr/bin/env python3
"""Calibrate, then diagnose what changed: the payload pair on the MuJoCo yardstick.

For each robot, generate.py writes two runs of the same references, friction
and noise seeds: unloaded (friction on every joint) and loaded (the same plus
a body at the tip). The unloaded run is diagnosed alone (the calibration);
the loaded run is diagnosed with that report as `--baseline`. The pair passes
when the second report names the payload and nothing else, its mass within
10 % of the body MuJoCo carries, and the held-out shrink is at least 0.85.

Usage:

    python scripts/mujoco/pair.py --out /tmp/pairs --seed-base 3 \\
        --dynamics target/release/dynamics [--robots panda,ur5,mar,arm3r]

Prints a table and writes OUT/pairs.json. Exit status 0 whatever the
outcome (it is a measurement, not a test).
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time

import generate as g

MASS_TOLERANCE = 0.10
SHRINK_TARGET = 0.85


def run(binary: str, robot: str, case_dir: str, report: str, baseline: str | None) -> tuple:
    """`dynamics diagnose` of one run; returns (report or None, seconds, error line)."""
    cmd = [binary, "diagnose", "--robot", robot,
           "--train", os.path.join(case_dir, "train.csv"),
           "--holdout", os.path.join(case_dir, "holdout.csv"), "--json", report]
    if baseline:
        cmd += ["--baseline", baseline]
    t0 = time.time()
    p = subprocess.run(cmd, capture_output=True, text=True)
    seconds = time.time() - t0
    with open(report[:-len(".json")] + ".txt", "w") as f:
        f.write(p.stdout)
        f.write(p.stderr)
    if p.returncode != 0:
        return None, seconds, (p.stderr.strip().splitlines() or [f"exit {p.returncode}"])[-1]
    with open(report) as f:
        return json.load(f), seconds, ""


def place(e: dict) -> str:
    where = e.get("joint") or e.get("point") or e.get("link") or ""
    return f"{e['kind']}@{where}" if where else e["kind"]


def value(e: dict, name: str):
    return next((p["value"] for p in e.get("parameters", []) if p["name"] == name), None)


def score(truth_mass: float, cal: dict | None, loaded: dict | None) -> dict:
    row = {"calibration": [], "named": [], "mass": None, "shrink": None, "pass": False}
    if cal is not None:
        row["calibration"] = sorted({place(e) for e in cal["which"]["effects"]
                                     if e["kind"] not in ("coulomb_friction", "viscous_friction")})
    if loaded is None:
        return row
    named = loaded["which"]["effects"]
    row["named"] = [place(e) for e in named]
    payloads = [e for e in named if e["kind"] == "payload_mass"]
    if len(payloads) == 1:
        row["mass"] = value(payloads[0], "mass")
    row["shrink"] = loaded.get("shrink", {}).get("fraction")
    row["pass"] = (len(named) == 1 and row["mass"] is not None
                   and abs(row["mass"] - truth_mass) <= MASS_TOLERANCE * truth_mass
                   and row["shrink"] is not None and row["shrink"] >= SHRINK_TARGET)
    return row


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", required=True, help="folder for the runs and reports")
    ap.add_argument("--seed-base", type=int, default=0, help="seed base (generate.py's)")
    ap.add_argument("--robots", default=",".join(g.ROBOTS), help="comma-separated robots")
    ap.add_argument("--duration", type=float, default=8.0, help="seconds of each of train and holdout")
    ap.add_argument("--dynamics", default=os.path.join(g.ROOT, "target", "release", "dynamics"))
    a = ap.parse_args(argv)
    os.makedirs(a.out, exist_ok=True)
    rows = []
    for robot in [r for r in a.robots.split(",") if r]:
        seed = a.seed_base * 100_000 + 99_999
        unloaded, loaded = g.make_payload_pair(a.out, robot, seed, g.Logging(rate=1000.0, jitter=0.0, repeats=0.0),
                                               a.duration)
        truth = next(value(e, "mass") for e in loaded["effects"] if e["kind"] == "payload_mass")
        cal_path = os.path.join(a.out, f"{robot}-calibration.json")
        cal, t1, err1 = run(a.dynamics, robot, os.path.join(a.out, unloaded["case"]), cal_path, None)
        loaded_report, t2 = None, 0.0
        err2 = ""
        if cal is not None:
            loaded_path = os.path.join(a.out, f"{robot}-loaded.json")
            loaded_report, t2, err2 = run(a.dynamics, robot, os.path.join(a.out, loaded["case"]), loaded_path,
                                          cal_path)
        row = score(truth, cal, loaded_report)
        row.update(robot=robot, truth=truth, seconds=t1 + t2, error=err1 or err2)
        rows.append(row)
        mass = "-" if row["mass"] is None else f"{row['mass']:.3f}"
        shrink = "-" if row["shrink"] is None else f"{row['shrink']:.3f}"
        print(f"{robot:6s} payload {truth:.3f} kg | calibration names (besides friction): "
              f"{', '.join(row['calibration']) or 'nothing'} | loaded with --baseline names: "
              f"{', '.join(row['named']) or 'nothing'} | mass {mass} | shrink {shrink} | "
              f"{'pass' if row['pass'] else 'FAIL'}{' | ' + row['error'] if row['error'] else ''}", flush=True)
    passed = sum(r["pass"] for r in rows)
    print(f"{passed} of {len(rows)} pairs: payload alone, mass within {MASS_TOLERANCE:.0%}, "
          f"shrink >= {SHRINK_TARGET}")
    with open(os.path.join(a.out, "pairs.json"), "w") as f:
        json.dump(rows, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
