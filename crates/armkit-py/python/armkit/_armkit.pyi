"""Type stubs of armkit's extension module (re-exported by ``armkit``).

Units: m, rad, s, kg, N. Poses: homogeneous (4, 4) float arrays in the world
frame (the frame the robot's base transform is given in). Jacobian rows:
``[vx, vy, vz, wx, wy, wz]``. Array arguments accept any float array-like
(lists, tuples, C- or Fortran-ordered or strided arrays of any real dtype);
results are new C-ordered float64 arrays. Bad input raises ``ValueError``
(``FileNotFoundError`` for a missing file) with the library's message.
"""

from os import PathLike
from types import ModuleType
import armkit.view
from typing import Any, Dict, Literal, Optional, Sequence, Tuple, Union, final

import numpy as np
import numpy.typing as npt

__version__: str
__all__ = [
    "__version__", "Beam", "ContinuousPath", "IkResult", "IkSolutions", "MpcPlanner", "Robot", "SpaceRobot", "Trajectory",
    "_reach", "_view_page", "builtin_robots", "continuous_path", "dynamics", "redundancy", "singularity", "study",
]

_ArrayLike = npt.ArrayLike
_FloatArray = npt.NDArray[np.float64]
_BoolArray = npt.NDArray[np.bool_]
_StrPath = Union[str, "PathLike[str]"]
_AnalyticSearch = Literal["elimination"]
_IkSolverName = Literal["auto", "analytic", "closed-form", "lm", "nr", "dls", "sri"]
_Representatives = Literal["nearest", "every"]
_JacobianFrameName = Literal["world", "end-effector"]

def _view_page(
    robot: Robot, t: _ArrayLike, q: _ArrayLike, path: Optional[_ArrayLike] = None
) -> str:
    """The 3-D view's HTML page (``armkit.view.animate``)."""

def builtin_robots() -> list[str]:
    """Names of the built-in robots (``Robot.builtin(name)``)."""

@final
class IkResult:
    """Result of ``Robot.ik``: not converging is a status, never an exception."""

    status: Literal["converged", "not_converged"]
    """``"converged"`` when both errors are within tolerance at ``q``."""
    converged: bool
    """``status == "converged"``."""
    solver: Literal["analytic", "analytic_sweep", "unreachable", "lm", "nr", "dls", "sri"]
    """The solver that produced ``q`` (``"unreachable"``: auto found the
    target beyond the reach bound and did not attempt it)."""
    q: _FloatArray
    """Joint positions (rad or m), shape (dof,), always within the joint limits
    (the best effort when not converged)."""
    position_error: float
    """Position error of FK(q) from the target, m."""
    orientation_error: float
    """Orientation error of FK(q) from the target, rad."""
    iterations: int
    """Iterations over all attempts (0 for the analytic solver)."""
    restarts: int
    """Random restarts used."""
    elapsed: float
    """Wall-clock time of the solve, s."""
    solutions: _FloatArray
    """Every solution found, shape (k, dof): where the analytic solver
    answered (``"analytic"``, or ``"auto"`` on its analytic route) every exact
    analytic solution within the limits, each distinct one once, nearest the
    start first (a 7-joint arm's at the answer's redundancy parameter); for a
    numeric solver the converged ``q`` (k = 1) or none (k = 0)."""

@final
class IkSolutions:
    """Result of ``Robot.ik_solutions``: every analytic solution within the
    joint limits, exact ones first, each group nearest ``q0`` first (k of
    them, possibly 0)."""

    q: _FloatArray
    """Joint positions (rad or m), shape (k, dof), nearest ``q0`` first."""
    exact: _BoolArray
    """Shape (k,): True where the solution reproduces the pose within 1e-10 m
    and rad; False for a least-squares one (a pose out of reach)."""
    fits: list[Literal["exact", "approximate"]]
    """Per solution, the library's fit name."""
    position_error: _FloatArray
    """Position error of each solution, m, shape (k,)."""
    orientation_error: _FloatArray
    """Orientation error of each solution, rad, shape (k,)."""
    arm_class: str
    """The arm's analytic class (``"three_parallel_2_3_4_intersecting_5_6"``
    for the UR5, ``"seed002_arm4"`` for arm4, ...)."""
    method: str
    """The class's description and the redundancy parameter of a 7-joint arm
    (elbow angle, or the held joint, 0-based, and its value)."""
    def __len__(self) -> int:
        """The number of solutions k."""

@final
class Robot:
    """A serial robot model: joint positions in rad (revolute) or m
    (prismatic), poses in the world frame (m)."""

    @staticmethod
    def builtin(name: str) -> Robot:
        """A built-in robot: ``puma560``, ``ur5``, ``panda``, ``stanford``,
        ``arm4``, ``space6r``, ``gantry9``, ``gantry9-flex``."""
    @staticmethod
    def from_urdf(path: _StrPath, base: Optional[str] = None, tip: Optional[str] = None) -> Robot:
        """The serial chain from link ``base`` (default: the root) to link
        ``tip`` (default: the only leaf below the base) of a URDF file. Fixed
        joints are folded away; floating, planar and mimic joints on the
        chain are errors giving the line."""
    @staticmethod
    def from_file(path: _StrPath) -> Robot:
        """A DH description file, TOML or JSON (the format of the CLI's
        ``--robot-file``; a reference JSON loads through its ``dh`` block)."""
    def description(self) -> str:
        """The robot as text: a built-in robot's name, the URDF text (led by
        ``<!-- armkit chain base="..." tip="..." -->`` when the chain is not
        the default one) or the DH description. ``Robot.from_description``
        reads it back; pickling and Dask workers use it."""
    @staticmethod
    def from_description(text: str) -> Robot:
        """The robot a description names: a built-in robot's name, URDF text
        (starting with ``<``) or a DH description in JSON (starting with
        ``{``) or TOML."""
    def __reduce__(self) -> Tuple[Any, Tuple[str]]:
        """Pickling: rebuilt by ``Robot.from_description(description())``."""
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
    def lower(self) -> _FloatArray:
        """Lower position limits, rad or m, shape (dof,); -inf where none."""
    @property
    def upper(self) -> _FloatArray:
        """Upper position limits, rad or m, shape (dof,); +inf where none."""
    @property
    def velocity_limits(self) -> Optional[_FloatArray]:
        """Velocity limits, rad/s or m/s, shape (dof,); None when a joint has none."""
    def neutral_configuration(self) -> _FloatArray:
        """The mid-range configuration (0 for joints without finite limits), shape (dof,)."""
    def check_limits(self, q: _ArrayLike) -> None:
        """Raises ValueError naming the first joint of ``q`` (dof,) outside its limits."""
    def show(self, q: Optional[_ArrayLike] = None) -> "armkit.view.View":
        """The robot in 3-D at ``q`` (default: mid-range): shown inline by
        Jupyter, ``save(path)`` writes the offline HTML page."""
    def fk(self, q: _ArrayLike, threads: Optional[int] = None) -> _FloatArray:
        """End-effector pose in the world frame: (4, 4) homogeneous (m) for
        ``q`` of shape (dof,); (N, 4, 4) for ``q`` of shape (N, dof), computed
        with the GIL released on ``threads`` threads (default: every core).
        ``q`` is evaluated even outside the joint limits (``check_limits(q)``
        raises for it), as ``armkit fk --allow-out-of-limits`` does."""
    @property
    def frame_names(self) -> list[str]:
        """Names of the frames ``fk_all`` returns, base to tip: the chain's
        joints (a URDF's joint names; ``q1``, ``q2``, ... for a DH table)."""
    def fk_all(self, q: _ArrayLike, threads: Optional[int] = None) -> _FloatArray:
        """Every link frame along the chain in the world frame: (n, 4, 4)
        homogeneous (m) for ``q`` of shape (dof,), (N, n, 4, 4) for (N, dof)
        (batched as ``fk``), n = ``len(frame_names)``. Frame i is the frame of
        the link joint i moves: a URDF's child link frame (Pinocchio's
        ``oMi``), a DH table's frame i."""
    def jacobian(
        self, q: _ArrayLike, frame: _JacobianFrameName = "world", threads: Optional[int] = None
    ) -> _FloatArray:
        """Geometric Jacobian of the end-effector frame, rows
        ``[vx, vy, vz, wx, wy, wz]`` (velocity of the end-effector origin, m/s,
        and angular velocity, rad/s, per unit joint velocity) in world or
        end-effector axes: (6, dof) for ``q`` (dof,), (N, 6, dof) for (N, dof)
        (batched as ``fk``)."""
    def ik(
        self,
        T: _ArrayLike,
        q0: Optional[_ArrayLike] = None,
        solver: _IkSolverName = "auto",
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
        ``"auto"`` (analytic where the arm's class allows: spherical wrist,
        the UR family, 7-DOF arms; else Levenberg-Marquardt), ``"analytic"``
        (every analytic solution, the nearest exact one returned; alias
        ``"closed-form"``), ``"lm"``, ``"nr"``, ``"dls"``, ``"sri"``: the names
        of ``armkit ik --solver``. Tolerances in m and rad; ``time_budget`` in s
        per solve (None: none); ``task_weights`` on ``[x, y, z, rx, ry, rz]``
        (a zero masks that component). Deterministic for a given ``seed``
        unless the time budget cuts the search short."""
    def ik_solutions(
        self,
        T: _ArrayLike,
        q0: Optional[_ArrayLike] = None,
        search: _AnalyticSearch = "elimination",
        fixed_joint: Optional[int] = None,
        parameter: Optional[float] = None,
        sweep: Optional[int] = None,
        representatives: _Representatives = "nearest",
    ) -> IkSolutions:
        """Every analytic IK solution of ``T`` ((4, 4), world frame, m) within
        the joint limits, exact ones first, each group nearest ``q0`` (dof,)
        first (default: mid-range), as ``armkit ik --solver analytic``.
        ``representatives``: ``"nearest"`` (default: each distinct solution
        once) or ``"every"`` (every 2 pi multiple within the joint limits), as
        ``--representatives``. ``search``: ``"elimination"`` (the
        default and the only route: closed forms, every other 6R arm by
        algebraic elimination, tens of microseconds); ``"1d"`` and ``"2d"``
        (retired searches) raise ValueError. 7-joint arms: the elbow angle of a
        spherical-shoulder-elbow-wrist arm (iiwa), else a held joint (Panda);
        ``fixed_joint`` holds that joint (0-based, like a numpy index);
        ``parameter`` is the elbow angle (rad) or the held joint's value
        (default: ``q0``'s); ``sweep`` N solves at N values of it (the elbow
        angle's circle, the held joint's range) together. ValueError naming
        the argument for bad input, or naming the arm's class when it has no
        analytic solver; GIL released."""
    def arm_class(self) -> Tuple[str, str]:
        """The arm's analytic class ``(name, description)`` (``armkit ik
        --explain``; a 7-joint arm's with its held joint, 0-based, when the
        whole arm has no class). Arms without solver have a class too."""
    def ik_batch(
        self,
        Ts: _ArrayLike,
        q0: Optional[_ArrayLike] = None,
        solver: _IkSolverName = "auto",
        position_tolerance: float = 1e-6,
        orientation_tolerance: float = 1e-6,
        max_iterations: int = 50,
        max_restarts: int = 1000,
        time_budget: Optional[float] = 0.005,
        seed: int = 0,
        task_weights: Optional[Sequence[float]] = None,
        threads: Optional[int] = None,
    ) -> Tuple[_FloatArray, _BoolArray]:
        """Inverse kinematics of ``Ts`` (N, 4, 4) from ``q0`` of shape (dof,)
        (one start for all), (N, dof) (one each) or None (mid-range), options
        as ``ik``. Returns ``(Q, converged)``: (N, dof) joint positions within
        the limits (the best effort where not converged) and an (N,) bool
        array. GIL released, ``threads`` threads (default: every core)."""
    def benchmark_targets(self, count: int, seed: int = 42) -> Tuple[_FloatArray, _FloatArray]:
        """``armkit bench-ik``'s targets: ``count`` configurations drawn
        uniformly within the limits (ChaCha8, ``seed``), shape (count, dof),
        and their end-effector poses, shape (count, 4, 4)."""

@final
class Trajectory:
    """A joint-space trajectory: a piecewise polynomial over all joints.
    Times in s; rad, rad/s, rad/s^2 (revolute) or m, m/s, m/s^2 (prismatic)."""

    @staticmethod
    def cubic(
        q_start: _ArrayLike, q_end: _ArrayLike, duration: float,
        v_start: Optional[_ArrayLike] = None, v_end: Optional[_ArrayLike] = None,
    ) -> Trajectory:
        """Cubic meeting boundary positions and velocities (default zero)."""
    @staticmethod
    def quintic(
        q_start: _ArrayLike, q_end: _ArrayLike, duration: float,
        v_start: Optional[_ArrayLike] = None, v_end: Optional[_ArrayLike] = None,
        a_start: Optional[_ArrayLike] = None, a_end: Optional[_ArrayLike] = None,
    ) -> Trajectory:
        """Quintic meeting boundary positions, velocities and accelerations (default zero)."""
    @staticmethod
    def trapezoidal(q_start: _ArrayLike, q_end: _ArrayLike, duration: float, acceleration_time: float) -> Trajectory:
        """Trapezoidal velocity, rest to rest, synchronized over the joints
        (``acceleration_time`` s of ramp at each end)."""
    @staticmethod
    def minimum_time(
        q_start: _ArrayLike, q_end: _ArrayLike, velocity_limits: _ArrayLike, acceleration_limits: _ArrayLike,
        shape: Literal["trapezoidal", "cubic", "quintic"] = "trapezoidal",
    ) -> Trajectory:
        """The fastest rest-to-rest profile of ``shape`` within the limits."""
    @staticmethod
    def spline(
        times: _ArrayLike, positions: _ArrayLike, v_start: Optional[_ArrayLike] = None, v_end: Optional[_ArrayLike] = None
    ) -> Trajectory:
        """The clamped C2 cubic spline through ``positions`` (K, dof) at ``times`` (K,) s."""
    @property
    def dof(self) -> int: ...
    @property
    def start_time(self) -> float:
        """s."""
    @property
    def end_time(self) -> float:
        """s."""
    @property
    def duration(self) -> float:
        """s."""
    @property
    def knots(self) -> _FloatArray:
        """Segment boundaries, s, shape (segments + 1,)."""
    def sample(self, t: _ArrayLike) -> Tuple[_FloatArray, _FloatArray, _FloatArray]:
        """Position, velocity, acceleration at ``t`` (s, clamped to the span):
        (dof,) each for a scalar ``t``, (N, dof) for ``t`` of shape (N,)."""

@final
class ContinuousPath:
    """Result of ``continuous_path`` (seed 002)."""

    status: Literal["tolerance_met", "tolerance_not_met"]
    trajectory: Trajectory
    """The joint trajectory, one polynomial per segment."""
    configurations: _FloatArray
    """IK solutions at the knots, (segments + 1, dof)."""
    checked_position_error: float
    """Largest position error at the check points, m."""
    checked_orientation_error: float
    """Largest orientation error at the check points, rad."""
    interior_position_error: float
    """Largest position error on 100 points per segment, m."""
    interior_orientation_error: float
    """Largest orientation error on 100 points per segment, rad."""
    passes: int
    ik_solves: int
    ik_method: str
    def path_poses(self, t: _ArrayLike) -> _FloatArray:
        """The Cartesian path's pose(s) at ``t`` (s): (4, 4) or (N, 4, 4), world frame, m."""

def continuous_path(
    robot: Robot, q_start: _ArrayLike, T_goal: _ArrayLike, duration: float,
    law: Literal["quintic", "linear", "trapezoidal"] = "quintic",
    acceleration_time: Optional[float] = None,
    task: Literal["pose", "position", "auto"] = "auto",
    tolerance: float = 1e-4, orientation_tolerance: float = 1e-3,
    segments: Optional[int] = None, max_segments: int = 4096,
) -> ContinuousPath:
    """Seed 002's continuous path along the straight line from FK(q_start)
    to ``T_goal`` ((4, 4), world frame, m) in ``duration`` s: IK at the knots
    (closed form where the robot has one, else numeric), one polynomial per
    segment, segments doubled where the path error exceeds ``tolerance`` (m)
    / ``orientation_tolerance`` (rad). ``task="auto"``: position only for
    arms under 6 DOF. Not meeting the tolerance is a status."""

@final
class MpcPlanner:
    """Seed 000's incremental MPC (Clarabel QP), joint position and velocity
    limits as constraints. Units s, m, rad; world frame."""

    def __new__(
        cls, robot: Robot, horizon: int = 10, control_horizon: int = 1, sample_time: float = 0.05,
        tracking: float = 10.0, terminal: float = 200.0, orientation: bool = True,
        increment_weights: Optional[Sequence[float]] = None,
        solver: Literal["active-set", "clarabel", "osqp"] = "active-set", reach: bool = True,
        priority: Literal["weighted", "strict"] = "weighted",
    ) -> MpcPlanner:
        """A planner for ``robot``: horizon N, control horizon M, sample time
        (s), task weights ``tracking`` (samples 1..N-1) and ``terminal`` (N)
        on position and, with ``orientation``, orientation; one increment
        weight per joint (seed 000's priorities: larger moves less). The
        robot's velocity and position limits are the constraints. ``solver``:
        the QP backend ("osqp" only when built in); ``reach``: the
        goal-posture aid (off: seed 000's planner as printed); ``priority``:
        "weighted" (the increment weights in one cost) or "strict" (joints
        of equal weight form a level, smallest weight first, one QP per
        level with the levels above held at their optimum)."""
    @property
    def solver(self) -> str:
        """The QP backend's name."""
    def set_target(self, T: _ArrayLike) -> None:
        """The target end-effector pose, (4, 4), world frame, m."""
    def step(self, q: _ArrayLike) -> Dict[str, Any]:
        """One step at measured ``q`` (dof,): ``status`` ("solved", "clamped",
        "recovering", "stopped"), ``velocity`` (dof,) to apply for one sample,
        ``position_error`` (m), ``orientation_error`` (rad),
        ``prediction_error`` (m), ``solve_time`` (s), ``limit_correction``."""
    def run(
        self, T: _ArrayLike, q_start: _ArrayLike, max_steps: int = 2000, position_tolerance: float = 1e-4,
        orientation_tolerance: float = 1e-3, velocity_tolerance: float = 1e-3,
        prismatic_resolution: float = 0.0, prismatic_deadband: float = 0.0,
        rotary_resolution: float = 0.0, rotary_deadband: float = 0.0,
    ) -> Dict[str, Any]:
        """Closed loop to ``T`` from ``q_start`` (the joints follow the
        commands exactly, or by actuators of limited precision: position
        resolution in m / rad, speed deadband in m/s / rad/s); arrays ``time`` (K,), ``q``
        and ``velocity`` (K, dof), ``position`` (K, 3), ``position_error``,
        ``orientation_error`` (K,), ``status`` (list); summary ``converged``,
        ``steps``, ``final_position_error``, ``final_orientation_error``,
        ``max_velocity_violation``, ``max_position_violation``."""

@final
class Beam:
    """A simply supported beam: length m, Young's modulus Pa, second moment
    m^4. Deflection positive downward, m; loads (K, 2) of (position m, force N)."""

    def __new__(cls, length: float, youngs_modulus: float, second_moment: float) -> Beam: ...
    @staticmethod
    def seed000() -> Beam:
        """Seed 000's gantry beam (its Table 1)."""
    @property
    def length(self) -> float: ...
    @property
    def stiffness(self) -> float:
        """E I, N m^2."""
    def deflection(self, x: float, loads: _ArrayLike) -> float: ...
    def slope(self, x: float, loads: _ArrayLike) -> float: ...
    def deflection_under_load(self, position: float, force: float) -> float: ...

@final
class SpaceRobot:
    """A free-floating space manipulator (arm on a spacecraft, no external
    force); poses in the inertial frame, m. ``mode``: "attitude-held"
    (seed 004) or "free-floating"."""

    @staticmethod
    def space6r() -> SpaceRobot:
        """Seed 004's robot: space6r on a 400 kg satellite."""
    @property
    def dof(self) -> int: ...
    @property
    def total_mass(self) -> float:
        """kg."""
    def generalized_jacobian(
        self, q: _ArrayLike, base: Optional[_ArrayLike] = None, mode: Literal["attitude-held", "free-floating"] = "attitude-held"
    ) -> _FloatArray:
        """J* (6, dof), rows [vx vy vz wx wy wz]; ``base`` (4, 4), default identity."""
    def step(
        self, q: _ArrayLike, joint_rates: _ArrayLike, dt: float, base: Optional[_ArrayLike] = None,
        mode: Literal["attitude-held", "free-floating"] = "attitude-held",
    ) -> Tuple[_FloatArray, _FloatArray]:
        """Integrates ``joint_rates`` held over ``dt`` s (0 < dt <= 1): the new (base (4, 4), q (dof,))."""

dynamics: ModuleType
redundancy: ModuleType
singularity: ModuleType
study: ModuleType
_reach: ModuleType
