#!/usr/bin/env python3
"""Writes the rosbag2 and Parquet fixtures of dynamics-sim2real/tests/data/bags/
with writers independent of ours: the `rosbags` package (MCAP and sqlite3
rosbag2 bags, CDR of either endianness), the `mcap` + `mcap-ros2-support`
packages (MCAP with small zstd or lz4 chunks) and `pyarrow` (Parquet).

    pip install rosbags mcap mcap-ros2-support pyarrow
    cargo build --release -p robots
    python3 scripts/make-bag-fixtures.py [--dynamics target/release/dynamics]

The data are our own: `dynamics synth --robot arm3r` (viscous friction on j3,
4 s at 250 Hz), and a few hundred samples of a made-up 3-joint motion. CI reads
the committed outputs and needs none of these packages.
"""

from __future__ import annotations

import argparse
import csv
import gzip
import io
import math
import random
import shutil
import subprocess
import tempfile
from pathlib import Path

import numpy as np
import pyarrow as pa
import pyarrow.parquet as pq
from mcap.writer import CompressionType
from mcap_ros2.writer import Writer as McapRos2Writer
from rosbags.rosbag2 import CompressionFormat, CompressionMode, StoragePlugin, Writer
from rosbags.typesys import Stores, get_typestore

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "dynamics-sim2real" / "tests" / "data" / "bags"
# 2025-11-24 16:00:00 UTC: a recording's clock since the epoch.
EPOCH_NS = 1_764_000_000 * 10**9
JOINTS = ["j1", "j2", "j3"]

TS = get_typestore(Stores.ROS2_HUMBLE)
JOINT_STATE = "sensor_msgs/msg/JointState"
JointState = TS.types[JOINT_STATE]
Header = TS.types["std_msgs/msg/Header"]
Time = TS.types["builtin_interfaces/msg/Time"]
String = TS.types["std_msgs/msg/String"]

JOINT_STATE_DEF = """std_msgs/Header header
string[] name
float64[] position
float64[] velocity
float64[] effort
================================================================================
MSG: std_msgs/Header
builtin_interfaces/Time stamp
string frame_id
================================================================================
MSG: builtin_interfaces/Time
int32 sec
uint32 nanosec
"""


def stamp(ns: int) -> Time:
    return Time(sec=ns // 10**9, nanosec=ns % 10**9)


def joint_state(ns: int, names, q, qd, tau, frame="") -> JointState:
    return JointState(
        header=Header(stamp=stamp(ns), frame_id=frame),
        name=list(names),
        position=np.array(q, dtype=np.float64),
        velocity=np.array(qd, dtype=np.float64),
        effort=np.array(tau, dtype=np.float64),
    )


def cdr(msg, little_endian=True) -> bytes:
    return bytes(TS.serialize_cdr(msg, msg.__msgtype__, little_endian=little_endian))


class Samples:
    """Rows of a 3-joint record: ns since the epoch, q, qd, tau (each a list of 3)."""

    def __init__(self, rows):
        self.rows = rows

    @staticmethod
    def motion(n=300, rate=200.0):
        rows = []
        for k in range(n):
            t = k / rate
            q = [0.4 * math.sin(2 * math.pi * (0.5 + 0.3 * j) * t + j) for j in range(3)]
            qd = [0.4 * 2 * math.pi * (0.5 + 0.3 * j) * math.cos(2 * math.pi * (0.5 + 0.3 * j) * t + j) for j in range(3)]
            tau = [2.0 * q[j] + 0.1 * qd[j] + j for j in range(3)]
            rows.append((EPOCH_NS + round(k * 1e9 / rate), q, qd, tau))
        return Samples(rows)

    @staticmethod
    def from_csv(path: Path):
        """Our CSV (`t,q_*,qd_*,tau_*`), times rounded to whole nanoseconds."""
        rows = []
        with open(path, newline="") as f:
            reader = csv.reader(f)
            header = next(reader)
            col = {name: i for i, name in enumerate(header)}
            for r in reader:
                ns = round(float(r[col["t"]]) * 1e9)
                pick = lambda p: [float(r[col[f"{p}_{j}"]]) for j in JOINTS]
                rows.append((EPOCH_NS + ns, pick("q"), pick("qd"), pick("tau")))
        return Samples(rows)

    def write_csv_gz(self, path: Path):
        """The same samples as our CSV, each time written so that it reads back
        as (ns - epoch) / 1e9, the bag reader's time."""
        text = io.StringIO()
        text.write("t," + ",".join(f"{p}_{j}" for p in ("q", "qd", "tau") for j in JOINTS) + "\n")
        for ns, q, qd, tau in self.rows:
            values = [(ns - EPOCH_NS) / 1e9] + q + qd + tau
            text.write(",".join(repr(float(v)) for v in values) + "\n")
        with gzip.GzipFile(path, "wb", mtime=0) as f:
            f.write(text.getvalue().encode())


def rosbag2(path: Path, samples: Samples, plugin, *, order=None, extra=None, other_topic=True,
            little_endian=True, zero_stamps=False, velocity=True, effort=True,
            joint_type=JOINT_STATE):
    """A rosbag2 directory written by `rosbags`: JointState on /joint_states in
    the joint order `order`, an extra joint, a second topic, ..."""
    if path.exists():
        shutil.rmtree(path)
    names = order or JOINTS
    with Writer(path, version=9, storage_plugin=plugin) as w:
        conn = w.add_connection("/joint_states", joint_type, typestore=TS)
        chatter = w.add_connection("/chatter", "std_msgs/msg/String", typestore=TS) if other_topic else None
        for k, (ns, q, qd, tau) in enumerate(samples.rows):
            idx = [JOINTS.index(n) for n in names]
            pick = lambda v: [v[i] for i in idx]
            msg_names, mq, mqd, mtau = list(names), pick(q), pick(qd), pick(tau)
            if extra:
                msg_names.append(extra)
                mq, mqd, mtau = mq + [0.01], mqd + [0.0], mtau + [0.5]
            received = ns + 250_000  # the message arrived 0.25 ms after its stamp
            if joint_type == JOINT_STATE:
                msg = joint_state(0 if zero_stamps else ns, msg_names, mq,
                                  mqd if velocity else [], mtau if effort else [])
            else:
                msg = String(data=f"not a joint state {k}")
            w.write(conn, received, cdr(msg, little_endian))
            if chatter is not None and k % 10 == 0:
                w.write(chatter, received + 1, cdr(String(data=f"tick {k}"), little_endian))


def rosbag2_compressed(path: Path, samples: Samples):
    """A rosbag2 directory whose MCAP chunks rosbags compresses with zstd."""
    if path.exists():
        shutil.rmtree(path)
    w = Writer(path, version=9, storage_plugin=StoragePlugin.MCAP)
    w.set_compression(CompressionMode.STORAGE, CompressionFormat.ZSTD)
    with w:
        conn = w.add_connection("/joint_states", JOINT_STATE, typestore=TS)
        for ns, q, qd, tau in samples.rows:
            w.write(conn, ns, cdr(joint_state(ns, JOINTS, q, qd, tau)))


def mcap_chunked(path: Path, samples: Samples, compression, chunk_size=4096, partial=False):
    """One .mcap file written by `mcap-ros2-support` with small chunks (several
    per file). `partial`: two publishers on /joint_states, one with j1 and j3,
    the other with j2, sharing stamps."""
    with open(path, "wb") as f:
        w = McapRos2Writer(f, chunk_size=chunk_size, compression=compression)
        schema = w.register_msgdef(JOINT_STATE, JOINT_STATE_DEF)
        for ns, q, qd, tau in samples.rows:
            msg = lambda names: {
                "header": {"stamp": {"sec": ns // 10**9, "nanosec": ns % 10**9}, "frame_id": ""},
                "name": names,
                "position": [q[JOINTS.index(n)] for n in names],
                "velocity": [qd[JOINTS.index(n)] for n in names],
                "effort": [tau[JOINTS.index(n)] for n in names],
            }
            if partial:
                w.write_message("/joint_states", schema, msg(["j3", "j1"]), log_time=ns, publish_time=ns)
                w.write_message("/joint_states", schema, msg(["j2"]), log_time=ns + 1000, publish_time=ns)
            else:
                w.write_message("/joint_states", schema, msg(["j2", "j3", "j1"]), log_time=ns, publish_time=ns)
        w.finish()


def parquet(path: Path, samples: Samples):
    cols = {"t": [(ns - EPOCH_NS) / 1e9 for ns, *_ in samples.rows]}
    for p, i in (("q", 1), ("qd", 2), ("tau", 3)):
        for j, name in enumerate(JOINTS):
            cols[f"{p}_{name}"] = [row[i][j] for row in samples.rows]
    # An extra column, and the joints' columns in another order than ours.
    cols["temperature_j1"] = [30.0] * len(samples.rows)
    table = pa.table(dict(sorted(cols.items(), key=lambda kv: kv[0][::-1])))
    pq.write_table(table, path, compression="snappy", row_group_size=128)


def flatten(bag: Path, name: str):
    """The one storage file of a rosbag2 directory, moved to OUT/name."""
    (storage,) = [p for p in bag.iterdir() if p.suffix in (".mcap", ".db3")]
    shutil.move(storage, OUT / name)
    shutil.rmtree(bag)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--dynamics", default=str(ROOT / "target" / "release" / "dynamics"))
    args = parser.parse_args()
    OUT.mkdir(parents=True, exist_ok=True)

    # The diagnosis of a bag equals that of the same data as CSV: synth data
    # as CSV (times on whole nanoseconds) and as bags.
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "synth.csv"
        subprocess.run([args.dynamics, "synth", "--robot", "arm3r", "--effect", "viscous_friction",
                        "--joint", "j3", "--magnitude", "0.3", "--duration", "4", "--rate", "250",
                        "--seed", "5", "--out", str(out)], check=True)
        train = Samples.from_csv(out)
        holdout = Samples.from_csv(out.with_name("synth-holdout.csv"))
    train.write_csv_gz(OUT / "arm3r-train.csv.gz")
    holdout.write_csv_gz(OUT / "arm3r-holdout.csv.gz")
    # Training data: a rosbag2 directory with MCAP storage, joints shuffled, a
    # gripper joint the robot does not have, a second topic.
    rosbag2(OUT / "arm3r-train", train, StoragePlugin.MCAP, order=["j3", "j1", "j2"], extra="gripper")
    # Held-out data: an sqlite3 bag, joints in another order, CDR big-endian.
    rosbag2(Path(tmp_dir := tempfile.mkdtemp()) / "b", holdout, StoragePlugin.SQLITE3,
            order=["j2", "j1", "j3"], little_endian=False)
    flatten(Path(tmp_dir) / "b", "arm3r-holdout.db3")

    small = Samples.motion()
    small.write_csv_gz(OUT / "motion.csv.gz")
    tmp = Path(tempfile.mkdtemp())
    cases = {
        "motion-zstd.mcap": None,  # mcap_chunked below
        "motion-zero-stamps.db3": dict(plugin=StoragePlugin.SQLITE3, zero_stamps=True),
        "motion-no-velocity.mcap": dict(plugin=StoragePlugin.MCAP, velocity=False),
        "motion-no-effort.db3": dict(plugin=StoragePlugin.SQLITE3, effort=False),
        "motion-missing-joint.mcap": dict(plugin=StoragePlugin.MCAP, order=["j1", "j2"]),
        "motion-wrong-type.mcap": dict(plugin=StoragePlugin.MCAP, joint_type="std_msgs/msg/String"),
        "motion-wrong-type.db3": dict(plugin=StoragePlugin.SQLITE3, joint_type="std_msgs/msg/String"),
    }
    for name, kw in cases.items():
        if kw is None:
            continue
        plugin = kw.pop("plugin")
        rosbag2(tmp / name, small, plugin, **kw)
        flatten(tmp / name, name)
    rosbag2_compressed(tmp / "c", small)
    flatten(tmp / "c", "motion-rosbags-zstd.mcap")
    mcap_chunked(OUT / "motion-zstd.mcap", small, CompressionType.ZSTD)
    mcap_chunked(OUT / "motion-lz4.mcap", small, CompressionType.LZ4)
    mcap_chunked(OUT / "motion-partial.mcap", small, CompressionType.ZSTD, partial=True)
    # Cut in the middle of a chunk: the chunks before it whole (about 80 % of
    # the messages), then half of one.
    data = (OUT / "motion-zstd.mcap").read_bytes()
    chunks, at = [], 8
    while at + 9 <= len(data) and data[at:] != b"\x89MCAP0\r\n":
        op, length = data[at], int.from_bytes(data[at + 1 : at + 9], "little")
        if op == 0x06:
            chunks.append((at, 9 + length))
        at += 9 + length
    start, length = chunks[len(chunks) * 4 // 5]
    (OUT / "motion-cut.mcap").write_bytes(data[: start + length // 2])
    print(f"motion-cut.mcap: cut at byte {start + length // 2}, inside the chunk at byte {start} "
          f"({len(chunks)} chunks)")
    parquet(OUT / "motion.parquet", small)
    shutil.rmtree(tmp)
    for p in sorted(OUT.rglob("*")):
        if p.is_file():
            print(f"{p.relative_to(ROOT)}: {p.stat().st_size} bytes")


if __name__ == "__main__":
    main()
