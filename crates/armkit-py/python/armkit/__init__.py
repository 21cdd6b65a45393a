"""armkit: robot-manipulator kinematics, inverse kinematics, trajectories,
redundancy resolution and model-predictive planning, from Rust.

Conventions: SI units (m, rad, s, kg, N); poses are homogeneous (4, 4) arrays
in the world frame (the frame the robot's base transform is given in);
Jacobian and twist rows are ``[vx, vy, vz, wx, wy, wz]``; roll-pitch-yaw is
URDF's ``R = Rz(yaw) Ry(pitch) Rx(roll)``.

Arrays come in as any float array-like (lists, C- or Fortran-ordered or
strided NumPy arrays) and go out as new C-ordered float64 arrays. Calls on a
batch (``robot.fk(Q)`` with ``Q`` of shape (N, dof), ``robot.ik_batch``)
release the GIL and run on every core (``threads=`` to choose). Bad input
raises ``ValueError`` (``FileNotFoundError`` for a missing file) with the
library's message; a solver that did not converge reports it in its status.

>>> import armkit, numpy as np
>>> robot = armkit.Robot.builtin("ur5")
>>> T = robot.fk([0.1, -1.2, 1.0, -0.5, 1.5, 0.3])
>>> T.shape
(4, 4)
"""

import sys as _sys

from ._armkit import (
    Beam,
    ContinuousPath,
    IkResult,
    IkSolutions,
    MpcPlanner,
    Robot,
    SpaceRobot,
    Trajectory,
    __version__,
    builtin_robots,
    continuous_path,
    dynamics,
    redundancy,
    singularity,
    study,
)

from . import reach, view

# The extension's submodules, importable as `import armkit.redundancy`.
for _module in (dynamics, redundancy, singularity, study):
    _sys.modules[f"{__name__}.{_module.__name__}"] = _module
del _module, _sys

__all__ = [
    "Beam",
    "ContinuousPath",
    "IkResult",
    "IkSolutions",
    "MpcPlanner",
    "Robot",
    "SpaceRobot",
    "Trajectory",
    "__version__",
    "builtin_robots",
    "continuous_path",
    "dynamics",
    "reach",
    "view",
    "redundancy",
    "singularity",
    "study",
]
