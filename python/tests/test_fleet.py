"""dynamics.fleet: 50 generated log pairs through a LocalCluster of two
workers; the table has 50 rows in order, each equal to the diagnosis made
here in the test process, and a corrupt file is one row with its error."""

import pytest

import dynamics
from dynamics.fleet import COLUMNS, diagnose_many, row, to_parquet

distributed = pytest.importorskip("distributed")

PAIRS = 50


def missing(x):
    return x is None or (isinstance(x, float) and x != x)
EFFECTS = ["coulomb_friction", "viscous_friction", "armature", "none"]


@pytest.fixture(scope="module")
def logs(tmp_path_factory):
    d = tmp_path_factory.mktemp("fleet")
    arm = dynamics.Robot("arm3r")
    pairs = []
    for k in range(PAIRS):
        data = arm.synth(effect=EFFECTS[k % len(EFFECTS)], joint="j2", seed=k, duration=1.5)
        train, holdout = d / f"log{k:02d}.csv", d / f"log{k:02d}-holdout.csv"
        train.write_text(data["train"])
        holdout.write_text(data["holdout"])
        pairs.append((f"arm{k % 5}/day{k:02d}", str(train), str(holdout)))
    # One corrupt file: the recorder stopped in the middle of a line.
    text = (d / "log17.csv").read_text()
    (d / "log17.csv").write_text(text[: len(text) // 2] + "\n0.75,0.1,oops\n")
    return pairs


def test_fifty_pairs_on_a_local_cluster_of_two_workers(logs, tmp_path):
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            table = diagnose_many(client, "arm3r", logs)
    assert list(table.columns) == COLUMNS
    assert len(table) == PAIRS
    assert list(table["log"]) == [log for log, _, _ in logs]
    failed = table[table["error"].notna()]
    assert list(failed["log"]) == ["arm2/day17"]
    assert failed["error"].iloc[0].startswith("ValueError: ")
    assert "log17.csv" in failed["error"].iloc[0]
    # Each row is the diagnosis made here, in this process.
    arm = dynamics.Robot("arm3r")
    for k in (0, 1, 2, 3, 49):
        log, train, holdout = logs[k]
        want = row("arm3r", log, arm.diagnose(train, holdout))
        got = table.iloc[k].to_dict()
        assert set(got) == set(want)
        for c in COLUMNS:
            assert got[c] == want[c] or (missing(got[c]) and missing(want[c])), (log, c)
    # The withheld friction is what the table names where there was one.
    found = table[table["log"] == "arm0/day00"].iloc[0]
    assert (found["verdict"], found["place"]) == ("coulomb_friction", "j2")
    # The table as Parquet (pyarrow), read back: the same 50 rows, the error kept.
    pytest.importorskip("pyarrow")
    import pandas as pd

    to_parquet(table, tmp_path / "fleet.parquet")
    back = pd.read_parquet(tmp_path / "fleet.parquet")
    assert len(back) == PAIRS and list(back["log"]) == list(table["log"])
    assert list(back["error"].notna()) == list(table["error"].notna())
    assert back["error"].iloc[17] == table["error"].iloc[17]
    assert list(back["verdict"].fillna("-")) == list(table["verdict"].fillna("-"))
