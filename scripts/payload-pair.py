"""The payload pair on our own generator: calibrate, then diagnose what changed.

For each robot and seed: friction at every joint (Coulomb and viscous, each drawn from `dynamics
synth`'s realistic range for that joint), an unloaded run diagnosed as the calibration, then a loaded
run (a payload drawn by `synth`, the same friction) diagnosed with `--baseline` the calibration.
A pair passes when the explanation names the payload alone, its mass within 10 % of the truth, and
the held-out torque gap shrinks by at least 0.85 (issue 27's rule; `scripts/mujoco/pair.py` is the
same pair on the MuJoCo yardstick).

    python scripts/payload-pair.py target/release/dynamics OUT arm3r,ur5,panda,mar,rrp 1,2,3,4
"""
import json
import os
import re
import subprocess
import sys


def run(binary, *args):
    r = subprocess.run([binary, *args], capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(" ".join(args) + "\n" + r.stderr[-2000:])


def drawn(truth_file):
    """The drawn effect's parameters, from the truth file's `effect` field."""
    effect = json.load(open(truth_file))["effect"]
    return {k: float(v) for k, v in re.findall(r"(\w+): ([-0-9.eE+]+)", effect)}


def place(e):
    return e["kind"] + "@" + str(e.get("joint") or e.get("point") or "")


def pair(binary, out, robot, seed):
    d = f"{out}/{robot}-{seed}"
    os.makedirs(d, exist_ok=True)
    diagnose = lambda data, json_out, *extra: run(
        binary, "diagnose", "--robot", robot, "--train", f"{d}/{data}.csv",
        "--holdout", f"{d}/{data}-holdout.csv", "--json", json_out, *extra)
    # The joints' names, from a short run's report.
    run(binary, "synth", "--robot", robot, "--effect", "none", "--duration", "0.5", "--out", f"{d}/p.csv")
    diagnose("p", f"{d}/p.json")
    names = [j["joint"] for j in json.load(open(f"{d}/p.json"))["where"]["joints"]]
    effects = []
    for k, name in enumerate(names):
        for i, (kind, params) in enumerate((("coulomb_friction", ("fc", "vw")), ("viscous_friction", ("fv",)))):
            t = f"{d}/t-{kind}-{k}.json"
            run(binary, "synth", "--robot", robot, "--effect", kind, "--joint", name,
                "--seed", str(100 * seed + 2 * k + i), "--duration", "0.5", "--out", f"{d}/t.csv", "--truth", t)
            values = drawn(t)
            effects.append({"kind": kind, "joint": name,
                            "parameters": [{"name": p, "value": values[p]} for p in params]})
    friction = f"{d}/friction.json"
    json.dump({"effects": effects}, open(friction, "w"), indent=1)
    run(binary, "synth", "--robot", robot, "--baseline", friction, "--effect", "none",
        "--seed", str(10 * seed + 1), "--out", f"{d}/ref.csv")
    diagnose("ref", f"{d}/calibration.json")
    run(binary, "synth", "--robot", robot, "--baseline", friction, "--effect", "payload_mass",
        "--seed", str(10 * seed + 2), "--out", f"{d}/loaded.csv", "--truth", f"{d}/truth.json")
    diagnose("loaded", f"{d}/with.json", "--baseline", f"{d}/calibration.json")
    mass_true = drawn(f"{d}/truth.json")["mass"]
    calibration = json.load(open(f"{d}/calibration.json"))["which"]["effects"]
    report = json.load(open(f"{d}/with.json"))
    named = [place(e) for e in report["which"]["effects"]]
    mass = next((p["value"] for e in report["which"]["effects"] if e["kind"] == "payload_mass"
                 for p in e["parameters"] if p["name"] == "mass"), None)
    shrink = report["shrink"]["torque_fraction"]
    ok = (len(named) == 1 and named[0].startswith("payload_mass") and mass is not None
          and abs(mass - mass_true) <= 0.1 * abs(mass_true) and shrink >= 0.85)
    others = [place(e) for e in calibration if e["kind"] not in ("coulomb_friction", "viscous_friction")]
    print(f"{robot:6} seed {seed} payload {mass_true:.3f} kg | calibration names (besides Coulomb and "
          f"viscous friction): {', '.join(others) or '-'} | with --baseline: {', '.join(named) or '-'} | "
          f"mass {mass if mass is None else round(mass, 4)} | shrink {shrink:.3f} | {'pass' if ok else 'FAIL'}",
          flush=True)
    return ok


def main():
    binary, out, robots, seeds = sys.argv[1], sys.argv[2], sys.argv[3].split(","), sys.argv[4].split(",")
    results = [pair(binary, out, r, int(s)) for r in robots for s in seeds]
    print(f"{sum(results)} of {len(results)} pairs: payload alone, mass within 10 %, shrink >= 0.85")


if __name__ == "__main__":
    main()
