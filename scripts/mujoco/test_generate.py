"""MuJoCo's inverse dynamics of the imported URDFs against our `dynamics eval`.

Needs `mujoco` and `numpy` (scripts/mujoco/requirements.txt) and a built
`dynamics` program (DYNAMICS, default target/release/dynamics):

    pip install -r scripts/mujoco/requirements.txt pytest
    cargo build --release -p dynamics-cli
    python -m pytest scripts/mujoco/test_generate.py

The first test is the independent check that the import keeps every inertial
exactly (no rebalancing, no inertia inferred from geometry, gravity as our
models have it). The others check the mapping of MuJoCo's parameters to the
effect kinds of the diagnosis: MuJoCo with damping, armature or a payload body
against `dynamics eval --baseline` with the truth entries generate.py writes.
"""

import json
import os
import shutil

import numpy as np
import pytest

mujoco = pytest.importorskip("mujoco")

import generate as g  # noqa: E402

BINARY = os.environ.get("DYNAMICS", os.path.join(g.ROOT, "target", "release", "dynamics"))
if not (os.path.exists(BINARY) or shutil.which(BINARY)):
    pytest.skip(f"no dynamics program at {BINARY} (set DYNAMICS)", allow_module_level=True)

TOL = 1e-6


@pytest.mark.parametrize("robot", list(g.ROBOTS))
def test_inverse_dynamics_agrees_without_effects(robot):
    err, ours, theirs = g.idcheck(BINARY, robot, count=8, seed=11)
    assert err < TOL, f"{robot}: relative difference {err:.2e}\nours {ours}\nmujoco {theirs}"
    # The states are not trivial: gravity, inertia and velocity terms act.
    assert np.abs(ours).max() > 1e-2


def effects_of(robot, **kw):
    n = len(g.ROBOTS[robot].home)
    eff = g.Effects.none(n)
    for key, value in kw.items():
        setattr(eff, key, value)
    return eff


@pytest.mark.parametrize("robot", ["panda", "arm3r", "mar"])
def test_damping_and_armature_are_viscous_friction_and_armature(robot):
    spec = g.ROBOTS[robot]
    names = g.joint_names(g.build(spec))
    n = len(names)
    damping = np.linspace(0.2, 0.9, n)
    armature = np.linspace(0.05, 0.4, n)
    eff = effects_of(robot, damping=damping, armature=armature)
    baseline = {"effects": [
        {"kind": "viscous_friction", "joint": names[j], "parameters": [g.param("fv", damping[j])]}
        for j in range(n)] + [
        {"kind": "armature", "joint": names[j], "parameters": [g.param("inertia", armature[j])]}
        for j in range(n)]}
    err, ours, theirs = g.idcheck(BINARY, robot, count=6, seed=12, eff=eff, baseline=baseline)
    assert err < TOL, f"{robot}: relative difference {err:.2e}"


@pytest.mark.parametrize("robot", ["panda", "arm3r", "mar"])
def test_payload_body_is_payload_mass_at_the_tip(robot):
    mass = 1.3
    eff = effects_of(robot, payload=mass)
    baseline = {"effects": [{"kind": "payload_mass", "point": g.ROBOTS[robot].tip,
                             "parameters": [g.param("mass", mass)]}]}
    # The payload body has a 2 cm sphere's inertia; our payload is a point.
    err, ours, theirs = g.idcheck(BINARY, robot, count=6, seed=13, eff=eff, baseline=baseline)
    assert err < 1e-3, f"{robot}: relative difference {err:.2e}"
    err0, _, _ = g.idcheck(BINARY, robot, count=6, seed=13, eff=eff)
    assert err0 > 100 * err, "the payload must be visible in the efforts"


def test_spring_preload_convention():
    # MuJoCo's spring: -k (q - springref); the report's joint_spring:
    # -(stiffness q + preload), so preload = -k springref.
    spec = g.ROBOTS["arm3r"]
    k, ref = np.array([3.0, 0.0, 5.0]), np.array([0.4, 0.0, -0.2])
    m = g.build(spec, effects_of("arm3r", stiffness=k, springref=ref))
    d = mujoco.MjData(m)
    q = np.array([0.1, 0.5, -0.6])
    d.qpos[:] = q
    mujoco.mj_forward(m, d)
    preload = -k * ref
    assert np.allclose(d.qfrc_passive, -(k * q + preload), atol=1e-12)


def test_case_files_are_what_diagnose_reads(tmp_path):
    info = g.make_case(str(tmp_path), 0, 123, "arm3r", False,
                       g.Logging(rate=100.0, jitter=0.3, repeats=0.05), duration=1.0)
    case = tmp_path / info["case"]
    header = (case / "train.csv").read_text().splitlines()[0].split(",")
    assert header == ["t"] + [f"{p}_{j}" for p in ("q", "qd", "tau") for j in ("j1", "j2", "j3")]
    rows = np.loadtxt(case / "train.csv", delimiter=",", skiprows=1)
    dt = np.diff(rows[:, 0])
    assert dt.min() >= 0.007 - 1e-9 and dt.max() <= 0.013 + 1e-9 and dt.std() > 5e-4
    same = np.all(rows[1:, 1:] == rows[:-1, 1:], axis=1)
    assert same.sum() == info["logs"]["train"]["repeated_rows"] > 0
    truth = json.loads((case / "truth.json").read_text())
    kinds = {e["kind"] for e in truth["effects"]}
    assert {"coulomb_friction", "viscous_friction"} <= kinds and len(kinds) >= 3


@pytest.mark.parametrize("robot", ["panda", "mar"])
def test_logged_effort_is_the_torque_at_the_sample_instant(robot):
    # On the physics grid of a clean run: the effort generate.py logs at t
    # against MuJoCo's inverse dynamics at t (acceleration by a central
    # difference of the velocity). Read at the instant, the two agree to the
    # difference's error; the effort held over the step after t (or before
    # it) is off by half a step's change and fits worse.
    spec = g.ROBOTS[robot]
    ref = g.Reference.draw(spec, np.random.default_rng(5))
    n = len(spec.home)
    run, start = g.simulate(spec, g.Effects.none(n), ref, duration=1.0)
    m = g.build(spec)
    d = mujoco.MjData(m)
    h = g.TIMESTEP
    ks = np.arange(start + 10, len(run.t) - 10, 7)
    qdd = (run.qd[ks + 1] - run.qd[ks - 1]) / (2 * h)
    ideal = np.array([g.inverse_dynamics(m, d, run.q[k], run.qd[k], a) for k, a in zip(ks, qdd)])
    centred = np.abs(run.tau[ks] - ideal).max()
    held_after = np.abs(run.held[ks] - ideal).max()
    held_before = np.abs(run.held[ks - 1] - ideal).max()
    scale = np.abs(ideal).max()
    assert centred < 1e-4 * scale, f"{robot}: {centred:.2e} of {scale:.2e}"
    assert min(held_after, held_before) > 3 * centred, (centred, held_after, held_before)


def test_the_pair_score_asks_for_the_payload_alone_within_ten_percent():
    import pair

    def report(effects, shrink):
        return {"which": {"effects": effects}, "shrink": {"fraction": shrink}}

    def payload(mass):
        return {"kind": "payload_mass", "point": "tip", "parameters": [{"name": "mass", "value": mass}]}

    stribeck = {"kind": "stribeck_friction", "joint": "j3", "parameters": []}
    calibration = report([{"kind": "coulomb_friction", "joint": "j1"}, stribeck], 0.5)
    ok = pair.score(1.0, calibration, report([payload(1.09)], 0.9))
    assert ok["pass"] and ok["calibration"] == ["stribeck_friction@j3"] and ok["named"] == ["payload_mass@tip"]
    assert not pair.score(1.0, calibration, report([payload(1.11)], 0.9))["pass"]
    assert not pair.score(1.0, calibration, report([payload(1.0), stribeck], 0.9))["pass"]
    assert not pair.score(1.0, calibration, report([payload(1.0)], 0.8))["pass"]
    assert not pair.score(1.0, calibration, report([], 0.9))["pass"]
    assert not pair.score(1.0, None, None)["pass"]
