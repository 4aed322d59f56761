"""The package's surface: names, parameters, limits (against the URDF read
here with ElementTree), shapes of every result, and the errors."""

import xml.etree.ElementTree as ET

import numpy as np
import pytest

import dynamics
from conftest import ROOT

SHIPPED = ["arm3r", "rrp", "rrp-rigid", "mar", "mar-drives", "ur5", "panda", "panda-damped",
           "panda-arm", "arm3r-urdf", "rrp-urdf", "mar-urdf"]


def test_robots_lists_the_built_in_robots_with_a_line_each():
    names = [n for n, _ in dynamics.robots()]
    assert names == SHIPPED
    assert all(line for _, line in dynamics.robots())
    for name in names:
        arm = dynamics.Robot(name)
        assert arm.name == name and arm.nq == len(arm.joint_names)


def test_unknown_robot_is_a_key_error_listing_the_known_ones():
    with pytest.raises(KeyError, match="unknown robot `r2d2`; known robots: arm3r, rrp"):
        dynamics.Robot("r2d2")


def urdf_limits(path, joints):
    root = ET.parse(path).getroot()
    limit = {j.get("name"): j.find("limit") for j in root.iter("joint")}
    return {k: np.array([float(limit[j].get(k)) for j in joints])
            for k in ("lower", "upper", "velocity", "effort")}


@pytest.mark.parametrize("name,urdf", [("panda", "panda.urdf"), ("ur5", "ur5.urdf")])
def test_limits_are_the_urdf_ones(name, urdf):
    arm = dynamics.Robot(name)
    want = urdf_limits(ROOT / "robots" / "data" / "urdf" / urdf, arm.joint_names)
    assert np.array_equal(arm.lower, want["lower"])
    assert np.array_equal(arm.upper, want["upper"])
    assert np.array_equal(arm.velocity_limit, want["velocity"])
    assert np.array_equal(arm.effort_limit, want["effort"])


def test_a_robot_without_a_urdf_has_no_limits():
    arm = dynamics.Robot("arm3r")
    assert np.all(arm.lower == -np.inf) and np.all(arm.upper == np.inf)
    assert np.all(arm.velocity_limit == np.inf) and np.all(arm.effort_limit == np.inf)


def test_params_and_set():
    arm = dynamics.Robot("panda-damped")
    assert arm.params["damping_panda_joint1"] == 0.003
    rigid = dynamics.Robot("panda")
    q, v = np.full(7, 0.2), np.linspace(-1.0, 1.0, 7)
    z = np.zeros(7)
    # Joint damping b adds b v to the efforts.
    assert np.allclose(arm.rnea(q, v, z) - rigid.rnea(q, v, z), 0.003 * v, rtol=0, atol=1e-12)
    for j in range(1, 8):
        arm.set(f"damping_panda_joint{j}", 0.5)
    assert arm.params["damping_panda_joint3"] == 0.5
    assert np.allclose(arm.rnea(q, v, z) - rigid.rnea(q, v, z), 0.5 * v, rtol=0, atol=1e-12)
    # A copy keeps its own parameters.
    other = arm.copy()
    other.set("damping_panda_joint1", 0.0)
    assert arm.params["damping_panda_joint1"] == 0.5


def test_set_errors():
    arm = dynamics.Robot("arm3r")
    with pytest.raises(KeyError, match="unknown parameter `mass`; arm3r has: m, b1, b2, b3"):
        arm.set("mass", 1.0)
    with pytest.raises(ValueError, match="m = NaN: a parameter must be finite"):
        arm.set("m", float("nan"))


def test_shapes_of_one_state_and_of_a_batch():
    arm = dynamics.Robot("panda")
    n, L = 7, len(arm.link_names)
    one, batch = np.full(n, 0.1), np.full((5, n), 0.1)
    for x, pre in ((one, ()), (batch, (5,))):
        assert arm.rnea(x, x, x).shape == pre + (n,)
        assert arm.mass_matrix(x).shape == pre + (n, n)
        assert arm.gravity(x).shape == pre + (n,)
        assert arm.nle(x, x).shape == pre + (n,)
        assert arm.coriolis_matrix(x, x).shape == pre + (n, n)
        assert arm.aba(x, x, x).shape == pre + (n,)
        assert [d.shape for d in arm.rnea_derivatives(x, x, x)] == [pre + (n, n)] * 2
        assert [d.shape for d in arm.aba_derivatives(x, x, x)] == [pre + (n, n)] * 3
        assert arm.regressor(x, x, x).shape == pre + (n, 10 * L)
        assert arm.frame_pose(arm.frame_names[-1], x).shape == pre + (4, 4)
        assert all(r.dtype == np.float64 for r in (arm.rnea(x, x, x), arm.mass_matrix(x)))
    assert isinstance(arm.kinetic_energy(one, one), float)
    assert isinstance(arm.potential_energy(one), float)
    assert arm.kinetic_energy(batch, batch).shape == (5,)
    assert arm.potential_energy(batch).shape == (5,)
    assert arm.rnea(np.zeros((0, n)), np.zeros((0, n)), np.zeros((0, n))).shape == (0, n)


def test_kinetic_energy_is_half_v_m_v():
    arm = dynamics.Robot("ur5")
    q, v = np.linspace(-1, 1, 6), np.linspace(0.5, -0.3, 6)
    assert np.isclose(arm.kinetic_energy(q, v), 0.5 * v @ arm.mass_matrix(q) @ v, rtol=1e-13)


def test_frame_pose_is_a_rigid_transform():
    arm = dynamics.Robot("panda")
    T = arm.frame_pose(arm.frame_names[-1], np.full(7, 0.3))
    assert np.array_equal(T[3], [0, 0, 0, 1])
    assert np.allclose(T[:3, :3] @ T[:3, :3].T, np.eye(3), atol=1e-14)
    with pytest.raises(KeyError, match="unknown frame `hand`; panda has: "):
        arm.frame_pose("hand", np.zeros(7))


def test_non_contiguous_lists_and_integers_are_read_as_float64():
    arm = dynamics.Robot("panda")
    rng = np.random.default_rng(1)
    big = rng.uniform(-1, 1, (40, 14))
    q = big[::2, ::2]  # strided both ways
    v = np.asfortranarray(big[::2, 1::2])
    a = big[1::2, :7].T.copy().T  # Fortran order
    assert not (q.flags.c_contiguous or v.flags.c_contiguous or a.flags.c_contiguous)
    want = arm.rnea(np.ascontiguousarray(q), np.ascontiguousarray(v), np.ascontiguousarray(a))
    assert np.array_equal(arm.rnea(q, v, a), want)
    assert np.array_equal(arm.mass_matrix(q), arm.mass_matrix(np.ascontiguousarray(q)))
    assert np.array_equal(arm.rnea(list(q[0]), tuple(v[0]), a[0]), want[0])
    assert np.array_equal(arm.gravity([0, 0, 0, -1, 0, 1, 0]),
                          arm.gravity(np.array([0.0, 0, 0, -1, 0, 1, 0])))
    assert np.array_equal(arm.gravity(q.astype(np.float32)),
                          arm.gravity(q.astype(np.float32).astype(np.float64)))


def test_shape_errors_name_the_argument():
    arm = dynamics.Robot("panda")
    z = np.zeros(7)
    with pytest.raises(ValueError, match=r"q has shape \(6,\), expected \(7,\) \(this robot has 7 joints"):
        arm.mass_matrix(np.zeros(6))
    with pytest.raises(ValueError, match=r"v has shape \(3, 7\), expected \(7,\).*got q \(7,\), v \(3, 7\), a \(7,\)"):
        arm.rnea(z, np.zeros((3, 7)), z)
    with pytest.raises(ValueError, match=r"a has shape \(4, 7\), expected \(3, 7\)"):
        arm.rnea(np.zeros((3, 7)), np.zeros((3, 7)), np.zeros((4, 7)))
    with pytest.raises(ValueError, match=r"q has shape \(2, 3, 7\): give one state as \(7,\) or a batch as \(B, 7\)"):
        arm.gravity(np.zeros((2, 3, 7)))
    with pytest.raises(ValueError, match=r"q has shape \(\): give one state"):
        arm.gravity(1.0)
    with pytest.raises(ValueError, match="q: not an array of numbers"):
        arm.gravity(["a"] * 7)


def test_non_finite_inputs_are_value_errors_naming_the_entry():
    arm = dynamics.Robot("panda")
    z = np.zeros(7)
    q = z.copy()
    q[2] = np.nan
    with pytest.raises(ValueError, match=r"^q\[2\] is NaN: inputs must be finite$"):
        arm.rnea(q, z, z)
    qs = np.zeros((4, 7))
    qs[3, 5] = np.inf
    with pytest.raises(ValueError, match=r"^v\[3, 5\] is inf: inputs must be finite$"):
        arm.nle(np.zeros((4, 7)), qs)


def test_a_mass_matrix_that_is_not_positive_definite_is_a_value_error():
    arm = dynamics.Robot("arm3r")
    arm.set("m", -100.0)  # a payload of negative mass
    z = np.zeros(3)
    with pytest.raises(ValueError, match="not positive definite"):
        arm.aba(z, z, z)
    # In a batch, the error names the state.
    with pytest.raises(ValueError, match=r"^state 0: the inertia matrix A\(q\) is not positive definite at q = \[0.0, 0.0, 0.0\]$"):
        arm.aba(np.zeros((2, 3)), np.zeros((2, 3)), np.zeros((2, 3)))
    with pytest.raises(ValueError, match=r"^state \d+: the inertia matrix A\(q\) is not positive definite"):
        arm.aba(np.zeros((100, 3)), np.zeros((100, 3)), np.zeros((100, 3)))
