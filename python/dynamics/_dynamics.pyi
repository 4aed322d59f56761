"""Type stubs of the extension module ``dynamics._dynamics``.

Conventions: ``N`` joints; every array argument is one state ``(N,)`` or a
batch ``(B, N)`` (all arguments of a call alike), float64 or convertible to
it, C-contiguous or not (read in place when C-contiguous). Results are new
float64 arrays: ``(N,)`` / ``(B, N)`` vectors, ``(N, N)`` / ``(B, N, N)``
matrices, floats / ``(B,)`` for energies. A batch runs without the GIL, over
threads from ``PARALLEL_FROM`` states on; it gives exactly what a loop of
single calls gives.

``out=`` (the dynamics calls and their derivatives): a C-contiguous,
writeable float64 array of exactly the result's shape (a tuple of them for
a call with several results) is written in place and returned instead of a
new array. A wrong shape, dtype, layout, a read-only array or one sharing
memory with an input raises ``ValueError`` naming it, before anything is
written.

Errors: ``ValueError`` for a wrong shape, an entry that is NaN or infinite
(naming the argument and entry), or a state where the dynamics fail (a
mass matrix that is not positive definite; naming the state of a batch);
``KeyError`` for an unknown robot, parameter or frame (listing the known ones).
"""

from os import PathLike
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

ArrayLike = npt.ArrayLike
Array = npt.NDArray[np.float64]
Data = Union[str, PathLike, Mapping[str, ArrayLike], Any]
Window = Union[str, Tuple[float, float]]
Levels = Union[float, Sequence[float]]
Effects = Union[str, PathLike, Mapping[str, Any]]

PARALLEL_FROM: int
"""Batches of at least this many states run on several threads."""

def robots() -> List[Tuple[str, str]]:
    """The robots ``Robot(name)`` knows: ``(name, one line about it)``."""

class Robot:
    """A robot: its dynamics at one state or a batch of states.

    ``Robot("panda")``: a built-in robot (``robots()`` lists them). A
    package made by ``dynamics new DIR --urdf FILE --python`` makes its own
    robot with ``Robot()``.
    """

    def __init__(self, name: Optional[str] = None) -> None: ...
    @property
    def name(self) -> str:
        """The robot's name."""
    @property
    def joint_names(self) -> List[str]:
        """Joint names in coordinate order."""
    @property
    def nq(self) -> int:
        """Number of joint coordinates N."""
    @property
    def params(self) -> Dict[str, float]:
        """Run-time parameters, name -> value (a copy; change one with ``set``)."""
    def set(self, name: str, value: float) -> None:
        """Sets a run-time parameter. KeyError (listing the known names) for an
        unknown one, ValueError for a value that is not finite."""
    @property
    def lower(self) -> Array:
        """Lower position limits ``(N,)`` (URDF; -inf where none)."""
    @property
    def upper(self) -> Array:
        """Upper position limits ``(N,)`` (URDF; +inf where none)."""
    @property
    def velocity_limit(self) -> Array:
        """Velocity limits ``(N,)`` (URDF; +inf where none)."""
    @property
    def effort_limit(self) -> Array:
        """Effort limits ``(N,)`` (URDF; +inf where none)."""
    @property
    def link_names(self) -> List[str]:
        """The L links of the inertial regressor, in its column order."""
    @property
    def frame_names(self) -> List[str]:
        """Frames ``frame_pose`` knows (one per link)."""
    def inertial_parameters(self) -> Array:
        """``(10 L,)``: per link ``[m, m cx, m cy, m cz, Ixx, Ixy, Iyy, Ixz, Iyz, Izz]``
        (Pinocchio's order, about the link frame's origin)."""
    def rnea(self, q: ArrayLike, v: ArrayLike, a: ArrayLike, *, out: Optional[Array] = None) -> Array:
        """Inverse dynamics: the efforts ``tau`` that give accelerations ``a``
        (with the model's damping and friction, if any)."""
    def mass_matrix(self, q: ArrayLike, *, out: Optional[Array] = None) -> Array:
        """The inertia matrix ``M(q)``: ``(N, N)`` or ``(B, N, N)``."""
    def gravity(self, q: ArrayLike, *, out: Optional[Array] = None) -> Array:
        """Gravity efforts ``g(q)``: what holds the robot still."""
    def nle(self, q: ArrayLike, v: ArrayLike, *, out: Optional[Array] = None) -> Array:
        """Efforts at zero acceleration: ``C(q, v) v + g(q)`` (plus damping, friction, springs)."""
    def coriolis_matrix(self, q: ArrayLike, v: ArrayLike, *, out: Optional[Array] = None) -> Array:
        """The Christoffel Coriolis matrix ``C(q, v)`` (``dM/dt - 2 C`` is skew)."""
    def aba(self, q: ArrayLike, v: ArrayLike, tau: ArrayLike, *, out: Optional[Array] = None) -> Array:
        """Forward dynamics: the accelerations under ``tau``. ValueError where
        ``M`` is not positive definite."""
    def rnea_derivatives(
        self, q: ArrayLike, v: ArrayLike, a: ArrayLike, *, out: Optional[Tuple[Array, Array]] = None
    ) -> Tuple[Array, Array]:
        """``(dtau_dq, dtau_dv)`` (Pinocchio's ``computeRNEADerivatives``)."""
    def aba_derivatives(
        self,
        q: ArrayLike,
        v: ArrayLike,
        tau: ArrayLike,
        *,
        out: Optional[Tuple[Array, Array, Array]] = None,
    ) -> Tuple[Array, Array, Array]:
        """``(ddq_dq, ddq_dv, ddq_dtau)`` at fixed ``tau``; ``ddq_dtau = M^-1``
        (Pinocchio's ``computeABADerivatives``)."""
    def regressor(self, q: ArrayLike, v: ArrayLike, a: ArrayLike, *, out: Optional[Array] = None) -> Array:
        """The inertial regressor ``Y``, ``(N, 10 L)``: ``Y @ inertial_parameters()``
        is the rigid-body part of ``rnea``."""
    def state_space(
        self,
        q: ArrayLike,
        v: ArrayLike,
        tau: ArrayLike,
        dt: Optional[float] = None,
        *,
        out: Optional[Tuple[Array, Array]] = None,
    ) -> Tuple[Array, Array]:
        """The linearised model ``(A, B)`` of ``x' = f(x, u)``, ``x = [q; v]``,
        ``u = tau``, about ``(q, v, tau)``: ``(2N, 2N)`` and ``(2N, N)`` (batch:
        ``(B, 2N, 2N)``, ``(B, 2N, N)``).

        ``dt=None``: continuous, ``A_c = [[0, I], [ddq_dq, ddq_dv]]``,
        ``B_c = [[0], [M^-1]]`` (the runtime's ``linearize::state_space``;
        the blocks are ``aba_derivatives``). ``dt`` (s): the runtime's
        zero-order hold ``StateSpace::discretize``, ``dx[k+1] = A_d dx[k] +
        B_d du[k]`` with ``A_d = exp(A_c dt)``, ``B_d = int_0^dt exp(A_c s) ds
        B_c`` (the exponential of ``[[A_c, B_c], [0, 0]] dt``; a Pade
        approximant with scaling and squaring). ValueError for a ``dt`` that
        is not a finite positive number, or so long the exponential overflows.
        """
    def kinetic_energy(self, q: ArrayLike, v: ArrayLike) -> Union[float, Array]:
        """``T = v' M v / 2``: a float, or ``(B,)``."""
    def potential_energy(self, q: ArrayLike) -> Union[float, Array]:
        """Gravity and spring potential: a float, or ``(B,)``."""
    def frame_pose(self, frame: str, q: ArrayLike) -> Array:
        """World pose of a frame, 4 x 4 homogeneous: ``(4, 4)`` or ``(B, 4, 4)``."""
    def synth(
        self,
        effect: Optional[str] = None,
        joint: Optional[str] = None,
        magnitude: Optional[float] = None,
        seed: int = 1,
        excitation: str = "sines",
        duration: float = 8.0,
        noise_q: float = 2e-5,
        noise_qd: float = 2e-3,
        noise_tau: float = 2e-3,
    ) -> Dict[str, Any]:
        """Synthetic measured data with a withheld effect, as ``dynamics synth``
        writes them: ``{"train": csv_text, "holdout": csv_text, "truth": dict}``."""
    def simulate(
        self,
        motion: Union[str, PathLike, None] = None,
        *,
        duration: float = 8.0,
        rate: float = 1000.0,
        seed: int = 1,
        bandwidth: float = 12.0,
        home: Optional[Levels] = None,
        amplitude: Optional[Levels] = None,
        effects: Optional[Effects] = None,
        baseline: Optional[Effects] = None,
    ) -> Dict[str, Array]:
        """The robot under a computed-torque controller on its own model following a
        reference, as ``dynamics simulate`` (the same function, with the same options):
        ``{"t": (T,), "q", "qd", "qdd", "tau", "reference": (T, N)}``; ``t, q, qd, qdd,
        tau`` are the columns of the CSV the command line writes, ``reference`` the
        positions followed.

        ``motion``: ``"sines"`` (``None``), ``"chirp"``, ``"pick-place"`` (the data generator's
        excitations, ``seed`` and ``duration`` as ``--seed``, ``--duration``), or the
        path of a CSV with columns ``t, q_<joint>`` (interpolated linearly; at most
        its own span). ``rate``: output samples per second. ``bandwidth``: the
        closed loop's, rad/s (``kp = w^2``, ``kd = 2 w``). ``home``/``amplitude``:
        one value or one per joint (default: the robot's). ``effects``: what acts on
        the simulated robot but not on the controller's model (``--effects``);
        ``baseline``: what both have (``--baseline``); each a path of a JSON file, or
        the JSON itself as a mapping: a diagnosis report dict, or ``{"effects":
        [{"kind", "joint", "parameters": [{"name", "value"}]}]}``. Runs without the
        GIL. ValueError with the command line's message when an option or the
        simulation fails.
        """
    def identify(
        self, train: Data, holdout: Data, *, topic: Optional[str] = None
    ) -> Dict[str, Any]:
        """Least-squares identification of friction, offsets, rotor inertias and the
        links' inertial parameters on ``train``, judged on ``holdout``: the JSON of
        ``dynamics identify --json`` as a dict (``robot, rank, columns, train_rows,
        shrink, joints, links, dropped``).

        ``train``/``holdout`` as for ``diagnose`` (a path of any format the command
        line reads, a DataFrame, a mapping of arrays); ``topic``: the JointState
        topic of a ROS 2 bag (``--topic``; default ``/joint_states``). The data's
        warnings go to the ``dynamics`` logger (WARNING), what was read of a bag
        to it at INFO. Runs without the GIL.
        """
    def diagnose(
        self,
        train: Data,
        holdout: Data,
        *,
        columns: Optional[str] = None,
        topic: Optional[str] = None,
        train_window: Optional[Window] = None,
        holdout_window: Optional[Window] = None,
        noise_tau: Optional[Levels] = None,
        noise_q: Optional[Levels] = None,
        noise_qd: Optional[Levels] = None,
        hold_links: bool = False,
        judge_links: bool = False,
        progress: Union[None, bool, Callable[[int, int], Any]] = None,
    ) -> Dict[str, Any]:
        """The gap diagnosis: the JSON report of ``dynamics diagnose --json`` as a dict.

        ``train``/``holdout``: a path (every format the command line reads: CSV,
        CSV.gz, Parquet, a ROS 2 bag; ``columns`` as its ``--columns``, ``topic``
        as its ``--topic``: the bag's JointState topic, default ``/joint_states``),
        a pandas DataFrame with the CSV's
        columns (``t, q_<joint>, [qd_<joint>,] tau_<joint>``), or a mapping
        ``{"t": (T,), "q": (T, N), "qd": (T, N) (optional), "tau": (T, N)}``.
        Windows: ``"START:END"`` or ``(START, END)`` seconds from the first
        sample. ``noise_*``: the known sensor noise (one level or one per joint),
        as ``--noise-tau/--noise-q/--noise-qd``. ``hold_links``: as ``--hold-links``
        (a link correction the data take beyond every body held to the nearest
        one and named if it holds on the held-out record; by default they are held
        only where the data ask for such corrections on most links).
        ``judge_links``: as ``--judge-links`` (never held). ``progress``: a callable
        ``progress(done, total)`` called as candidates are fitted; ``True`` for a
        ``tqdm.auto`` bar (or, without tqdm, INFO lines on the ``dynamics`` logger
        every tenth of the candidates); never writes to the terminal itself. Warnings go to the ``dynamics`` logger
        too. ValueError with the cause when the data cannot be read or diagnosed.
        """
    def copy(self) -> "Robot":
        """A copy with its own parameters."""
