"""Shared helpers: the repository's paths, the Pinocchio reference files and
the `dynamics` command-line program built from this checkout."""

import json
import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
PINOCCHIO = ROOT / "robots" / "data" / "pinocchio"

# Built-in robots whose model is the very one of a shipped Pinocchio file
# (robots/src/builtin.rs, REFERENCE_VALUES), with that file.
REFERENCE = {
    "arm3r": "arm3r.json",
    "rrp-rigid": "rrp.json",
    "mar": "mar.json",
    "ur5": "ur5.json",
    "panda": "panda.json",
    "arm3r-urdf": "arm3r.json",
    "rrp-urdf": "rrp.json",
    "mar-urdf": "mar.json",
}


def reference(name):
    return json.loads((PINOCCHIO / REFERENCE[name]).read_text())


def dynamics_bin():
    """The command-line program: $DYNAMICS_BIN, else target/release/dynamics."""
    path = pathlib.Path(os.environ.get("DYNAMICS_BIN", ROOT / "target" / "release" / "dynamics"))
    if not path.exists():
        pytest.fail(
            f"{path}: no `dynamics` program; build it (cargo build --release -p robots) "
            "or set DYNAMICS_BIN"
        )
    return path


def run_cli(*args):
    """Runs the program; fails the test with its stderr when it fails."""
    out = subprocess.run([str(dynamics_bin()), *map(str, args)], capture_output=True, text=True)
    if out.returncode != 0:
        pytest.fail(f"dynamics {' '.join(map(str, args))}: {out.stderr}")
    return out
