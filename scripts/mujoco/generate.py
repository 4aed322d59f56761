#!/usr/bin/env python3
"""Sim-to-real test cases from MuJoCo: an outside simulator as the yardstick of the diagnosis.

Each case is a robot of the repository (its URDF imported into MuJoCo with the
inertials exactly as written) driven by this script's own controller, with
effects MuJoCo models itself and logging artefacts added on the way to the
CSV. The model the diagnosis is given is the clean built-in robot of the same
name, so everything added here is the gap it has to name.

Effects (MuJoCo parameter -> effect kind of the diagnosis report):

    joint damping                 -> viscous_friction  (fv = damping)
    joint frictionloss            -> coulomb_friction  (fc = frictionloss; MuJoCo's
                                     soft dry-friction constraint, no tanh width)
    joint armature                -> armature          (inertia = armature)
    a body at the tip/flange      -> payload_mass      (mass)
    joint stiffness + springref   -> joint_spring      (stiffness = k,
                                     preload = -k * springref: the joint feels
                                     -k (q - springref) = -(k q + preload))
    effort stream shifted late    -> time_delay        (channel effort, delay s)
    logged effort = k x applied   -> effort_scale      (scale = k, one joint)

Logging conditions that are not effects: the sample rate (1 kHz, or 100 Hz
with sample instants jittered by up to +-30 % of the period, each instant
stamped exactly), repeated rows (a row whose values repeat the previous row's,
with its own time stamp), sensor noise (white noise on q, qd and effort, plus
an encoder quantisation of q).

The logged effort is the actuator torque at the sample's instant: the
controller updates every physics step (0.5 ms) and holds its torque over the
step; a sample at step boundary t logs the mean of the torques held just
before and just after t, which is the torque at t to second order.

Usage:

    python scripts/mujoco/generate.py --out out/mujoco --seed-base 0 --cases 44
    python scripts/mujoco/generate.py --idcheck --dynamics target/release/dynamics

Only Python, NumPy and MuJoCo (scripts/mujoco/requirements.txt).
"""

from __future__ import annotations

import argparse
import gzip
import io
import json
import os
import re
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass

import mujoco
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))
URDF_DIR = os.path.join(ROOT, "robots", "data", "urdf")

# Physics step and integrator: 0.5 ms, MuJoCo's fourth-order Runge-Kutta.
TIMESTEP = 5e-4
INTEGRATOR = mujoco.mjtIntegrator.mjINT_RK4
# Time constant of MuJoCo's dry-friction constraint (default 0.02 s would make
# the friction creep over a wide velocity band); >= 2 physics steps.
FRICTION_TIMECONST = 0.004
# Pre-roll before the first logged sample, s (start-up transients and the
# effort history a delayed effort stream needs).
PRE_ROLL = 0.25


@dataclass(frozen=True)
class RobotSpec:
    """A robot of the repository as this generator uses it."""

    name: str  # the built-in robot of `dynamics` (the diagnosis's model)
    urdf: str  # file under robots/data/urdf
    gravity: tuple  # as the built-in model has it
    home: tuple  # centre of the reference motion
    amplitude: tuple  # amplitude of the reference motion per joint
    payload_body: str  # MuJoCo body the payload is welded to
    payload_pos: tuple  # its position in that body's frame
    tip: str  # the point the diagnosis reports for a payload
    nominal_damping: tuple = ()  # the built-in model's own viscous damping


ROBOTS = {
    "panda": RobotSpec(
        "panda", "panda.urdf", (0.0, 0.0, -9.81),
        (0.0, -0.4, 0.0, -2.0, 0.0, 1.7, 0.8), (0.35,) * 7,
        # At the tool centre point, 0.1034 m beyond the hand's origin (the
        # built-in panda's tool frame, `panda_hand_tcp`).
        "panda_hand", (0.0, 0.0, 0.1034), "panda_hand_tcp",
    ),
    "ur5": RobotSpec(
        "ur5", "ur5.urdf", (0.0, 0.0, -9.81),
        (0.0, -1.2, 1.2, -1.5, -1.5, 0.0), (0.4,) * 6,
        # The flange, `tool0` (the built-in ur5's tool frame).
        "tool0", (0.0, 0.0, 0.0), "tool0",
    ),
    "arm3r": RobotSpec(
        "arm3r", "arm3r.urdf", (0.0, -9.8, 0.0),
        (0.0, 0.4, -0.4), (0.6, 0.6, 0.6),
        "payload", (0.0, 0.0, 0.0), "tip",
    ),
    "mar": RobotSpec(
        "mar", "mar.urdf", (0.0, -9.81, 0.0),
        (0.0, 0.3, 0.05), (0.4, 0.5, 0.04),
        # The built-in mar's `gripper` point: 0.21 m beyond link 3's centre.
        "link3", (0.39, 0.0, 0.0), "gripper",
    ),
}


# ---------------------------------------------------------------- the model


def urdf_text(spec: RobotSpec) -> str:
    """The robot's URDF without visual, collision and joint dynamics elements,
    with compiler options that keep the inertials exactly as written."""
    with open(os.path.join(URDF_DIR, spec.urdf)) as f:
        src = f.read()
    src = re.sub(r"<!--.*?-->", "", src, flags=re.S)
    for tag in ("visual", "collision"):
        src = re.sub(rf"<{tag}\b.*?</{tag}>", "", src, flags=re.S)
        src = re.sub(rf"<{tag}\b[^>]*/>", "", src)
    src = re.sub(r"<dynamics\b[^>]*/>", "", src)
    compiler = (
        '<mujoco><compiler discardvisual="true" fusestatic="false" '
        'balanceinertia="false" inertiafromgeom="false" boundmass="0" '
        'boundinertia="0" angle="radian"/></mujoco>'
    )
    return src.replace("</robot>", compiler + "</robot>")


@dataclass
class Effects:
    """The effects of one case in MuJoCo's own parameters, per joint."""

    damping: np.ndarray
    frictionloss: np.ndarray
    armature: np.ndarray
    stiffness: np.ndarray
    springref: np.ndarray
    payload: float = 0.0
    delay: float = 0.0
    scale: np.ndarray | None = None  # per joint; none() sets ones

    @staticmethod
    def none(n: int) -> "Effects":
        z = np.zeros(n)
        return Effects(z.copy(), z.copy(), z.copy(), z.copy(), z.copy(), 0.0, 0.0, np.ones(n))


def build(spec: RobotSpec, eff: Effects | None = None) -> mujoco.MjModel:
    """The MuJoCo model of `spec` with effects `eff` (None: the clean robot)."""
    s = mujoco.MjSpec.from_string(urdf_text(spec))
    s.option.gravity = np.array(spec.gravity)
    s.option.timestep = TIMESTEP
    s.option.integrator = INTEGRATOR
    joints = [j for j in s.joints if j.type != mujoco.mjtJoint.mjJNT_FREE]
    damping = np.array(spec.nominal_damping) if spec.nominal_damping else np.zeros(len(joints))
    for i, j in enumerate(joints):
        # The diagnosis's model has no joint limits: neither does this one
        # (the reference stays inside them).
        j.limited = mujoco.mjtLimited.mjLIMITED_FALSE
        # MuJoCo's damping and stiffness are polynomials (linear term first).
        j.damping = [damping[i], 0.0, 0.0]
        j.frictionloss = 0.0
        j.armature = 0.0
        j.stiffness = [0.0, 0.0, 0.0]
        j.springref = 0.0
        j.solref_friction = [FRICTION_TIMECONST, 1.0]
        if eff is not None:
            j.damping = [damping[i] + eff.damping[i], 0.0, 0.0]
            j.frictionloss = eff.frictionloss[i]
            j.armature = eff.armature[i]
            j.stiffness = [eff.stiffness[i], 0.0, 0.0]
            j.springref = eff.springref[i]
    if eff is not None and eff.payload > 0.0:
        parent = s.body(spec.payload_body)
        body = parent.add_body(name="mujoco_payload", pos=list(spec.payload_pos))
        body.mass = eff.payload
        body.ipos = [0.0, 0.0, 0.0]  # the centre of mass at the body's origin
        body.iquat = [1.0, 0.0, 0.0, 0.0]
        # A compact mass: a 2 cm sphere's inertia.
        i = 0.4 * eff.payload * 0.01**2
        body.inertia = [i, i, i]
        body.explicitinertial = True
    m = s.compile()
    return m


def joint_names(m: mujoco.MjModel) -> list:
    return [m.joint(i).name for i in range(m.njnt)]


def inverse_dynamics(m: mujoco.MjModel, d: mujoco.MjData, q, v, a) -> np.ndarray:
    """MuJoCo's inverse dynamics at (q, v, a): qfrc_inverse (rigid body,
    armature, passive damping and springs; no constraints)."""
    d.qpos[:] = q
    d.qvel[:] = v
    d.qacc[:] = a
    mujoco.mj_inverse(m, d)
    return d.qfrc_inverse.copy()


def mass_matrix(m: mujoco.MjModel, d: mujoco.MjData, q) -> np.ndarray:
    d.qpos[:] = q
    mujoco.mj_forward(m, d)
    full = np.zeros((m.nv, m.nv))
    mujoco.mj_fullM(m, d, full)
    return full


# ------------------------------------------------------------ the reference


@dataclass
class Reference:
    """A smooth multi-sine per joint: home + amplitude * sum_i w_i sin(2 pi f_i t + p_i),
    sum w_i = 1, so it stays within home +- amplitude (inside the joint limits)."""

    home: np.ndarray
    amplitude: np.ndarray
    freq: np.ndarray  # (n, K)
    weight: np.ndarray  # (n, K)
    phase: np.ndarray  # (n, K)

    @staticmethod
    def draw(spec: RobotSpec, rng: np.random.Generator, k: int = 4) -> "Reference":
        n = len(spec.home)
        freq = rng.uniform(0.12, 0.7, size=(n, k))
        weight = rng.uniform(0.5, 1.0, size=(n, k))
        weight /= weight.sum(axis=1, keepdims=True)
        phase = rng.uniform(0, 2 * np.pi, size=(n, k))
        return Reference(np.array(spec.home), np.array(spec.amplitude), freq, weight, phase)

    def at(self, t: np.ndarray):
        """q, qd, qdd at times t (shape (T,)), each (T, n)."""
        w = 2 * np.pi * self.freq  # (n, K)
        arg = w[None] * t[:, None, None] + self.phase[None]
        aw = self.amplitude[:, None] * self.weight  # (n, K)
        q = self.home + (aw[None] * np.sin(arg)).sum(-1)
        qd = (aw[None] * w[None] * np.cos(arg)).sum(-1)
        qdd = -(aw[None] * w[None] ** 2 * np.sin(arg)).sum(-1)
        return q, qd, qdd


# ------------------------------------------------------------ the simulation


@dataclass
class Run:
    """A simulated run on the physics grid (t >= 0 only)."""

    t: np.ndarray  # (S,)
    q: np.ndarray  # (S, n)
    qd: np.ndarray
    tau: np.ndarray  # applied actuator torque at each instant (S, n)
    held: np.ndarray  # the torque the controller holds over the step after each instant


def simulate(spec: RobotSpec, eff: Effects, ref: Reference, duration: float,
             bandwidth: float = 15.0) -> tuple:
    """Run the robot with effects `eff` under a PD + feedforward controller
    that tracks `ref` and knows only the clean robot. Returns the run (from
    -PRE_ROLL) and the index of t = 0."""
    clean = build(spec)
    cd = mujoco.MjData(clean)
    m = build(spec, eff)
    d = mujoco.MjData(m)
    n = m.nv
    steps = int(round((duration + PRE_ROLL) / TIMESTEP))
    t = -PRE_ROLL + TIMESTEP * np.arange(steps + 1)
    qr, qdr, qddr = ref.at(t)
    ff = np.array([inverse_dynamics(clean, cd, qr[k], qdr[k], qddr[k]) for k in range(steps + 1)])
    # PD gains scaled by the clean mass matrix's diagonal at home: closed-loop
    # bandwidth `bandwidth` rad/s on every joint, critically damped.
    mdiag = np.diag(mass_matrix(clean, cd, ref.home)).copy()
    kp = bandwidth**2 * mdiag
    kd = 2 * bandwidth * mdiag
    d.qpos[:] = qr[0]
    d.qvel[:] = qdr[0]
    mujoco.mj_forward(m, d)
    q = np.empty((steps + 1, n))
    qd = np.empty((steps + 1, n))
    u = np.empty((steps + 1, n))
    for k in range(steps + 1):
        q[k] = d.qpos
        qd[k] = d.qvel
        u[k] = ff[k] + kp * (qr[k] - q[k]) + kd * (qdr[k] - qd[k])
        if k == steps:
            break
        d.qfrc_applied[:] = u[k]
        mujoco.mj_step(m, d)
        if not np.all(np.isfinite(d.qpos)):
            raise RuntimeError(f"{spec.name}: the simulation diverged at t = {t[k]:.4f} s")
    # The torque at instant k: the mean of the torques held over the steps
    # before and after it.
    tau = u.copy()
    tau[1:] = 0.5 * (u[:-1] + u[1:])
    start = int(round(PRE_ROLL / TIMESTEP))
    # Keep the pre-roll for the delayed effort (negative times).
    return Run(t, q, qd, tau, u), start


# ---------------------------------------------------------------- the log


@dataclass
class Logging:
    rate: float  # Hz
    jitter: float  # fraction of the period, uniform +-
    repeats: float  # fraction of rows repeating the previous row's values
    noise_q: float = 2e-5  # rad or m, white
    noise_qd: float = 2e-3  # rad/s or m/s, white
    noise_tau: float = 3e-3  # fraction of each joint's peak effort
    encoder_bits: int = 20  # quantisation of q: 2 pi / 2^bits (revolute), 1 um (prismatic)


def sample_instants(duration: float, log: Logging, rng: np.random.Generator) -> np.ndarray:
    """Sample instants on the physics grid: period 1/rate, each interval
    times a factor 1 +- jitter."""
    period = 1.0 / log.rate
    out = [0.0]
    while True:
        step = period * (1.0 + (rng.uniform(-log.jitter, log.jitter) if log.jitter > 0 else 0.0))
        nxt = out[-1] + step
        if nxt > duration + 1e-9:
            break
        out.append(nxt)
    return np.round(np.array(out) / TIMESTEP) * TIMESTEP


def write_log(path: str, names: list, prismatic: list, run: Run, start: int, duration: float,
              eff: Effects, log: Logging, rng: np.random.Generator) -> dict:
    """Sample `run` as a logger would and write the CSV; returns what was done."""
    ts = sample_instants(duration, log, rng)
    idx = start + np.round(ts / TIMESTEP).astype(int)
    q = run.q[idx].copy()
    qd = run.qd[idx].copy()
    # Effort stream late by `delay`: the value logged at t is the torque
    # applied at t - delay (linear interpolation on the physics grid).
    tt = run.t[idx] - eff.delay
    tau = np.stack([np.interp(tt, run.t, run.tau[:, j]) for j in range(run.tau.shape[1])], axis=1)
    tau = tau * eff.scale[None, :]
    n = q.shape[1]
    peak = np.abs(run.tau[start:]).max(axis=0)
    sigma_tau = np.maximum(log.noise_tau * peak, 1e-4)
    q += rng.normal(0, log.noise_q, size=q.shape)
    res = np.where(prismatic, 1e-6, 2 * np.pi / 2**log.encoder_bits)
    q = np.round(q / res) * res
    qd += rng.normal(0, log.noise_qd, size=qd.shape)
    tau += rng.normal(0, 1, size=tau.shape) * sigma_tau[None, :]
    repeated = []
    if log.repeats > 0:
        rows = rng.choice(np.arange(1, len(ts)), size=int(round(log.repeats * (len(ts) - 1))),
                          replace=False)
        for r in np.sort(rows):
            q[r], qd[r], tau[r] = q[r - 1], qd[r - 1], tau[r - 1]
        repeated = np.sort(rows).tolist()
    header = ["t"] + [f"q_{j}" for j in names] + [f"qd_{j}" for j in names] + [f"tau_{j}" for j in names]
    if path.endswith(".gz"):
        # No time stamp in the gzip header: the same case gives the same bytes.
        f = io.TextIOWrapper(gzip.GzipFile(path, "wb", mtime=0), encoding="ascii")
    else:
        f = open(path, "w")
    with f:
        f.write(",".join(header) + "\n")
        for k in range(len(ts)):
            # Digits well below each channel's noise (q to 1e-7 of its value).
            vals = [f"{ts[k]:.6f}"] + [f"{x:.8g}" for x in q[k]] + [f"{x:.6g}" for x in qd[k]] \
                + [f"{x:.6g}" for x in tau[k]]
            f.write(",".join(vals) + "\n")
    return {"rows": len(ts), "repeated_rows": len(repeated), "noise_tau": sigma_tau.tolist()}


# ------------------------------------------- agreement with our inverse dynamics


def random_states(spec: RobotSpec, count: int, rng: np.random.Generator):
    n = len(spec.home)
    home, amp = np.array(spec.home), np.array(spec.amplitude)
    q = home + amp * rng.uniform(-1, 1, size=(count, n))
    v = rng.uniform(-1, 1, size=(count, n)) * np.maximum(amp, 0.3)
    a = rng.uniform(-3, 3, size=(count, n)) * np.maximum(amp, 0.3)
    return q, v, a


def dynamics_eval(binary: str, robot: str, q, v, a, baseline: dict | None = None) -> np.ndarray:
    """Our program's inverse dynamics (`dynamics eval`) at the states."""
    with tempfile.TemporaryDirectory() as tmp:
        states = os.path.join(tmp, "states.json")
        out = os.path.join(tmp, "out.json")
        with open(states, "w") as f:
            json.dump({"states": [{"q": list(map(float, q[k])), "v": list(map(float, v[k])),
                                   "a": list(map(float, a[k]))} for k in range(len(q))]}, f)
        cmd = [binary, "eval", "--robot", robot, "--states", states, "--out", out]
        if baseline is not None:
            path = os.path.join(tmp, "baseline.json")
            with open(path, "w") as f:
                json.dump(baseline, f)
            cmd += ["--baseline", path]
        subprocess.run(cmd, check=True, capture_output=True)
        with open(out) as f:
            return np.array([s["tau"] for s in json.load(f)["states"]])


def idcheck(binary: str, robot: str, count: int = 8, seed: int = 7, eff: Effects | None = None,
            baseline: dict | None = None):
    """Largest relative difference between MuJoCo's qfrc_inverse and our
    program's tau over `count` random states (relative to the largest |tau|
    of the state)."""
    spec = ROBOTS[robot]
    m = build(spec, eff)
    d = mujoco.MjData(m)
    q, v, a = random_states(spec, count, np.random.default_rng(seed))
    ours = dynamics_eval(binary, robot, q, v, a, baseline)
    theirs = np.array([inverse_dynamics(m, d, q[k], v[k], a[k]) for k in range(count)])
    scale = np.maximum(np.abs(ours).max(axis=1, keepdims=True), 1e-9)
    return float((np.abs(ours - theirs) / scale).max()), ours, theirs


# ------------------------------------------------------------------ the cases

EXTRA_KINDS = ("armature", "payload_mass", "joint_spring", "time_delay", "effort_scale")
PAYLOAD_RANGE = {"panda": (0.5, 2.0), "ur5": (0.5, 3.0), "arm3r": (0.5, 2.0), "mar": (2.0, 8.0)}


def scales(spec: RobotSpec, ref: Reference):
    """Peak effort and speed per joint of the clean robot on `ref`, and the
    mass matrix diagonal at home: the yardsticks of the effect sizes."""
    m = build(spec)
    d = mujoco.MjData(m)
    t = np.linspace(0, 8, 400)
    q, qd, qdd = ref.at(t)
    tau = np.array([inverse_dynamics(m, d, q[k], qd[k], qdd[k]) for k in range(len(t))])
    return np.abs(tau).max(axis=0), np.abs(qd).max(axis=0), np.diag(mass_matrix(m, d, ref.home))


def param(name, value):
    return {"name": name, "value": float(value)}


def draw_case(seed: int, robot: str, control: bool, log: Logging):
    """The effects of one case (MuJoCo's parameters and the truth entries)."""
    rng = np.random.default_rng(seed)
    spec = ROBOTS[robot]
    m = build(spec)
    names = joint_names(m)
    n = len(names)
    eff = Effects.none(n)
    truth = []
    train_ref = Reference.draw(spec, np.random.default_rng([seed, 1]))
    peak, speed, mdiag = scales(spec, train_ref)
    if not control:
        for j in range(n):
            fc = rng.uniform(0.03, 0.08) * peak[j]
            fv = rng.uniform(0.02, 0.06) * peak[j] / speed[j]
            eff.frictionloss[j] = fc
            eff.damping[j] = fv
            truth.append({"kind": "coulomb_friction", "joint": names[j], "parameters": [param("fc", fc)]})
            truth.append({"kind": "viscous_friction", "joint": names[j], "parameters": [param("fv", fv)]})
        count = int(rng.integers(1, 4))
        for kind in rng.choice(EXTRA_KINDS, size=count, replace=False):
            j = int(rng.integers(0, n))
            if kind == "armature":
                eff.armature[j] = rng.uniform(0.3, 1.0) * mdiag[j]
                truth.append({"kind": kind, "joint": names[j],
                              "parameters": [param("inertia", eff.armature[j])]})
            elif kind == "payload_mass":
                eff.payload = rng.uniform(*PAYLOAD_RANGE[robot])
                truth.append({"kind": kind, "point": spec.tip,
                              "parameters": [param("mass", eff.payload)],
                              "mujoco_body": spec.payload_body, "mujoco_pos": list(spec.payload_pos)})
            elif kind == "joint_spring":
                k = rng.uniform(0.08, 0.2) * peak[j] / spec.amplitude[j]
                ref = spec.home[j] + rng.uniform(-0.5, 0.5) * spec.amplitude[j]
                eff.stiffness[j], eff.springref[j] = k, ref
                truth.append({"kind": kind, "joint": names[j],
                              "parameters": [param("stiffness", k), param("preload", -k * ref)]})
            elif kind == "time_delay":
                lo = max(3e-3, 1.5 / log.rate)
                eff.delay = rng.uniform(lo, 3 * lo)
                truth.append({"kind": kind, "channel": "effort",
                              "parameters": [param("delay", eff.delay)]})
            elif kind == "effort_scale":
                k = rng.uniform(0.8, 0.9) if rng.uniform() < 0.5 else rng.uniform(1.1, 1.25)
                eff.scale[j] = k
                truth.append({"kind": kind, "joint": names[j], "parameters": [param("scale", k)]})
    return spec, names, eff, truth, train_ref


def plan(count: int, controls: int, seed_base: int):
    """The cases: `controls` effect-free controls (every other one at 100 Hz
    with jittered timestamps, every third with repeated rows), then effect
    mixes (every fourth at 100 Hz jittered, every fifth with repeated rows)."""
    robots = list(ROBOTS)
    out = []
    for i in range(count):
        control = i < controls
        k = i if control else i - controls
        # Robots in turn, shifted by one every round so that each rate and
        # logging condition meets every robot.
        robot = robots[(i + i // len(robots)) % len(robots)]
        if control:
            slow, repeats = k % 2 == 0, 0.04 if k % 3 == 0 else 0.0
        else:
            slow, repeats = k % 4 == 3, 0.03 if k % 5 == 4 else 0.0
        log = Logging(rate=100.0 if slow else 1000.0, jitter=0.3 if slow else 0.0, repeats=repeats)
        out.append((i, seed_base * 100_000 + i, robot, control, log))
    return out


def make_case(out_dir: str, index: int, seed: int, robot: str, control: bool, log: Logging,
              duration: float, gz: bool = False) -> dict:
    """Draw case `index` and write its folder."""
    drawn = draw_case(seed, robot, control, log)
    name = f"{index:03d}-{robot}-{'control' if control else 'mix'}"
    return write_case(out_dir, name, drawn, seed, control, log, duration, gz)


def write_case(out_dir: str, name: str, drawn: tuple, seed: int, control: bool, log: Logging,
               duration: float, gz: bool) -> dict:
    """Simulate the training and held-out runs of a drawn case and write
    train.csv, holdout.csv and truth.json under out_dir/name."""
    spec, names, eff, truth, train_ref = drawn
    case_dir = os.path.join(out_dir, name)
    os.makedirs(case_dir, exist_ok=True)
    m = build(spec)
    prismatic = [m.jnt_type[i] == mujoco.mjtJoint.mjJNT_SLIDE for i in range(m.njnt)]
    logs = {}
    for part, ref in (("train", train_ref),
                      ("holdout", Reference.draw(spec, np.random.default_rng([seed, 2])))):
        run, start = simulate(spec, eff, ref, duration)
        path = os.path.join(case_dir, f"{part}.csv" + (".gz" if gz else ""))
        logs[part] = write_log(path, names, prismatic, run, start, duration, eff, log,
                               np.random.default_rng([seed, 3, len(logs)]))
    info = {
        "case": name,
        "robot": spec.name,
        "control": control,
        "effects": truth,
        "rate": log.rate,
        "jitter": log.jitter,
        "repeats": log.repeats,
        "seed": seed,
        "duration": duration,
        "noise": {"q": log.noise_q, "qd": log.noise_qd, "tau_fraction_of_peak": log.noise_tau,
                  "encoder_bits": log.encoder_bits},
        "logs": logs,
        "simulator": {"mujoco": mujoco.__version__, "timestep": TIMESTEP, "integrator": "RK4",
                      "friction_timeconst": FRICTION_TIMECONST},
    }
    with open(os.path.join(case_dir, "truth.json"), "w") as f:
        json.dump(info, f, indent=1)
    return info


def make_payload_pair(out_dir: str, robot: str, seed: int, log: Logging, duration: float,
                      gz: bool = False) -> tuple:
    """The same robot, friction, references and noise seeds twice: unloaded
    (friction on every joint only) and loaded (the same plus a payload), for
    a calibration on the first and `diagnose --baseline` on the second."""
    spec, names, eff, truth, train_ref = draw_case(seed, robot, False, log)
    n = len(names)
    eff.armature[:] = 0.0
    eff.stiffness[:] = 0.0
    eff.springref[:] = 0.0
    eff.delay = 0.0
    eff.scale = np.ones(n)
    eff.payload = 0.0
    friction = [e for e in truth if e["kind"] in ("coulomb_friction", "viscous_friction")]
    unloaded = write_case(out_dir, f"{robot}-unloaded", (spec, names, eff, friction, train_ref),
                          seed, False, log, duration, gz)
    mass = np.random.default_rng([seed, 4]).uniform(*PAYLOAD_RANGE[robot])
    loaded_eff = Effects(eff.damping, eff.frictionloss, eff.armature, eff.stiffness, eff.springref,
                         mass, 0.0, eff.scale)
    payload = {"kind": "payload_mass", "point": spec.tip, "parameters": [param("mass", mass)],
               "mujoco_body": spec.payload_body, "mujoco_pos": list(spec.payload_pos)}
    loaded = write_case(out_dir, f"{robot}-loaded", (spec, names, loaded_eff, friction + [payload],
                                                     train_ref), seed, False, log, duration, gz)
    return unloaded, loaded


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default="out/mujoco", help="output folder, one sub-folder a case")
    ap.add_argument("--seed-base", type=int, default=0, help="seed base: fresh cases per value")
    ap.add_argument("--cases", type=int, default=44, help="number of cases")
    ap.add_argument("--controls", type=int, default=12, help="how many of them are controls")
    ap.add_argument("--duration", type=float, default=8.0, help="seconds of each of train and holdout")
    ap.add_argument("--gzip", action="store_true", help="write train.csv.gz and holdout.csv.gz")
    ap.add_argument("--only", default="", help="comma-separated case indices to make (default: all)")
    ap.add_argument("--payload-pair", default="", metavar="ROBOT",
                    help="write ROBOT-unloaded and ROBOT-loaded (friction; friction and a payload, "
                         "same references) instead of the cases")
    ap.add_argument("--idcheck", action="store_true",
                    help="compare MuJoCo's inverse dynamics with `dynamics eval` and exit")
    ap.add_argument("--dynamics", default=os.path.join(ROOT, "target", "release", "dynamics"),
                    help="the dynamics program (for --idcheck)")
    a = ap.parse_args(argv)
    if a.idcheck:
        worst = 0.0
        for robot in ROBOTS:
            err, _, _ = idcheck(a.dynamics, robot)
            worst = max(worst, err)
            print(f"{robot:8s} max relative difference {err:.2e}")
        return 0 if worst < 1e-6 else 1
    only = {int(x) for x in a.only.split(",") if x}
    os.makedirs(a.out, exist_ok=True)
    if a.payload_pair:
        pair = make_payload_pair(a.out, a.payload_pair, a.seed_base * 100_000 + 99_999,
                                 Logging(rate=1000.0, jitter=0.0, repeats=0.0), a.duration, a.gzip)
        for info in pair:
            extra = [f"{e['kind']} {e['parameters'][0]['value']:.3f} kg at {e['point']}"
                     for e in info["effects"] if e["kind"] == "payload_mass"]
            print(f"{info['case']:22s} friction on every joint" + "".join(", " + x for x in extra))
        return 0
    for index, seed, robot, control, log in plan(a.cases, a.controls, a.seed_base):
        if only and index not in only:
            continue
        t0 = time.time()
        info = make_case(a.out, index, seed, robot, control, log, a.duration, a.gzip)
        kinds = ", ".join(sorted({e["kind"] for e in info["effects"]})) or "none"
        print(f"{info['case']:22s} {log.rate:6.0f} Hz jitter {log.jitter:.1f} repeats {log.repeats:.2f} "
              f"{kinds}  ({time.time() - t0:.1f} s)", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
