"""Singularity detection and avoidance (seed 004)."""

from typing import Any, Dict, Literal, Optional, Tuple

import numpy as np
import numpy.typing as npt

from ._armkit import Robot

__all__ = ["classify", "line_through", "track_line"]

def classify(robot: Robot, q: npt.ArrayLike, tolerance: float = 1e-6) -> Dict[str, Any]:
    """``kinds`` (wrist, elbow, shoulder, unclassified; empty when regular),
    ``singular``, ``rank``, ``singular_values`` (largest first),
    ``determinant`` (6-DOF robots, else None) at ``q``."""

def line_through(
    robot: Robot, through: npt.ArrayLike, joint_direction: npt.ArrayLike, miss: float = 0.0
) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """(q_start, T_goal): a pose line whose midpoint is FK(through) and whose
    direction is the motion of ``joint_direction`` there (seed 004's path);
    ``miss`` moves it off that pose along the motion the Jacobian cannot make
    there (m and rad together; the study's near-miss lines)."""

def track_line(
    robot: Robot, q_start: npt.ArrayLike, T_goal: npt.ArrayLike,
    method: Literal["plain", "avoidance", "dls", "dls_clamped", "sri", "separation"] = "avoidance", k: int = 5,
    duration: float = 20.0, acceleration_time: float = 4.0, dt: float = 0.01,
    determinant_threshold: Optional[float] = None, joint_step_threshold: float = 0.005,
    max_rate: float = 0.5, region_plan: Literal["joint", "greedy", "exact"] = "joint",
    feedback: Literal["next-pose", "open-loop"] = "next-pose",
) -> Dict[str, Any]:
    """Tracks the pose line from FK(q_start) to T_goal (trapezoidal speed)
    every ``dt`` s with ``method`` (``"dls_clamped"``: DLS with its rates
    scaled to at most ``max_rate`` rad/s; ``region_plan``: the avoidance's
    knots of a region all together, ``"joint"``, one by one, ``"greedy"``, or
    seed 004's Newton knots as printed without a rate bound, ``"exact"``;
    ``feedback``: ``"next-pose"`` (seed 004, eqs 26-27) or ``"open-loop"``,
    the path's twist alone); arrays ``time``, ``q``, ``joint_rates``
    (samples, dof), ``position_error`` (m), ``orientation_error`` (rad),
    ``determinant``, ``in_region``; summary ``status``, ``peak_joint_rate``
    (rad/s), ``max_position_error``, ``max_orientation_error``,
    ``final_position_error``, ``time_in_singular_region`` (s), ``ik_solves``;
    ``determinant_threshold`` (m^3) and ``threshold_rule``: ``"given"``, or
    without one, seed 004's rule (``"calibrated"``: the largest |det J| where
    this line's plain run jumps; ``"fitted"`` 0.004 when it never jumps).
    At most 10^6 control periods (``duration / dt``) and ``k`` in
    1..=10^6: beyond, ValueError naming ``dt`` (with the memory the run
    would need) or ``k``, before any work."""
