"""Rigid-body dynamics: one state, or a batch of N states (arrays of shape
(N, dof); GIL released, ``threads`` threads, default every core).

Units: q rad or m, v rad/s or m/s, a rad/s^2 or m/s^2, torques N m or N,
mass matrix kg m^2 / kg, energy J; ``gravity`` a world-frame acceleration
(m/s^2), default (0, 0, -9.81). The robot needs mass properties (URDF
inertials, DH ``mass``/``com``/``inertia``; the built-ins with them:
``ur5``, ``ur5-urdf``, ``panda``, ``space6r``, ``gantry9``, ``gantry9-flex``); a model
with joint couplings (mimic joints, gantry9-flex's beam) runs in its
independent joints."""

from typing import Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

from ._armkit import Robot

__all__ = ["rnea", "aba", "mass_matrix", "gravity_torques", "coriolis_torques", "kinetic_energy"]

def rnea(
    robot: Robot, q: npt.ArrayLike, v: npt.ArrayLike, a: npt.ArrayLike,
    gravity: Optional[Sequence[float]] = None, threads: Optional[int] = None,
) -> npt.NDArray[np.float64]:
    """Inverse dynamics: tau = M(q) a + C(q, v) v + g(q); (dof,) or (N, dof)."""

def aba(
    robot: Robot, q: npt.ArrayLike, v: npt.ArrayLike, tau: npt.ArrayLike,
    gravity: Optional[Sequence[float]] = None, threads: Optional[int] = None,
) -> npt.NDArray[np.float64]:
    """Forward dynamics: a = M(q)^-1 (tau - C(q, v) v - g(q)); (dof,) or (N, dof).

    Raises ValueError when M(q) is numerically singular (a pivot at or below
    armkit's MASS_MATRIX_THRESHOLD, 1e-10, times M's largest diagonal entry),
    naming the joint."""

def mass_matrix(robot: Robot, q: npt.ArrayLike, threads: Optional[int] = None) -> npt.NDArray[np.float64]:
    """M(q): (dof, dof) or (N, dof, dof), symmetric positive definite."""

def gravity_torques(
    robot: Robot, q: npt.ArrayLike, gravity: Optional[Sequence[float]] = None, threads: Optional[int] = None
) -> npt.NDArray[np.float64]:
    """g(q), the torques that hold the arm still; (dof,) or (N, dof)."""

def coriolis_torques(
    robot: Robot, q: npt.ArrayLike, v: npt.ArrayLike, threads: Optional[int] = None
) -> npt.NDArray[np.float64]:
    """C(q, v) v; (dof,) or (N, dof)."""

def kinetic_energy(
    robot: Robot, q: npt.ArrayLike, v: npt.ArrayLike, threads: Optional[int] = None
) -> Union[float, npt.NDArray[np.float64]]:
    """v' M(q) v / 2, J: a float, or (N,) for a batch."""
