"""Type stubs of armkit's extension module (re-exported by ``armkit``).

Units: m, rad, s, kg, N. Poses: homogeneous (4, 4) float arrays in the world
frame (the frame the robot's base transform is given in). Jacobian rows:
``[vx, vy, vz, wx, wy, wz]``. Array arguments accept any float array-like
(lists, tuples, C- or Fortran-ordered or strided arrays of any real dtype);
results are new C-ordered float64 arrays. Bad input raises ``ValueError``
(``FileNotFoundError`` for a missing file) with the library's message.
"""

from os import PathLike
from typing import Literal, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str

ArrayLike = npt.ArrayLike
FloatArray = npt.NDArray[np.float64]
BoolArray = npt.NDArray[np.bool_]
StrPath = Union[str, "PathLike[str]"]
IkSolverName = Literal["auto", "closed-form", "lm", "nr", "dls", "sri"]
JacobianFrameName = Literal["world", "end-effector"]

def builtin_robots() -> list[str]:
    """Names of the built-in robots (``Robot.builtin(name)``)."""

class IkResult:
    """Result of ``Robot.ik``: not converging is a status, never an exception."""

    status: Literal["converged", "not_converged"]
    """``"converged"`` when both errors are within tolerance at ``q``."""
    converged: bool
    """``status == "converged"``."""
    solver: Literal["closed-form", "lm", "nr", "dls", "sri"]
    """The solver that produced ``q``."""
    q: FloatArray
    """Joint positions (rad or m), shape (dof,), always within the joint limits
    (the best effort when not converged)."""
    position_error: float
    """Position error of FK(q) from the target, m."""
    orientation_error: float
    """Orientation error of FK(q) from the target, rad."""
    iterations: int
    """Iterations over all attempts (0 for the closed form)."""
    restarts: int
    """Random restarts used."""
    elapsed: float
    """Wall-clock time of the solve, s."""
    solutions: FloatArray
    """Every solution found, shape (k, dof): all closed-form solutions within
    the limits, nearest the start first; for a numeric solver the converged
    ``q`` (k = 1) or none (k = 0)."""

class Robot:
    """A serial robot model: joint positions in rad (revolute) or m
    (prismatic), poses in the world frame (m)."""

    @staticmethod
    def builtin(name: str) -> Robot:
        """A built-in robot: ``puma560``, ``ur5``, ``panda``, ``stanford``,
        ``arm4``, ``space6r``, ``gantry9``, ``gantry9-flex``."""
    @staticmethod
    def from_urdf(path: StrPath, base: Optional[str] = None, tip: Optional[str] = None) -> Robot:
        """The serial chain from link ``base`` (default: the root) to link
        ``tip`` (default: the only leaf below the base) of a URDF file. Fixed
        joints are folded away; floating, planar and mimic joints on the
        chain are errors giving the line."""
    @staticmethod
    def from_file(path: StrPath) -> Robot:
        """A DH description file, TOML or JSON (the format of the CLI's
        ``--robot-file``; a reference JSON loads through its ``dh`` block)."""
    @property
    def dof(self) -> int:
        """Degrees of freedom (moving joints)."""
    @property
    def name(self) -> str:
        """The model's name."""
    @property
    def joint_names(self) -> list[str]:
        """Joint names, base to tip."""
    @property
    def lower(self) -> FloatArray:
        """Lower position limits, rad or m, shape (dof,); -inf where none."""
    @property
    def upper(self) -> FloatArray:
        """Upper position limits, rad or m, shape (dof,); +inf where none."""
    @property
    def velocity_limits(self) -> Optional[FloatArray]:
        """Velocity limits, rad/s or m/s, shape (dof,); None when a joint has none."""
    def neutral_configuration(self) -> FloatArray:
        """The mid-range configuration (0 for joints without finite limits), shape (dof,)."""
    def check_limits(self, q: ArrayLike) -> None:
        """Raises ValueError naming the first joint of ``q`` (dof,) outside its limits."""
    def fk(self, q: ArrayLike, threads: Optional[int] = None) -> FloatArray:
        """End-effector pose in the world frame: (4, 4) homogeneous (m) for
        ``q`` of shape (dof,); (N, 4, 4) for ``q`` of shape (N, dof), computed
        with the GIL released on ``threads`` threads (default: every core)."""
    def jacobian(
        self, q: ArrayLike, frame: JacobianFrameName = "world", threads: Optional[int] = None
    ) -> FloatArray:
        """Geometric Jacobian of the end-effector frame, rows
        ``[vx, vy, vz, wx, wy, wz]`` (velocity of the end-effector origin, m/s,
        and angular velocity, rad/s, per unit joint velocity) in world or
        end-effector axes: (6, dof) for ``q`` (dof,), (N, 6, dof) for (N, dof)
        (batched as ``fk``)."""
    def ik(
        self,
        T: ArrayLike,
        q0: Optional[ArrayLike] = None,
        solver: IkSolverName = "auto",
        position_tolerance: float = 1e-6,
        orientation_tolerance: float = 1e-6,
        max_iterations: int = 50,
        max_restarts: int = 1000,
        time_budget: Optional[float] = 0.005,
        seed: int = 0,
        task_weights: Optional[Sequence[float]] = None,
    ) -> IkResult:
        """Inverse kinematics of the end-effector pose ``T`` ((4, 4), world
        frame, m) from ``q0`` (dof,) (default: mid-range). ``solver``:
        ``"auto"`` (the closed form where the robot has one, else
        Levenberg-Marquardt), ``"closed-form"``, ``"lm"``, ``"nr"``,
        ``"dls"``, ``"sri"``. Tolerances in m and rad; ``time_budget`` in s
        per solve (None: none); ``task_weights`` on ``[x, y, z, rx, ry, rz]``
        (a zero masks that component). Deterministic for a given ``seed``
        unless the time budget cuts the search short."""
    def ik_batch(
        self,
        Ts: ArrayLike,
        q0: Optional[ArrayLike] = None,
        solver: IkSolverName = "auto",
        position_tolerance: float = 1e-6,
        orientation_tolerance: float = 1e-6,
        max_iterations: int = 50,
        max_restarts: int = 1000,
        time_budget: Optional[float] = 0.005,
        seed: int = 0,
        task_weights: Optional[Sequence[float]] = None,
        threads: Optional[int] = None,
    ) -> Tuple[FloatArray, BoolArray]:
        """Inverse kinematics of ``Ts`` (N, 4, 4) from ``q0`` of shape (dof,)
        (one start for all), (N, dof) (one each) or None (mid-range), options
        as ``ik``. Returns ``(Q, converged)``: (N, dof) joint positions within
        the limits (the best effort where not converged) and an (N,) bool
        array. GIL released, ``threads`` threads (default: every core)."""
    def benchmark_targets(self, count: int, seed: int = 42) -> Tuple[FloatArray, FloatArray]:
        """``armkit bench-ik``'s targets: ``count`` configurations drawn
        uniformly within the limits (ChaCha8, ``seed``), shape (count, dof),
        and their end-effector poses, shape (count, 4, 4)."""
