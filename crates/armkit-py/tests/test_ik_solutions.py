"""Robot.ik_solutions: every analytic solution, each checked by forward
kinematics, the generating configuration among them, within the limits,
nearest q0 first; 7-joint arms by elbow angle or held joint; sweeps; the
retired searches; bad input raises ValueError naming the argument."""

import re

import numpy as np
import pytest

import armkit

from conftest import DATA

GENERAL_6R = """convention = "standard"
[[links]]
type = "R"
d = 0.3
a = 0.1
alpha = 0.7
[[links]]
type = "R"
d = 0.05
a = 0.4
alpha = -1.1
[[links]]
type = "R"
d = 0.1
a = 0.35
alpha = 0.9
[[links]]
type = "R"
d = 0.25
a = 0.05
alpha = -0.6
[[links]]
type = "R"
d = 0.02
a = 0.07
alpha = 1.2
[[links]]
type = "R"
d = 0.1
a = 0.03
alpha = 0.5
"""


def random_configurations(robot, count, seed):
    """`count` configurations uniform within the limits (a full turn where a
    joint has none)."""
    rng = np.random.default_rng(seed)
    lower = np.where(np.isfinite(robot.lower), robot.lower, -np.pi)
    upper = np.where(np.isfinite(robot.upper), robot.upper, np.pi)
    return lower + (upper - lower) * rng.random((count, robot.dof))


def wrapped(d):
    """Angle differences into [-pi, pi)."""
    return (d + np.pi) % (2 * np.pi) - np.pi


def pose_gap(robot, q, T):
    """Largest entry of |FK(q) - T| (rotation entries bound the angle)."""
    return np.max(np.abs(robot.fk(q) - T))


def contains(solutions, q, tolerance=1e-6):
    """True when some row of `solutions` equals `q` modulo 2 pi, to 1e-6 rad
    (the recovery tolerance of crates/armkit/tests/it/ik_analytic.rs: near a
    singularity, e.g. a nearly straight elbow, a pose exact to 1e-10 can sit
    1e-8 rad from the generating configuration)."""
    if len(solutions) == 0:
        return False
    return bool(np.min(np.max(np.abs(wrapped(solutions - q)), axis=1)) < tolerance)


def check_solutions(robot, result, T, q0):
    """Every exact solution reproduces T to 1e-10, all within the limits,
    exact ones first, each group sorted by Euclidean distance to q0, fields
    consistent."""
    k = len(result)
    assert result.q.shape == (k, robot.dof)
    assert result.exact.shape == (k,) and result.exact.dtype == np.bool_
    assert result.position_error.shape == (k,) and result.orientation_error.shape == (k,)
    assert result.fits == ["exact" if e else "approximate" for e in result.exact]
    for q, exact, position, orientation in zip(
        result.q, result.exact, result.position_error, result.orientation_error
    ):
        assert np.all(q >= robot.lower) and np.all(q <= robot.upper)
        if exact:
            assert pose_gap(robot, q, T) <= 1e-10
            assert position <= 1e-10 and orientation <= 1e-10
    # Exact ones first, each group sorted by distance.
    k_exact = int(result.exact.sum())
    assert result.exact[:k_exact].all() and not result.exact[k_exact:].any()
    distances = np.linalg.norm(result.q - q0, axis=1)
    for group in (distances[:k_exact], distances[k_exact:]):
        assert np.all(np.diff(group) >= -1e-12)


@pytest.mark.parametrize("name", ["ur5", "puma560"])
def test_every_solution_reproduces_the_pose_and_includes_the_generator(name):
    robot = armkit.Robot.builtin(name)
    configurations = random_configurations(robot, 50, seed=17)
    starts = random_configurations(robot, 50, seed=18)
    for q, q0 in zip(configurations, starts):
        T = robot.fk(q)
        result = robot.ik_solutions(T, q0=q0)
        check_solutions(robot, result, T, q0)
        # Branches out of reach stay as least-squares (approximate) answers.
        assert contains(result.q[result.exact], q), (q, result.q)
    assert result.arm_class == robot.arm_class()[0]


def test_ur5_has_eight_solutions_at_a_generic_pose():
    robot = armkit.Robot.builtin("ur5")
    q = np.array([0.3, -1.2, 1.4, -0.5, 1.2, 0.4])
    T = robot.fk(q)
    result = robot.ik_solutions(T, q0=q)
    assert result.arm_class == "three_parallel_2_3_4_intersecting_5_6"
    assert result.exact.all()
    # Each distinct solution once by default.
    branches = np.unique(np.round(wrapped(result.q), 6), axis=0)
    assert len(branches) == 8 and len(result) == 8
    # Joint ranges of +-2 pi: with every representative, each branch
    # appears with its 2 pi multiples.
    every = robot.ik_solutions(T, q0=q, representatives="every")
    assert len(np.unique(np.round(wrapped(every.q), 6), axis=0)) == 8
    assert len(every) > 8
    # Nearest first: the generating configuration itself.
    assert np.max(np.abs(result.q[0] - q)) < 1e-9


def test_panda_by_its_held_joint():
    robot = armkit.Robot.builtin("panda")
    name, description = robot.arm_class()
    assert "held" in description
    for q in random_configurations(robot, 20, seed=3):
        T = robot.fk(q)
        result = robot.ik_solutions(T, q0=q)
        check_solutions(robot, result, T, q)
        assert "held" in result.method
        assert contains(result.q[result.exact], q)
    # An explicit held joint, 0-based: joint 0 at q's value.
    result = robot.ik_solutions(T, q0=q, fixed_joint=0)
    assert "joint 0 (0-based)" in result.method
    check_solutions(robot, result, T, q)
    assert contains(result.q[result.exact], q)
    assert np.allclose(result.q[:, 0], q[0])


def iiwa14_urdf():
    path = DATA / "urdf" / "iiwa14.urdf"
    if not path.is_file():
        pytest.skip("tests/data/urdf/iiwa14.urdf not present")
    return path


def check_seven_joint_route(robot, seed):
    """Every solution checked; the generating configuration found (the
    redundancy parameter read from q0 = q); returns the last method."""
    for q in random_configurations(robot, 20, seed=seed):
        T = robot.fk(q)
        result = robot.ik_solutions(T, q0=q)
        check_solutions(robot, result, T, q)
        assert contains(result.q[result.exact], q)
    return result.method


def test_iiwa14_by_its_elbow_angle(tmp_path):
    # Joints 2 and 4 of the shipped URDF sit 0.436 mm off the axis (not an
    # exact spherical shoulder-elbow-wrist): without the offsets it is one,
    # solved at the elbow angle.
    text = (
        iiwa14_urdf()
        .read_text()
        .replace('xyz="-0.00043624 0 0.36"', 'xyz="0 0 0.36"')
        .replace('xyz="0.00043624 0 0.42"', 'xyz="0 0 0.42"')
    )
    path = tmp_path / "iiwa14-ideal.urdf"
    path.write_text(text)
    robot = armkit.Robot.from_urdf(path, base="base_link", tip="tool0")
    assert robot.dof == 7
    assert "elbow angle" in check_seven_joint_route(robot, seed=11)


def test_iiwa14_as_shipped_by_a_held_joint():
    robot = armkit.Robot.from_urdf(iiwa14_urdf(), base="base_link", tip="tool0")
    assert "held" in robot.arm_class()[1]
    assert "(0-based) held" in check_seven_joint_route(robot, seed=12)


def test_a_sweep_gives_more_solutions_than_one_value():
    robot = armkit.Robot.builtin("panda")
    q = random_configurations(robot, 1, seed=23)[0]
    T = robot.fk(q)
    single = robot.ik_solutions(T, q0=q)
    swept = robot.ik_solutions(T, q0=q, sweep=12)
    check_solutions(robot, swept, T, q)
    assert swept.exact.sum() > single.exact.sum() > 0
    # The held joint (named in `method`, 0-based) takes only the 12 sweep
    # values, cell midpoints of its range, and several of them.
    joint = int(re.search(r"joint (\d) \(0-based\) held", single.method).group(1))
    assert np.allclose(single.q[:, joint], q[joint])
    lower, upper = robot.lower[joint], robot.upper[joint]
    values = lower + (upper - lower) * (np.arange(12) + 0.5) / 12
    gaps = np.abs(swept.q[:, joint, None] - values[None, :]).min(axis=1)
    assert np.all(gaps < 1e-9)
    assert len(np.unique(np.round(swept.q[:, joint], 9))) >= 3


def test_general_6r_by_elimination_and_the_searches_retired(tmp_path):
    path = tmp_path / "general-6r.toml"
    path.write_text(GENERAL_6R)
    robot = armkit.Robot.from_file(path)
    name = robot.arm_class()[0]
    assert "general" in name
    q = np.array([0.4, -0.3, 0.8, 0.5, -0.6, 0.2])
    T = robot.fk(q)
    # The default: elimination, every solution exact and the generating one
    # among them.
    result = robot.ik_solutions(T, q0=q)
    assert result.arm_class == name
    assert "elimination" in result.method
    check_solutions(robot, result, T, q)
    assert contains(result.q[result.exact], q)
    # The retired 1-D searches: an error naming the value.
    with pytest.raises(ValueError, match='"1d" is retired'):
        robot.ik_solutions(T, search="1d")
    # The retired 2-D search: an error naming the value.
    with pytest.raises(ValueError, match="retired"):
        robot.ik_solutions(T, q0=q, search="2d")


def test_arm_class_names_a_class_without_solver():
    robot = armkit.Robot.builtin("gantry9")
    with pytest.raises(ValueError, match="no analytic solver"):
        robot.ik_solutions(robot.fk(robot.neutral_configuration()))


def test_arm4_by_its_closed_form():
    robot = armkit.Robot.builtin("arm4")
    q = random_configurations(robot, 1, seed=2)[0]
    T = robot.fk(q)
    result = robot.ik_solutions(T, q0=q)
    assert result.arm_class == "seed002_arm4"
    check_solutions(robot, result, T, q)
    assert contains(result.q[result.exact], q)


@pytest.mark.parametrize(
    "robot_name, arguments, match",
    [
        ("ur5", {"T": np.eye(4)[:3]}, "T"),
        ("ur5", {"T": np.diag([2.0, 1.0, 1.0, 1.0])}, "orthonormal"),
        ("ur5", {"T": np.full((4, 4), np.nan)}, "T"),
        ("ur5", {"q0": [0.0, np.nan, 0, 0, 0, 0]}, "q0"),
        ("ur5", {"q0": [0.0] * 5}, "q0"),
        ("ur5", {"search": "3d"}, "search"),
        ("ur5", {"fixed_joint": 1}, "fixed_joint"),
        ("ur5", {"parameter": 0.3}, "parameter"),
        ("ur5", {"sweep": 4}, "sweep"),
        ("panda", {"fixed_joint": 7}, "fixed_joint"),
        ("panda", {"fixed_joint": -1}, "fixed_joint"),
        ("panda", {"sweep": 0}, "sweep"),
        ("panda", {"parameter": float("nan")}, "parameter"),
    ],
)
def test_bad_input_raises_value_error_naming_the_argument(robot_name, arguments, match):
    robot = armkit.Robot.builtin(robot_name)
    arguments = dict(arguments)
    T = arguments.pop("T", robot.fk(robot.neutral_configuration()))
    with pytest.raises(ValueError, match=match):
        robot.ik_solutions(T, **arguments)
