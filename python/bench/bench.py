"""Per-state cost of the Panda's dynamics from Python: this package beside
Pinocchio's Python bindings (`pip install pin`), in the same sitting.

    python3 python/bench/bench.py            # all rows (needs `pin`)
    RAYON_NUM_THREADS=1 python3 python/bench/bench.py --ours-only

Each figure is the best of REPEATS runs of the whole call (or loop),
divided by the number of states, in microseconds. Pinocchio reads the same
URDF (robots/data/urdf/panda.urdf: 7 joints, the hand welded), ours is
`dynamics.Robot("panda")` (the rigid body, as Pinocchio models it). The rows
of our batches with one thread run in a child process started with
RAYON_NUM_THREADS=1 (rayon reads it once, when its pool starts).
"""

import argparse
import os
import pathlib
import subprocess
import sys
import time

import numpy as np

import dynamics

ROOT = pathlib.Path(__file__).resolve().parents[2]
URDF = ROOT / "robots" / "data" / "urdf" / "panda.urdf"
REPEATS = 5


def best(f, states):
    times = []
    for _ in range(REPEATS):
        t0 = time.perf_counter()
        f()
        times.append(time.perf_counter() - t0)
    return min(times) / states * 1e6


def data(batch, seed=1):
    rng = np.random.default_rng(seed)
    arm = dynamics.Robot("panda")
    lo, hi = arm.lower, arm.upper
    q = rng.uniform(lo, hi, (batch, 7))
    v = rng.uniform(-2, 2, (batch, 7))
    a = rng.uniform(-2, 2, (batch, 7))
    return q, v, a


def ours(big):
    arm = dynamics.Robot("panda")
    rows = {}
    q, v, a = data(1)
    q1, v1, a1 = q[0], v[0], a[0]
    loop = 20000
    rows["ours rnea B=1"] = best(lambda: [arm.rnea(q1, v1, a1) for _ in range(loop)], loop)
    rows["ours mass_matrix B=1"] = best(lambda: [arm.mass_matrix(q1) for _ in range(loop)], loop)
    rows["ours rnea_derivatives B=1"] = best(
        lambda: [arm.rnea_derivatives(q1, v1, a1) for _ in range(loop)], loop)
    t1, m1 = np.empty(7), np.empty((7, 7))
    rows["ours rnea out= B=1"] = best(
        lambda: [arm.rnea(q1, v1, a1, out=t1) for _ in range(loop)], loop)
    rows["ours mass_matrix out= B=1"] = best(
        lambda: [arm.mass_matrix(q1, out=m1) for _ in range(loop)], loop)
    rows["ours state_space B=1"] = best(
        lambda: [arm.state_space(q1, v1, a1) for _ in range(loop)], loop)
    rows["ours state_space dt=1e-3 B=1"] = best(
        lambda: [arm.state_space(q1, v1, a1, 1e-3) for _ in range(loop)], loop)
    Q, V, A = data(big)
    rows[f"ours rnea B={big}"] = best(lambda: arm.rnea(Q, V, A), big)
    rows[f"ours mass_matrix B={big}"] = best(lambda: arm.mass_matrix(Q), big)
    rows[f"ours rnea_derivatives B={big}"] = best(lambda: arm.rnea_derivatives(Q, V, A), big)
    T, M = np.empty((big, 7)), np.empty((big, 7, 7))
    rows[f"ours rnea out= B={big}"] = best(lambda: arm.rnea(Q, V, A, out=T), big)
    rows[f"ours mass_matrix out= B={big}"] = best(lambda: arm.mass_matrix(Q, out=M), big)
    rows[f"ours state_space B={big}"] = best(lambda: arm.state_space(Q, V, A), big)
    return rows


def pinocchio(big):
    import pinocchio as pin

    model = pin.buildModelFromUrdf(str(URDF))
    d = model.createData()
    rows = {}
    q, v, a = data(1)
    q1, v1, a1 = q[0], v[0], a[0]
    loop = 20000
    rows["pin.rnea B=1"] = best(lambda: [pin.rnea(model, d, q1, v1, a1) for _ in range(loop)], loop)
    rows["pin.crba B=1"] = best(lambda: [pin.crba(model, d, q1) for _ in range(loop)], loop)
    rows["pin.computeRNEADerivatives B=1"] = best(
        lambda: [pin.computeRNEADerivatives(model, d, q1, v1, a1) for _ in range(loop)], loop)
    Q, V, A = data(big)
    rows[f"Python loop over pin.rnea B={big}"] = best(
        lambda: [pin.rnea(model, d, Q[k], V[k], A[k]) for k in range(big)], big)
    rows[f"Python loop over pin.crba B={big}"] = best(
        lambda: [pin.crba(model, d, Q[k]) for k in range(big)], big)
    rows[f"Python loop over pin.computeRNEADerivatives B={big}"] = best(
        lambda: [pin.computeRNEADerivatives(model, d, Q[k], V[k], A[k]) for k in range(big)], big)
    pool = pin.ModelPool(model, 2)
    Qt, Vt, At = (np.asfortranarray(x.T) for x in (Q, V, A))
    tau = np.zeros((7, big), order="F")
    for threads in (1, 2):
        rows[f"pin.rneaInParallel {threads} thread(s) B={big}"] = best(
            lambda: pin.rneaInParallel(threads, pool, Qt, Vt, At, tau), big)
    # Same values (the rigid body either way).
    ours_tau = dynamics.Robot("panda").rnea(Q, V, A)
    err = np.max(np.abs(ours_tau - tau.T)) / np.max(np.abs(tau))
    rows["(max relative difference of the two rnea batches)"] = err
    return rows


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--ours-only", action="store_true")
    p.add_argument("--batch", type=int, default=10000)
    args = p.parse_args()
    rows = ours(args.batch)
    if not args.ours_only:
        env = dict(os.environ, RAYON_NUM_THREADS="1")
        child = subprocess.run(
            [sys.executable, __file__, "--ours-only", "--batch", str(args.batch)],
            env=env, capture_output=True, text=True, check=True)
        for line in child.stdout.splitlines():
            name, value = line.rsplit("  ", 1)
            if "B=1 " not in name + " ":
                rows[name.strip() + " (1 thread)"] = float(value)
        rows.update(pinocchio(args.batch))
    for name, value in rows.items():
        print(f"{name:60s}  {value:.4g}")


if __name__ == "__main__":
    main()
