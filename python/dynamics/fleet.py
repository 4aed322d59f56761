"""The diagnosis of many logs on a Dask cluster, gathered into one table.

A fleet of robots writes logs every day; each pair (training log, held-out
log) is one diagnosis. ``diagnose_many`` maps them over a
``distributed.Client`` (a ``LocalCluster`` on one machine, or a real cluster
by its scheduler's address: the same code) and returns a pandas DataFrame
with one row per pair, in the order given. A pair that cannot be diagnosed
(a missing or corrupt file, too few samples, ...) is a row whose ``error``
says why: nothing is lost, nothing stops the others. Write the table with
``to_parquet(table, path)`` (needs pyarrow; the column types fixed, so
``values`` is a Parquet map whatever the rows hold) or ``table.to_csv(path)``.

>>> from distributed import Client, LocalCluster
>>> from dynamics.fleet import diagnose_many
>>> client = Client(LocalCluster(n_workers=2, threads_per_worker=1))  # doctest: +SKIP
>>> table = diagnose_many(client, "panda", [("arm-07/2026-11-26", "a.csv", "b.csv")])  # doctest: +SKIP

Paths are read by the workers: on a real cluster they must name shared
storage; mappings of arrays and DataFrames travel with the task instead.
"""

from typing import Any, Dict, Iterable, List, Optional, Sequence, Tuple, Union

COLUMNS = [
    "robot", "log", "verdict", "place", "status", "effects", "values",
    "torque_shrink", "rms_shrink", "simulation_shrink", "warnings", "error",
]

Pair = Tuple[str, Any, Any]


def _place(entry: Dict[str, Any]) -> Optional[str]:
    return entry.get("joint") or entry.get("point")


def row(robot: str, log: str, report: Optional[Dict[str, Any]] = None,
        error: Optional[str] = None) -> Dict[str, Any]:
    """One row of the table: the report's verdict, effects (``kind@place``), their
    fitted values (``kind@place.name`` -> value), the shrink on held-out data;
    or the error."""
    out: Dict[str, Any] = {c: None for c in COLUMNS}
    out.update(robot=robot, log=log, error=error)
    if report is None:
        return out
    verdict = report["which"]["verdict"]
    effects = report["which"]["effects"]
    out.update(
        verdict=verdict["kind"],
        place=_place(verdict),
        status=verdict["status"],
        effects=[f"{e['kind']}@{_place(e) or ''}" for e in effects],
        values={f"{e['kind']}@{_place(e) or ''}.{p['name']}": p["value"]
                for e in effects for p in e.get("parameters", [])},
        torque_shrink=report["shrink"]["torque_fraction"],
        rms_shrink=report["shrink"]["rms_fraction"],
        simulation_shrink=report["shrink"].get("simulation_fraction"),
        warnings=len(report.get("warnings", [])),
    )
    return out


def diagnose_one(robot: str, log: str, train: Any, holdout: Any,
                 options: Optional[Dict[str, Any]] = None) -> Dict[str, Any]:
    """One pair's row; any failure becomes the row's ``error`` (never raises)."""
    try:
        import dynamics

        report = dynamics.Robot(robot).diagnose(train, holdout, **(options or {}))
        return row(robot, log, report)
    except Exception as e:  # every failure is data here: the row says why
        return row(robot, log, error=f"{type(e).__name__}: {e}")


def diagnose_many(client: Any, robot: Union[str, Sequence[str]], pairs: Iterable[Pair],
                  **options: Any):
    """Diagnoses every ``(log, train, holdout)`` of ``pairs`` on ``client``'s workers.

    ``robot``: one robot's name for all pairs, or one name per pair.
    ``options``: as ``Robot.diagnose`` takes them (the same for every pair).
    Returns a pandas DataFrame with the columns ``COLUMNS``, one row per pair
    in the order of ``pairs``; a task lost with its worker is a row too.
    """
    import pandas as pd

    pairs = list(pairs)
    robots: List[str] = [robot] * len(pairs) if isinstance(robot, str) else list(robot)
    if len(robots) != len(pairs):
        raise ValueError(f"{len(robots)} robot names for {len(pairs)} pairs")
    futures = [
        client.submit(diagnose_one, r, log, train, holdout, options, pure=False)
        for r, (log, train, holdout) in zip(robots, pairs)
    ]
    rows = []
    for r, (log, _, _), f in zip(robots, pairs, futures):
        try:
            rows.append(f.result())
        except Exception as e:  # the worker died or the task could not run
            rows.append(row(r, log, error=f"{type(e).__name__}: {e}"))
    return pd.DataFrame(rows, columns=COLUMNS)


def parquet_schema():
    """The table's Arrow schema: ``effects`` a list of strings, ``values`` a map
    string -> float64 (a dict per row; a struct inferred from dicts would have
    a field per name and none at all when every row's dict is empty, which
    Parquet cannot hold), ``warnings`` int64."""
    import pyarrow as pa

    text = pa.string()
    return pa.schema([
        ("robot", text), ("log", text), ("verdict", text), ("place", text), ("status", text),
        ("effects", pa.list_(text)), ("values", pa.map_(text, pa.float64())),
        ("torque_shrink", pa.float64()), ("rms_shrink", pa.float64()),
        ("simulation_shrink", pa.float64()), ("warnings", pa.int64()), ("error", text),
    ])


def to_parquet(table: Any, path: Any) -> None:
    """Writes a ``diagnose_many`` table to the Parquet file ``path`` (needs pyarrow).

    Read back with ``pandas.read_parquet(path)``: the same rows; ``values``
    comes back as a list of ``(name, value)`` pairs per row (``dict(...)`` of
    it is the row's dict), ``effects`` as an array of strings.
    """
    import pyarrow as pa
    import pyarrow.parquet as pq

    frame = table.copy()
    frame["warnings"] = [None if missing(w) else int(w) for w in frame["warnings"]]
    pq.write_table(pa.Table.from_pandas(frame, schema=parquet_schema(), preserve_index=False),
                   path)


def missing(x: Any) -> bool:
    """Whether a cell is empty (None, or NaN as pandas fills a missing number)."""
    return x is None or (isinstance(x, float) and x != x)
