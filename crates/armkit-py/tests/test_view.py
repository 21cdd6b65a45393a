"""robot.show and armkit.view.animate: the page armkit writes, with every
link placed by armkit's FK (its JSON holds the link poses; checked here
against robot.fk at the end effector), shown inline by Jupyter and saved."""

import json
import re

import numpy as np
import pytest

import armkit
from conftest import data_file


def scene_of(page):
    found = re.search(r'<script type="application/json" id="armkit-view-0-scene">(.*?)</script>', page, re.S)
    assert found, "no scene in the page"
    return json.loads(found.group(1).replace("<\\/", "</"))


def pose_matrix(p):
    x, y, z, qx, qy, qz, qw = p
    R = np.array([
        [1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qz * qw), 2 * (qx * qz + qy * qw)],
        [2 * (qx * qy + qz * qw), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qx * qw)],
        [2 * (qx * qz - qy * qw), 2 * (qy * qz + qx * qw), 1 - 2 * (qx * qx + qy * qy)],
    ])
    T = np.eye(4)
    T[:3, :3] = R
    T[:3, 3] = [x, y, z]
    return T


def test_show_places_the_end_effector_at_armkit_fk_and_saves(tmp_path):
    robot = armkit.Robot.builtin("puma560")
    q = [0.3, -0.5, -0.8, 0.1, 0.7, -0.2]
    view = robot.show(q)
    scene = scene_of(view.html)
    assert scene["joints"] == robot.joint_names
    end = pose_matrix(scene["poses"][0][-1])
    assert np.allclose(end, robot.fk(q), atol=1e-9)
    shown = view._repr_html_()
    assert shown.startswith("<iframe srcdoc=") and "&lt;script" in shown
    saved = view.save(tmp_path / "puma.html")
    assert saved.read_text(encoding="utf-8") == view.html
    assert "src=\"http" not in view.html


def test_animate_frames_path_and_errors():
    robot = armkit.Robot.builtin("ur5")
    t = np.linspace(0.0, 1.0, 11)
    Q = np.outer(t, [0.5, -0.3, 0.4, 0.2, -0.1, 0.6])
    view = armkit.view.animate(robot, t, Q, path=[[0.1, 0.2, 0.3], [0.2, 0.2, 0.3]])
    scene = scene_of(view.html)
    assert len(scene["times"]) == 11 and scene["path"] == [[0.1, 0.2, 0.3], [0.2, 0.2, 0.3]]
    for k in (0, 5, 10):
        assert np.allclose(pose_matrix(scene["poses"][k][-1]), robot.fk(Q[k]), atol=1e-9)
    with pytest.raises(ValueError, match="t has 3 times but Q has 11 rows"):
        armkit.view.animate(robot, t[:3], Q)
    with pytest.raises(ValueError, match="Q"):
        armkit.view.animate(robot, t, Q[:, :4])
    with pytest.raises(ValueError, match="non-decreasing"):
        armkit.view.animate(robot, t[::-1], Q)


def test_urdf_robots_show_their_meshes():
    urdf = data_file("urdf/meshbot/meshbot.urdf")
    robot = armkit.Robot.from_urdf(str(urdf), tip="tool")
    scene = scene_of(robot.show().html)
    # The relative mesh paths resolve beside the URDF; package://meshbot
    # resolves in the folders above it.
    assert len(scene["meshes"]) == 4
    assert [l["name"] for l in scene["links"]][:2] == ["base_link", "shoulder"]
