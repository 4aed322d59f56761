"""ROS 2 bags with `topic=`, Parquet files, the fleet table as Parquet, and
the progress conventions (a callable, a tqdm bar, the logger)."""

import json
import logging
import subprocess
import sys
import types

import pandas as pd
import pytest

import dynamics
from conftest import ROOT, dynamics_bin, run_cli

BAGS = ROOT / "dynamics-sim2real" / "tests" / "data" / "bags"
TRAIN_BAG = BAGS / "arm3r-train"          # rosbag2 directory, MCAP, plus a /chatter topic
HOLDOUT_BAG = BAGS / "arm3r-holdout.db3"  # sqlite3 storage, big-endian CDR


def cli_json(tmp_path, command, *flags):
    out = tmp_path / f"{command}.json"
    run_cli(command, "--robot", "arm3r", *flags, "--json", out)
    return json.loads(out.read_text())


def cli_error(*args):
    out = subprocess.run([str(dynamics_bin()), *map(str, args)], capture_output=True, text=True)
    assert out.returncode != 0
    return out.stderr


def test_diagnose_on_bags_with_a_topic_equals_the_command_line(tmp_path):
    arm = dynamics.Robot("arm3r")
    want = cli_json(tmp_path, "diagnose", "--train", TRAIN_BAG, "--holdout", HOLDOUT_BAG,
                    "--topic", "/joint_states")
    assert arm.diagnose(TRAIN_BAG, HOLDOUT_BAG, topic="/joint_states") == want
    # /joint_states is the default topic.
    assert arm.diagnose(TRAIN_BAG, HOLDOUT_BAG) == want
    # The bags hold the same samples as the CSV beside them: the same diagnosis.
    csv = arm.diagnose(BAGS / "arm3r-train.csv.gz", BAGS / "arm3r-holdout.csv.gz")
    assert csv["which"] == want["which"]


def test_the_topic_is_the_one_read(tmp_path):
    """The training bag's second topic, /chatter, carries strings: asked for it,
    the reader reads it and fails as the command line does."""
    arm = dynamics.Robot("arm3r")
    with pytest.raises(ValueError) as e:
        arm.diagnose(TRAIN_BAG, HOLDOUT_BAG, topic="/chatter")
    assert "/chatter" in str(e.value)
    assert str(e.value) in cli_error("diagnose", "--robot", "arm3r", "--train", TRAIN_BAG,
                                     "--holdout", HOLDOUT_BAG, "--topic", "/chatter")
    with pytest.raises(ValueError, match="/nowhere"):
        arm.diagnose(TRAIN_BAG, HOLDOUT_BAG, topic="/nowhere")
    # A topic for a file that is not a bag, or for data in memory.
    with pytest.raises(ValueError, match="is not a ROS 2 bag"):
        arm.diagnose(BAGS / "arm3r-train.csv.gz", HOLDOUT_BAG, topic="/joint_states")
    with pytest.raises(ValueError, match="data in memory have no topics"):
        arm.diagnose({"t": [0.0], "q": [[0.0] * 3], "tau": [[0.0] * 3]}, HOLDOUT_BAG,
                     topic="/joint_states")


def test_identify_on_bags_with_a_topic_equals_the_command_line(tmp_path, caplog):
    arm = dynamics.Robot("arm3r")
    want = cli_json(tmp_path, "identify", "--train", TRAIN_BAG, "--holdout", HOLDOUT_BAG,
                    "--topic", "/joint_states")
    with caplog.at_level(logging.INFO, logger="dynamics"):
        assert arm.identify(TRAIN_BAG, HOLDOUT_BAG, topic="/joint_states") == want
    # What was read of each bag is logged, as the command line prints it.
    read = [r.getMessage() for r in caplog.records if r.getMessage().startswith("data: ")]
    assert len(read) == 2 and all("/joint_states" in line for line in read)
    with pytest.raises(ValueError, match="/chatter"):
        arm.identify(TRAIN_BAG, HOLDOUT_BAG, topic="/chatter")


@pytest.fixture(scope="module")
def parquet_and_csv(tmp_path_factory):
    """The same synth data written as Parquet and as CSV by the command line."""
    d = tmp_path_factory.mktemp("parquet")
    flags = ["synth", "--robot", "arm3r", "--effect", "coulomb_friction", "--joint", "j1",
             "--magnitude", "0.3", "--seed", "9", "--duration", "3"]
    run_cli(*flags, "--out", d / "x.parquet")
    run_cli(*flags, "--out", d / "x.csv")
    report = d / "report.json"
    run_cli("diagnose", "--robot", "arm3r", "--train", d / "x.csv",
            "--holdout", d / "x-holdout.csv", "--json", report)
    return d, json.loads(report.read_text())


def test_diagnose_on_parquet_equals_the_csv_report(parquet_and_csv):
    d, want = parquet_and_csv
    arm = dynamics.Robot("arm3r")
    got = arm.diagnose(d / "x.parquet", str(d / "x-holdout.parquet"))
    assert got == want
    assert got["which"]["verdict"]["kind"] == "coulomb_friction"


def test_parquet_read_by_pandas_equals_the_file(parquet_and_csv):
    """A DataFrame read with pandas from the Parquet file gives the same report."""
    pytest.importorskip("pyarrow")
    d, want = parquet_and_csv
    arm = dynamics.Robot("arm3r")
    train = pd.read_parquet(d / "x.parquet")
    holdout = pd.read_parquet(d / "x-holdout.parquet")
    assert arm.diagnose(train, holdout) == want


def test_fleet_table_to_parquet_and_back(tmp_path, parquet_and_csv):
    pytest.importorskip("pyarrow")
    from dynamics.fleet import COLUMNS, row, to_parquet

    d, report = parquet_and_csv
    none_report = json.loads(json.dumps(report))
    none_report["which"]["effects"] = []
    rows = [row("arm3r", "a", report), row("arm3r", "b", error="ValueError: broken.csv: line 3"),
            row("arm3r", "c", none_report)]
    table = pd.DataFrame(rows, columns=COLUMNS)
    path = tmp_path / "fleet.parquet"
    to_parquet(table, path)
    back = pd.read_parquet(path)
    assert list(back.columns) == COLUMNS and len(back) == 3
    assert list(back["log"]) == ["a", "b", "c"]
    assert back["error"].iloc[1] == "ValueError: broken.csv: line 3"
    assert dict(back["values"].iloc[0]) == rows[0]["values"] and rows[0]["values"]
    assert list(back["effects"].iloc[0]) == rows[0]["effects"]
    assert list(back["values"].iloc[2]) == [] and list(back["effects"].iloc[2]) == []
    assert back["torque_shrink"].iloc[0] == rows[0]["torque_shrink"]
    assert back["warnings"].iloc[0] == rows[0]["warnings"]


@pytest.fixture(scope="module")
def small(tmp_path_factory):
    d = tmp_path_factory.mktemp("progress")
    data = dynamics.Robot("arm3r").synth(effect="viscous_friction", joint="j2", seed=1,
                                         duration=2.0)
    (d / "a.csv").write_text(data["train"])
    (d / "b.csv").write_text(data["holdout"])
    return d / "a.csv", d / "b.csv"


def test_progress_callable(small):
    calls = []
    dynamics.Robot("arm3r").diagnose(*small, progress=lambda k, n: calls.append((k, n)))
    assert calls and calls[-1][0] == calls[-1][1]
    # Reported from worker threads, delivered in order: never decreasing.
    done = [k for k, _ in calls]
    assert done == sorted(done) and len(set(n for _, n in calls)) == 1


def test_progress_true_without_tqdm_logs(small, monkeypatch, caplog):
    monkeypatch.setitem(sys.modules, "tqdm", None)
    monkeypatch.setitem(sys.modules, "tqdm.auto", None)
    with caplog.at_level(logging.INFO, logger="dynamics"):
        dynamics.Robot("arm3r").diagnose(*small, progress=True)
    lines = [r.getMessage() for r in caplog.records if "candidates fitted" in r.getMessage()]
    assert 1 <= len(lines) <= 11
    total = lines[-1].split(" of ")[1].split()[0]
    assert lines[-1] == f"diagnose: {total} of {total} candidates fitted"


def test_progress_true_with_tqdm_drives_a_bar(small, monkeypatch):
    bars = []

    class Bar:
        def __init__(self, **kwargs):
            self.kwargs, self.total, self.n, self.closed = kwargs, None, 0, False
            bars.append(self)

        def update(self, k):
            self.n += k

        def close(self):
            self.closed = True

    package = types.ModuleType("tqdm")
    auto = types.ModuleType("tqdm.auto")
    auto.tqdm = Bar
    package.auto = auto
    monkeypatch.setitem(sys.modules, "tqdm", package)
    monkeypatch.setitem(sys.modules, "tqdm.auto", auto)
    dynamics.Robot("arm3r").diagnose(*small, progress=True)
    (bar,) = bars
    assert bar.closed and bar.total is not None and bar.n == bar.total
    assert bar.kwargs["desc"] == "diagnose: fitting candidates"


def test_progress_false_or_wrong(small):
    arm = dynamics.Robot("arm3r")
    arm.diagnose(*small, progress=False)
    with pytest.raises(TypeError, match="progress: give True"):
        arm.diagnose(*small, progress="yes")
