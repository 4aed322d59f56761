"""Every built-in robot against Pinocchio 4.1.0's values (robots/data/pinocchio),
one state at a time and as a batch, at 1e-10 relative: per state the largest
entry error over the largest reference entry of the quantity, as
`dynamics check` measures it (C compared as C v: C is one factorisation of
many)."""

import numpy as np
import pytest

import dynamics
from conftest import REFERENCE, reference

TOL = 1e-10


def rel(ours, theirs):
    ours, theirs = np.asarray(ours, dtype=float), np.asarray(theirs, dtype=float)
    assert ours.shape == theirs.shape
    return np.max(np.abs(ours - theirs)) / max(np.max(np.abs(theirs)), 1e-12)


def quantities(arm, q, v, a):
    """What the reference files hold, from the Python API (one state or a batch)."""
    tau = arm.rnea(q, v, a)
    dtau_dq, dtau_dv = arm.rnea_derivatives(q, v, a)
    ddq_dq, ddq_dv, ddq_dtau = arm.aba_derivatives(q, v, tau)
    C = arm.coriolis_matrix(q, v)
    return {
        "tau": tau,
        "M": arm.mass_matrix(q),
        "g": arm.gravity(q),
        "C v": np.einsum("...ij,...j->...i", C, v),
        "nle": arm.nle(q, v),
        "ddq": arm.aba(q, v, tau),
        "dtau_dq": dtau_dq,
        "dtau_dv": dtau_dv,
        "ddq_dq": ddq_dq,
        "ddq_dv": ddq_dv,
        "kinetic_energy": arm.kinetic_energy(q, v),
        "potential_energy": arm.potential_energy(q),
        "M^-1": ddq_dtau,
    }


def expected(state):
    out = {k: state[k] for k in ["tau", "M", "g", "nle", "ddq", "dtau_dq", "dtau_dv",
                                 "ddq_dq", "ddq_dv", "kinetic_energy", "potential_energy"]}
    out["C v"] = np.asarray(state["C"]) @ np.asarray(state["v"])
    out["M^-1"] = np.linalg.inv(state["M"])
    return out


def states(doc):
    return tuple(np.array([s[k] for s in doc["states"]]) for k in ("q", "v", "a"))


@pytest.mark.parametrize("name", sorted(REFERENCE))
def test_single_states_match_pinocchio(name):
    arm, doc = dynamics.Robot(name), reference(name)
    assert arm.joint_names == doc["joint_names"]
    assert len(doc["states"]) == 20
    for s in doc["states"]:
        ours = quantities(arm, np.array(s["q"]), np.array(s["v"]), np.array(s["a"]))
        for k, theirs in expected(s).items():
            # M^-1 by NumPy's inverse of Pinocchio's M: its round-off grows
            # with M's condition number.
            tol = TOL * max(1.0, np.linalg.cond(s["M"]) * 1e-2) if k == "M^-1" else TOL
            assert rel(ours[k], theirs) <= tol, f"{name}: {k} differs from Pinocchio"


@pytest.mark.parametrize("name", sorted(REFERENCE))
def test_batch_matches_pinocchio_and_equals_single_calls(name):
    arm, doc = dynamics.Robot(name), reference(name)
    q, v, a = states(doc)
    batch = quantities(arm, q, v, a)
    for k, s in enumerate(doc["states"]):
        single = quantities(arm, q[k], v[k], a[k])
        for key, theirs in expected(s).items():
            assert np.array_equal(batch[key][k], single[key]), f"{name}: batch {key}[{k}]"
        assert rel(batch["tau"][k], s["tau"]) <= TOL


@pytest.mark.parametrize("name", ["panda", "ur5", "arm3r"])
def test_threaded_batches_equal_single_calls(name):
    """Batches from PARALLEL_FROM states up run over threads: same numbers."""
    arm, doc = dynamics.Robot(name), reference(name)
    q, v, a = (np.tile(x, (13, 1)) for x in states(doc))  # 260 states
    assert len(q) >= dynamics.PARALLEL_FROM
    tau = arm.rnea(q, v, a)
    M = arm.mass_matrix(q)
    K, D = arm.rnea_derivatives(q, v, a)
    ddq = arm.aba(q, v, tau)
    T = arm.kinetic_energy(q, v)
    for k in range(0, len(q), 7):
        assert np.array_equal(tau[k], arm.rnea(q[k], v[k], a[k]))
        assert np.array_equal(M[k], arm.mass_matrix(q[k]))
        assert np.array_equal(K[k], arm.rnea_derivatives(q[k], v[k], a[k])[0])
        assert np.array_equal(D[k], arm.rnea_derivatives(q[k], v[k], a[k])[1])
        assert np.array_equal(ddq[k], arm.aba(q[k], v[k], tau[k]))
        assert T[k] == arm.kinetic_energy(q[k], v[k])


@pytest.mark.parametrize("name", ["panda", "ur5", "arm3r", "mar"])
def test_regressor_times_inertial_parameters_is_the_rigid_body_rnea(name):
    arm, doc = dynamics.Robot(name), reference(name)
    q, v, a = states(doc)
    Y = arm.regressor(q, v, a)
    pi = arm.inertial_parameters()
    assert Y.shape == (20, arm.nq, 10 * len(arm.link_names))
    assert pi.shape == (10 * len(arm.link_names),)
    for k, s in enumerate(doc["states"]):
        assert rel(Y[k] @ pi, s["tau"]) <= TOL
