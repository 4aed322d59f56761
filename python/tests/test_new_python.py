"""`dynamics new DIR --urdf FILE --python` on a URDF the repository does not
build (a copy of the UR5's, the robot renamed): the package it writes,
installed with pip into a fresh virtual environment, gives `import my_arm`
whose `my_arm.Robot()` has Pinocchio's UR5 values to 1e-10.

SLOW: one release build of the new package (its dependencies shared with
the repository's target directory when built with the same flags)."""

import os
import subprocess
import sys
import textwrap

from conftest import PINOCCHIO, ROOT, run_cli

CHECK = textwrap.dedent(
    """
    import json, sys
    import numpy as np
    import my_arm

    doc = json.load(open(sys.argv[1]))
    arm = my_arm.Robot()
    assert arm.name == "my_arm", arm.name
    assert [n for n, _ in my_arm.robots()] == ["my_arm"]
    assert arm.joint_names == doc["joint_names"], arm.joint_names
    assert arm.upper[0] == 6.28318530718  # the URDF's limit, as written
    q, v, a = (np.array([s[k] for s in doc["states"]]) for k in ("q", "v", "a"))
    def rel(ours, theirs):
        theirs = np.asarray(theirs)
        return np.max(np.abs(ours - theirs)) / max(np.max(np.abs(theirs)), 1e-12)
    tau, M = arm.rnea(q, v, a), arm.mass_matrix(q)
    K, D = arm.rnea_derivatives(q, v, a)
    worst = 0.0
    for k, s in enumerate(doc["states"]):
        worst = max(worst, rel(tau[k], s["tau"]), rel(M[k], s["M"]), rel(K[k], s["dtau_dq"]),
                    rel(D[k], s["dtau_dv"]), rel(arm.aba(q[k], v[k], tau[k]), s["ddq"]))
        assert np.array_equal(tau[k], arm.rnea(q[k], v[k], a[k]))
    assert worst <= 1e-10, worst
    try:
        my_arm.Robot("panda")
    except KeyError as e:
        assert "known robots: my_arm" in str(e), e
    else:
        raise AssertionError("a package of one robot knows no other")
    print("ok", worst)
    """
)


def test_a_package_for_a_users_robot_installs_and_matches_pinocchio(tmp_path):
    urdf = (ROOT / "robots" / "data" / "urdf" / "ur5.urdf").read_text()
    urdf = urdf.replace('<robot name="ur5">', '<robot name="my_arm">')
    (tmp_path / "my_arm.urdf").write_text(urdf)
    package = tmp_path / "my-arm"
    said = run_cli("new", package, "--urdf", tmp_path / "my_arm.urdf", "--python").stdout
    assert "Python module my_arm" in said and "pip install" in said
    lib = (package / "src" / "lib.rs").read_text()
    assert "pub robot MyArm;" in lib and "_dynamics::kernel(MyArm::default())" in lib

    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
    python = venv / "bin" / "python"
    pip = [str(python), "-m", "pip", "install", "--quiet", "--disable-pip-version-check"]
    subprocess.run(pip + ["numpy"], check=True)
    # The repository's target directory and flags: its compiled crates are reused.
    env = dict(os.environ, CARGO_TARGET_DIR=os.environ.get("CARGO_TARGET_DIR", str(ROOT / "target")),
               RUSTFLAGS="-C target-cpu=native")
    build = subprocess.run(pip + [str(package)], env=env, capture_output=True, text=True)
    assert build.returncode == 0, build.stderr[-4000:]
    out = subprocess.run([str(python), "-c", CHECK, str(PINOCCHIO / "ur5.json")],
                         capture_output=True, text=True, cwd=tmp_path)
    assert out.returncode == 0, out.stderr
    assert out.stdout.startswith("ok")
