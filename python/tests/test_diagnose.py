"""The diagnosis from Python equals the command line's JSON report on the
same data: from the files themselves, from arrays read out of them, from a
pandas DataFrame; and Robot.synth writes what `dynamics synth` writes."""

import json
import logging

import numpy as np
import pandas as pd
import pytest

import dynamics
from conftest import run_cli

SYNTH = dict(effect="coulomb_friction", joint="j2", magnitude=0.3, seed=3, duration=4.0)


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    """`dynamics synth` data of arm3r and `dynamics diagnose --json` on them."""
    d = tmp_path_factory.mktemp("arm3r")
    train, holdout, report = d / "train.csv", d / "train-holdout.csv", d / "report.json"
    run_cli("synth", "--robot", "arm3r", "--effect", SYNTH["effect"], "--joint", SYNTH["joint"],
            "--magnitude", SYNTH["magnitude"], "--seed", SYNTH["seed"],
            "--duration", SYNTH["duration"], "--out", train, "--truth", d / "truth.json")
    run_cli("diagnose", "--robot", "arm3r", "--train", train, "--holdout", holdout,
            "--json", report)
    return {"train": train, "holdout": holdout, "truth": json.loads((d / "truth.json").read_text()),
            "report": json.loads(report.read_text())}


def test_synth_writes_what_the_command_line_writes(files):
    out = dynamics.Robot("arm3r").synth(**SYNTH)
    assert out["train"] == files["train"].read_text()
    assert out["holdout"] == files["holdout"].read_text()
    assert out["truth"] == files["truth"]


def test_on_the_files_it_equals_the_command_line(files):
    report = dynamics.Robot("arm3r").diagnose(files["train"], str(files["holdout"]))
    assert report == files["report"]
    # The withheld effect is found (the data were made with it).
    assert report["which"]["verdict"]["kind"] == "coulomb_friction"
    assert report["which"]["verdict"]["joint"] == "j2"


def read_csv(path):
    """The file's numbers exactly (pandas before 3 parses them exactly only when asked)."""
    if int(pd.__version__.split(".")[0]) < 3:
        return pd.read_csv(path, float_precision="round_trip")
    return pd.read_csv(path)


def arrays(path, joints):
    table = read_csv(path)
    return {
        "t": table["t"].to_numpy(),
        "q": table[[f"q_{j}" for j in joints]].to_numpy(),
        "qd": table[[f"qd_{j}" for j in joints]].to_numpy(),
        "tau": table[[f"tau_{j}" for j in joints]].to_numpy(),
    }


def test_on_arrays_it_equals_the_command_line(files):
    arm = dynamics.Robot("arm3r")
    train = arrays(files["train"], arm.joint_names)
    # Non-contiguous columns of a larger array are read as well.
    hold = arrays(files["holdout"], arm.joint_names)
    wide = np.hstack([hold["q"], hold["tau"]])
    hold["q"], hold["tau"] = wide[:, :3], wide[:, 3:]
    assert not hold["q"].flags.c_contiguous
    done = []
    report = arm.diagnose(train, hold, progress=lambda k, n: done.append((k, n)))
    assert report == files["report"]
    assert done and done[-1][0] == done[-1][1]


def test_on_dataframes_it_equals_the_command_line(files):
    report = dynamics.Robot("arm3r").diagnose(read_csv(files["train"]), read_csv(files["holdout"]))
    assert report == files["report"]


def test_options_are_the_command_line_flags(files, tmp_path):
    out = tmp_path / "r.json"
    run_cli("diagnose", "--robot", "arm3r", "--train", files["train"], "--holdout", files["holdout"],
            "--train-window", "0:3", "--noise-tau", "0.01,0.02,0.01", "--json", out)
    report = dynamics.Robot("arm3r").diagnose(
        files["train"], files["holdout"], train_window=(0, 3), noise_tau=[0.01, 0.02, 0.01])
    assert report == json.loads(out.read_text())


def test_warnings_reach_the_logger(files, caplog):
    arm = dynamics.Robot("arm3r")
    train = arrays(files["train"], arm.joint_names)
    train["tau"][100, 1] = 1e300  # a glitch the reader repairs and reports
    with caplog.at_level(logging.WARNING, logger="dynamics"):
        report = arm.diagnose(train, files["holdout"])
    assert any("glitch" in w.lower() for w in caplog.messages), caplog.messages
    assert report["warnings"]


def test_errors_say_what_is_wrong(files, tmp_path):
    arm = dynamics.Robot("arm3r")
    with pytest.raises(ValueError, match="nowhere.csv"):
        arm.diagnose(tmp_path / "nowhere.csv", files["holdout"])
    data = arrays(files["train"], arm.joint_names)
    del data["tau"]
    with pytest.raises(ValueError, match="train: the mapping has no `tau`"):
        arm.diagnose(data, files["holdout"])
    data = arrays(files["train"], arm.joint_names)
    data["q"] = data["q"][:, :2]
    with pytest.raises(ValueError, match=r"train: q has shape \[\d+, 2\], expected \(\d+, 3\)"):
        arm.diagnose(data, files["holdout"])
    table = read_csv(files["train"]).drop(columns=["q_j3"])
    with pytest.raises(ValueError, match="q_j3"):
        arm.diagnose(table, files["holdout"])
    with pytest.raises(ValueError, match="train_window"):
        arm.diagnose(files["train"], files["holdout"], train_window=(3, 1))
    with pytest.raises(ValueError, match="noise_q and noise_qd need noise_tau"):
        arm.diagnose(files["train"], files["holdout"], noise_q=0.001)
    with pytest.raises(TypeError, match="give a path, a pandas DataFrame"):
        arm.diagnose(42, files["holdout"])
