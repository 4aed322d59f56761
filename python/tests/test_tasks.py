"""Robot.simulate and Robot.identify equal the command line's `simulate`
(its trajectory CSV) and `identify --json` on the same inputs."""

import json
import logging

import numpy as np
import pandas as pd
import pytest

import dynamics
from conftest import run_cli

EFFECTS = {"effects": [
    {"kind": "coulomb_friction", "joint": "j2", "parameters": [{"name": "fc", "value": 0.4}]},
    {"kind": "viscous_friction", "joint": "j3", "parameters": [{"name": "fv", "value": 0.2}]},
]}


def read_csv(path):
    """The file's numbers exactly (pandas before 3 parses them exactly only when asked)."""
    if int(pd.__version__.split(".")[0]) < 3:
        return pd.read_csv(path, float_precision="round_trip")
    return pd.read_csv(path)


def cli_simulation(tmp_path, *flags):
    out = tmp_path / "sim"
    run_cli("simulate", "--robot", "arm3r", "--out", out, *flags)
    table = read_csv(out / "arm3r.csv")
    return table


def assert_same_run(run, table, joints):
    assert np.array_equal(run["t"], table["t"].to_numpy())
    for key in ("q", "qd", "qdd", "tau"):
        want = table[[f"{key}_{j}" for j in joints]].to_numpy()
        assert run[key].shape == want.shape
        assert np.array_equal(run[key], want), key


def test_simulate_equals_the_command_line(tmp_path):
    arm = dynamics.Robot("arm3r")
    table = cli_simulation(tmp_path, "--duration", "1.5", "--rate", "200", "--seed", "4")
    run = arm.simulate(duration=1.5, rate=200, seed=4)
    assert_same_run(run, table, arm.joint_names)
    assert run["reference"].shape == (301, 3)
    # Computed torque on the exact model: the robot follows the reference
    # (amplitude 0.4 rad) to within a few milliradians.
    assert np.abs(run["q"] - run["reference"]).max() < 1e-2


def test_simulate_with_effects_and_options_equals_the_command_line(tmp_path):
    arm = dynamics.Robot("arm3r")
    effects = tmp_path / "effects.json"
    effects.write_text(json.dumps(EFFECTS))
    flags = ["--motion", "chirp", "--duration", "1", "--rate", "250", "--bandwidth", "20",
             "--amplitude", "0.2", "--home", "0.1,-0.2,0.3", "--effects", effects]
    table = cli_simulation(tmp_path, *flags)
    kwargs = dict(duration=1, rate=250, bandwidth=20, amplitude=0.2, home=[0.1, -0.2, 0.3])
    assert_same_run(arm.simulate("chirp", effects=effects, **kwargs), table, arm.joint_names)
    # The same effects as a mapping.
    assert_same_run(arm.simulate("chirp", effects=EFFECTS, **kwargs), table, arm.joint_names)
    # The friction the controller does not know makes it track worse.
    clean = arm.simulate("chirp", **kwargs)
    bad = arm.simulate("chirp", effects=EFFECTS, **kwargs)
    assert (np.abs(bad["q"] - bad["reference"]).max()
            > 2 * np.abs(clean["q"] - clean["reference"]).max())


def test_simulate_with_a_baseline_and_a_csv_reference_equals_the_command_line(tmp_path):
    arm = dynamics.Robot("arm3r")
    baseline = tmp_path / "baseline.json"
    baseline.write_text(json.dumps(EFFECTS))
    t = np.arange(0, 0.8, 0.01)
    reference = pd.DataFrame({"t": t, "q_j1": 0.3 * np.sin(3 * t), "q_j2": 0.2 * t,
                              "q_j3": -0.1 * np.cos(2 * t)})
    path = tmp_path / "reference.csv"
    reference.to_csv(path, index=False)
    table = cli_simulation(tmp_path, "--motion", path, "--baseline", baseline, "--rate", "100")
    run = arm.simulate(path, rate=100, baseline=baseline)
    assert_same_run(run, table, arm.joint_names)
    assert run["t"][-1] == pytest.approx(0.79)


def test_simulate_warns_of_the_baseline_effects_it_leaves_out(tmp_path, caplog):
    # An effort scale (a sensor's) and an elastic joint (a motor side) are no
    # part of the model a simulation's controller uses: the run is the one
    # without them, and the warning names them, as the command line's does.
    arm = dynamics.Robot("arm3r")
    apart = {"effects": EFFECTS["effects"] + [
        {"kind": "effort_scale", "joint": "j1", "parameters": [{"name": "scale", "value": 1.2}]},
        {"kind": "joint_elasticity", "joint": "j2", "parameters": [
            {"name": "motor_inertia", "value": 0.01}, {"name": "stiffness", "value": 50.0},
            {"name": "damping", "value": 0.1}]},
    ]}
    kwargs = dict(duration=0.5, rate=100, seed=2)
    with caplog.at_level(logging.WARNING, logger="dynamics"):
        run = arm.simulate(baseline=apart, **kwargs)
    warned = [r.getMessage() for r in caplog.records if r.name == "dynamics"]
    assert len(warned) == 1
    assert "effort_scale" in warned[0] and "joint_elasticity" in warned[0]
    assert "friction" not in warned[0]
    folded = arm.simulate(baseline=EFFECTS, **kwargs)
    for key in ("q", "qd", "tau"):
        assert np.array_equal(run[key], folded[key]), key
    path = tmp_path / "apart.json"
    path.write_text(json.dumps(apart))
    cli = run_cli("simulate", "--robot", "arm3r", "--out", tmp_path / "sim", "--duration", "0.5",
                  "--rate", "100", "--seed", "2", "--baseline", path)
    assert f"warning: {warned[0]}" in cli.stderr


def test_simulate_errors():
    arm = dynamics.Robot("arm3r")
    with pytest.raises(ValueError, match="--rate and --bandwidth must be positive"):
        arm.simulate(rate=0)
    with pytest.raises(ValueError, match="--home: 2 values; the robot has 3 joints"):
        arm.simulate(home=[0.0, 0.0])
    with pytest.raises(ValueError, match="--motion `wobble`"):
        arm.simulate("wobble")
    with pytest.raises(ValueError, match="effects"):
        arm.simulate(duration=0.1, effects={"effects": [{"kind": "coulomb_friction", "joint": "j9",
                                                          "parameters": []}]})
    with pytest.raises(TypeError, match="motion"):
        arm.simulate(3)


@pytest.fixture(scope="module")
def data(tmp_path_factory):
    d = tmp_path_factory.mktemp("identify")
    train, holdout = d / "train.csv", d / "train-holdout.csv"
    run_cli("synth", "--robot", "arm3r", "--effect", "viscous_friction", "--joint", "j3",
            "--magnitude", "0.3", "--seed", "2", "--duration", "3", "--out", train)
    report = d / "identify.json"
    run_cli("identify", "--robot", "arm3r", "--train", train, "--holdout", holdout,
            "--json", report)
    return {"train": train, "holdout": holdout, "json": json.loads(report.read_text())}


def test_identify_equals_the_command_line(data):
    arm = dynamics.Robot("arm3r")
    got = arm.identify(data["train"], str(data["holdout"]))
    assert got == data["json"]
    # The withheld viscous friction on j3 is what it finds.
    j3 = next(j for j in got["joints"] if j["joint"] == "j3")
    assert j3["viscous"]["value"] == pytest.approx(0.3, rel=0.1)


def test_identify_on_dataframes_and_arrays_equals_the_command_line(data):
    arm = dynamics.Robot("arm3r")
    train = read_csv(data["train"])
    holdout = read_csv(data["holdout"])
    assert arm.identify(train, holdout) == data["json"]
    joints = arm.joint_names
    mapping = {"t": holdout["t"].to_numpy(),
               "q": holdout[[f"q_{j}" for j in joints]].to_numpy(),
               "qd": holdout[[f"qd_{j}" for j in joints]].to_numpy(),
               "tau": holdout[[f"tau_{j}" for j in joints]].to_numpy()}
    assert arm.identify(train, mapping) == data["json"]


def test_identify_logs_the_data_warnings(tmp_path, caplog):
    arm = dynamics.Robot("arm3r")
    train, holdout = tmp_path / "a.csv", tmp_path / "a-holdout.csv"
    run_cli("synth", "--robot", "arm3r", "--duration", "3", "--glitches", "3", "--seed", "3",
            "--out", train)
    with caplog.at_level(logging.WARNING, logger="dynamics"):
        arm.identify(train, holdout)
    assert any("glitch" in r.getMessage() for r in caplog.records)


def test_identify_errors(tmp_path):
    arm = dynamics.Robot("arm3r")
    with pytest.raises(ValueError, match="nowhere.csv"):
        arm.identify(tmp_path / "nowhere.csv", tmp_path / "nowhere.csv")
    with pytest.raises(TypeError, match="give a path"):
        arm.identify(3, 4)
