"""Singularity detection (seed 004)."""

from typing import Any, Dict

import numpy.typing as npt

from ._armkit import Robot

__all__ = ["classify"]

def classify(robot: Robot, q: npt.ArrayLike, tolerance: float = 1e-6) -> Dict[str, Any]:
    """``kinds`` (wrist, elbow, shoulder, unclassified; empty when regular),
    ``singular``, ``rank``, ``singular_values`` (largest first),
    ``determinant`` (6-DOF robots, else None) at ``q``."""
