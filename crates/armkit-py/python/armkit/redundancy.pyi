"""Redundancy resolution (seed 001): joint velocities realizing an
end-effector twist ``[vx, vy, vz, wx, wy, wz]`` (m/s, rad/s, world frame)."""

from typing import Optional, Sequence, Tuple

import numpy.typing as npt
import numpy as np

from ._armkit import Robot

__all__ = ["weighted_least_norm", "joint_torques", "energy_measure", "energy_optimal"]

def weighted_least_norm(
    robot: Robot, q: npt.ArrayLike, twist: npt.ArrayLike,
    weights: Optional[Sequence[float]] = None, damping: Optional[float] = None,
) -> npt.NDArray[np.float64]:
    """q_dot (dof,) with J q_dot = twist and the least sum a_i q_dot_i^2
    (seed 001, eq 18); ``weights`` a_i > 0 (default 1), ``inf`` locks a joint."""

def joint_torques(
    robot: Robot, q: npt.ArrayLike, payload: float = 0.0,
    wrench: Optional[Sequence[float]] = None, gravity: bool = True,
) -> npt.NDArray[np.float64]:
    """Static joint torques (N m or N) holding the end-effector wrench
    (default ``payload`` N) plus, with ``gravity``, the links' weights."""

def energy_measure(q_dot: npt.ArrayLike, torques: npt.ArrayLike) -> float:
    """Seed 001's F = sum (q_dot_i tau_i)^2 (eq 9)."""

def energy_optimal(
    robot: Robot, q: npt.ArrayLike, twist: npt.ArrayLike, payload: float = 0.0,
    wrench: Optional[Sequence[float]] = None, gravity: bool = True, torque_floor: float = 0.05,
) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], float]:
    """Seed 001's energy-optimal distribution: (q_dot, torques, F)."""
