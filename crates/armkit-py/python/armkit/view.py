"""The robot in 3-D: the page ``armkit view`` writes (three.js inlined,
offline), with every link placed by armkit's forward kinematics.

>>> import armkit, numpy as np
>>> robot = armkit.Robot.builtin("puma560")
>>> view = robot.show([0.3, -0.5, -0.8, 0.1, 0.7, -0.2])
>>> t = np.linspace(0.0, 2.0, 50)
>>> Q = np.outer(t / 2.0, [1.0, -0.5, -0.5, 0.5, 0.5, 0.5])
>>> moving = armkit.view.animate(robot, t, Q)
>>> path = moving.save("puma.html")  # doctest: +SKIP
"""

from __future__ import annotations

import html as _html
from pathlib import Path
from typing import Any, Optional

from ._armkit import _view_page

__all__ = ["View", "animate", "show"]


class View:
    """One 3-D view: displayed inline by Jupyter (``_repr_html_``, the page
    in an iframe), written to a file by :meth:`save`."""

    def __init__(self, page: str) -> None:
        #: The whole HTML page.
        self.html = page

    def _repr_html_(self) -> str:
        # An iframe: the page's scripts run whatever the notebook's policy
        # for scripts in output cells.
        return (
            '<iframe srcdoc="%s" style="width:100%%;height:660px;border:0" '
            'title="armkit 3-D view"></iframe>' % _html.escape(self.html, quote=True)
        )

    def save(self, path: Any) -> Path:
        """Writes the page to ``path`` (UTF-8) and returns it as a ``Path``."""
        target = Path(path)
        target.write_text(self.html, encoding="utf-8")
        return target


def animate(robot: Any, t: Any, Q: Any, path: Optional[Any] = None) -> View:
    """``robot`` moving through the configurations ``Q`` (shape (N, dof), rad
    or m) at the times ``t`` (shape (N,), s, non-decreasing); ``path``
    (shape (M, 3), world frame, m), if given, is drawn as the path line
    instead of the end effector's."""
    return View(_view_page(robot, t, Q, path))


def show(robot: Any, q: Optional[Any] = None) -> View:
    """``robot`` at configuration ``q`` (default: the middle of each joint's
    range); the same as ``robot.show(q)``."""
    if q is None:
        q = robot.neutral_configuration()
    return View(_view_page(robot, [0.0], [list(q)], None))
