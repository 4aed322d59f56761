"""`out=` buffers (written in place, returned, every misfit a ValueError
naming it) and `state_space(q, v, tau, dt=None)`: against finite differences
of `aba`, against the command line's `eval` (the same derivatives), and its
zero-order hold against a matrix exponential computed here by a Taylor series."""

import json
import math

import numpy as np
import pytest

import dynamics
from conftest import run_cli

RNG = np.random.default_rng(7)
ARM = dynamics.Robot("panda")
N = ARM.nq
B = 70  # above PARALLEL_FROM: the threaded path writes into `out` too


def states(b=None):
    shape = (N,) if b is None else (b, N)
    return RNG.uniform(-1, 1, shape), RNG.uniform(-1, 1, shape), RNG.uniform(-1, 1, shape)


# name, arguments, number of outputs
ONE = [("rnea", 3), ("mass_matrix", 1), ("gravity", 1), ("nle", 2), ("coriolis_matrix", 2),
       ("aba", 3), ("regressor", 3)]
MANY = [("rnea_derivatives", 3), ("aba_derivatives", 3), ("state_space", 3)]


@pytest.mark.parametrize("b", [None, 1, B])
@pytest.mark.parametrize("name,k", ONE)
def test_out_is_written_in_place_and_returned(name, k, b):
    args = states(b)[:k]
    want = getattr(ARM, name)(*args)
    out = np.full(want.shape, np.nan)
    got = getattr(ARM, name)(*args, out=out)
    assert got is out
    assert np.array_equal(out, want)


@pytest.mark.parametrize("b", [None, B])
@pytest.mark.parametrize("name,k", MANY)
def test_out_tuples_are_written_in_place_and_returned(name, k, b):
    args = states(b)[:k]
    want = getattr(ARM, name)(*args)
    outs = tuple(np.full(w.shape, np.nan) for w in want)
    got = getattr(ARM, name)(*args, out=outs)
    assert len(got) == len(want)
    for g, o, w in zip(got, outs, want):
        assert g is o
        assert np.array_equal(o, w)
    # A list does as well.
    outs = [np.empty(w.shape) for w in want]
    getattr(ARM, name)(*args, out=outs)
    assert all(np.array_equal(o, w) for o, w in zip(outs, want))


def test_out_that_does_not_fit_is_a_value_error_naming_it():
    q, v, a = states()
    cases = [
        (np.empty(N - 1), "out has shape (6,), expected (7,)"),
        (np.empty((1, N)), "out has shape (1, 7), expected (7,)"),
        (np.empty(N, dtype=np.float32), "out has dtype float32, expected float64"),
        (np.empty(N, dtype=np.int64), "out has dtype int64, expected float64"),
        (np.empty((N, 2))[:, 0], "out is not C-contiguous"),
        ([0.0] * N, "out is a list, not a NumPy array"),
    ]
    for out, message in cases:
        with pytest.raises(ValueError, match=message.replace("(", r"\(").replace(")", r"\)")):
            ARM.rnea(q, v, a, out=out)
    frozen = np.empty(N)
    frozen.flags.writeable = False
    with pytest.raises(ValueError, match="out is read-only"):
        ARM.rnea(q, v, a, out=frozen)
    # A Fortran-ordered matrix is not C-contiguous.
    with pytest.raises(ValueError, match="out is not C-contiguous"):
        ARM.mass_matrix(q, out=np.empty((N, N), order="F"))
    # The batch dimension belongs to the shape.
    with pytest.raises(ValueError, match=r"out has shape \(7,\), expected \(3, 7\)"):
        ARM.gravity(np.zeros((3, N)), out=np.empty(N))


def test_out_tuple_that_does_not_fit():
    q, v, a = states()
    with pytest.raises(ValueError, match=r"out: give a tuple of 2 float64 arrays of shapes \(7, 7\), \(7, 7\)"):
        ARM.rnea_derivatives(q, v, a, out=np.empty((N, N)))
    with pytest.raises(ValueError, match="out: give a tuple of 3"):
        ARM.aba_derivatives(q, v, a, out=(np.empty((N, N)), np.empty((N, N))))
    with pytest.raises(ValueError, match=r"out\[1\] has shape \(7, 7\), expected \(14, 7\)"):
        ARM.state_space(q, v, a, out=(np.empty((2 * N, 2 * N)), np.empty((N, N))))


def test_out_sharing_memory_with_an_input_or_output_is_refused():
    q, v, a = states()
    before = a.copy()
    with pytest.raises(ValueError, match="out shares memory with an input or another output"):
        ARM.rnea(q, v, a, out=a)
    # Nothing was written where the call was refused.
    assert np.array_equal(a, before)
    m = np.empty((N, N))
    with pytest.raises(ValueError, match=r"out\[1\] shares memory"):
        ARM.rnea_derivatives(q, v, a, out=(m, m))


def test_out_left_untouched_when_the_input_is_bad():
    out = np.full(N, 5.0)
    with pytest.raises(ValueError, match="is NaN"):
        ARM.gravity(np.full(N, np.nan), out=out)
    assert np.all(out == 5.0)


def test_state_space_blocks_are_the_forward_dynamics_derivatives():
    q, v, tau = states()
    a_c, b_c = ARM.state_space(q, v, tau)
    assert a_c.shape == (2 * N, 2 * N) and b_c.shape == (2 * N, N)
    ddq_dq, ddq_dv, minv = ARM.aba_derivatives(q, v, tau)
    assert np.array_equal(a_c[:N, :N], np.zeros((N, N)))
    assert np.array_equal(a_c[:N, N:], np.eye(N))
    assert np.array_equal(a_c[N:, :N], ddq_dq)
    assert np.array_equal(a_c[N:, N:], ddq_dv)
    assert np.array_equal(b_c[:N], np.zeros((N, N)))
    assert np.array_equal(b_c[N:], minv)


def test_state_space_against_finite_differences_of_aba():
    for name in ("panda", "ur5", "arm3r", "panda-damped"):
        arm = dynamics.Robot(name)
        n = arm.nq
        q, v, tau = (RNG.uniform(-1, 1, n) for _ in range(3))
        a_c, b_c = arm.state_space(q, v, tau)
        x = np.concatenate([q, v])

        def f(x, u):
            return np.concatenate([x[n:], arm.aba(x[:n], x[n:], u)])

        h = 1e-6
        fd_a = np.column_stack([(f(x + h * e, tau) - f(x - h * e, tau)) / (2 * h)
                                for e in np.eye(2 * n)])
        fd_b = np.column_stack([(f(x, tau + h * e) - f(x, tau - h * e)) / (2 * h)
                                for e in np.eye(n)])
        scale_a = np.abs(a_c).max()
        scale_b = np.abs(b_c).max()
        assert np.abs(a_c - fd_a).max() <= 1e-6 * scale_a, name
        assert np.abs(b_c - fd_b).max() <= 1e-6 * scale_b, name


def test_state_space_equals_the_command_lines_eval():
    """`dynamics eval` prints ddq_dq and ddq_dv at tau = rnea(q, v, a) for the
    robot's reference states: the blocks of A_c there (the same Rust code in
    another binary, inlined differently: equal to rounding)."""
    for name in ("panda", "ur5"):
        arm = dynamics.Robot(name)
        n = arm.nq
        doc = json.loads(run_cli("eval", "--robot", name).stdout)
        for s in doc["states"]:
            q, v, a = (np.array(s[k]) for k in ("q", "v", "a"))
            tau = np.array(s["tau"])
            a_c, _ = arm.state_space(q, v, tau)
            for block, key in ((a_c[n:, :n], "ddq_dq"), (a_c[n:, n:], "ddq_dv")):
                want = np.array(s[key])
                assert np.abs(block - want).max() <= 1e-12 * np.abs(want).max(), (name, key)


def expm_taylor(m):
    """exp(m) by scaling and squaring a 30-term Taylor series (an independent
    reference for the runtime's Pade approximant)."""
    s = max(0, int(math.ceil(math.log2(max(np.abs(m).sum(axis=1).max(), 1e-300)))) + 1)
    a = m / 2.0 ** s
    out, term = np.eye(len(m)), np.eye(len(m))
    for k in range(1, 30):
        term = term @ a / k
        out = out + term
    for _ in range(s):
        out = out @ out
    return out


@pytest.mark.parametrize("dt", [1e-3, 1e-2, 0.1])
def test_discrete_state_space_is_the_zero_order_hold(dt):
    q, v, tau = states()
    a_c, b_c = ARM.state_space(q, v, tau)
    a_d, b_d = ARM.state_space(q, v, tau, dt)
    aug = np.zeros((3 * N, 3 * N))
    aug[: 2 * N, : 2 * N] = a_c
    aug[: 2 * N, 2 * N:] = b_c
    e = expm_taylor(aug * dt)
    assert np.abs(a_d - e[: 2 * N, : 2 * N]).max() <= 1e-12 * np.abs(a_d).max()
    assert np.abs(b_d - e[: 2 * N, 2 * N:]).max() <= 1e-12 * np.abs(b_d).max()
    # keyword form, batch == single exactly
    qs, vs, taus = states(B)
    ab, bb = ARM.state_space(qs, vs, taus, dt=dt)
    assert ab.shape == (B, 2 * N, 2 * N) and bb.shape == (B, 2 * N, N)
    for k in (0, 33, B - 1):
        a1, b1 = ARM.state_space(qs[k], vs[k], taus[k], dt=dt)
        assert np.array_equal(ab[k], a1) and np.array_equal(bb[k], b1)


def test_state_space_batch_equals_single_exactly():
    qs, vs, taus = states(B)
    ab, bb = ARM.state_space(qs, vs, taus)
    for k in range(B):
        a1, b1 = ARM.state_space(qs[k], vs[k], taus[k])
        assert np.array_equal(ab[k], a1) and np.array_equal(bb[k], b1)


@pytest.mark.parametrize("dt", [0.0, -0.1, float("nan"), float("inf")])
def test_state_space_step_must_be_positive(dt):
    q, v, tau = states()
    with pytest.raises(ValueError, match="the step must be a finite positive number of seconds"):
        ARM.state_space(q, v, tau, dt)


def test_state_space_too_long_a_step_is_a_value_error():
    q, v, tau = states()
    with pytest.raises(ValueError, match="overflows"):
        ARM.state_space(q, v, tau, 1e200)
