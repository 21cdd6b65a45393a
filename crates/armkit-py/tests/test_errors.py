"""Every class of bad input raises ValueError (FileNotFoundError for a
missing file) with the library's message, naming the argument and what was
expected; a solver that does not converge is a status, not an exception."""

import re

import numpy as np
import pytest

import armkit
from conftest import DATA

ROBOT = armkit.Robot.builtin("ur5")
T = ROBOT.fk(np.zeros(6))
NOT_RIGID = np.diag([2.0, 1.0, 1.0, 1.0])

CASES = [
    # joint positions
    ("wrong length", lambda: ROBOT.fk([0.0] * 5), "joint_positions: expected 6 values, got 5"),
    ("NaN", lambda: ROBOT.fk([0, 0, np.nan, 0, 0, 0]), "joint_positions[2] is not finite (NaN)"),
    ("infinity in a batch row", lambda: ROBOT.fk(np.array([[0.0] * 6, [0, 0, 0, np.inf, 0, 0]])), "q[1]: joint_positions[3] is not finite (inf)"),
    ("NaN in a batched Jacobian", lambda: ROBOT.jacobian(np.array([[0.0] * 6] * 3 + [[np.nan] * 6])), "q[3]: joint_positions[0] is not finite (NaN)"),
    ("batch of the wrong width", lambda: ROBOT.fk(np.zeros((3, 5))), "q: expected an array of shape (N, 6), got shape (3, 5)"),
    ("three dimensions", lambda: ROBOT.jacobian(np.zeros((2, 3, 6))), "q: expected an array of shape (6,) or (N, 6), got shape (2, 3, 6)"),
    ("a scalar", lambda: ROBOT.fk(1.0), "q: expected an array of shape (6,) or (N, 6), got shape ()"),
    ("not numbers", lambda: ROBOT.fk("abc"), "q: expected an array of numbers: could not convert string to float: 'abc'"),
    ("a string in a list", lambda: ROBOT.fk([0, 0, "a", 0, 0, 0]), "q: expected an array of numbers: could not convert string to float: 'a'"),
    ("a list too short", lambda: ROBOT.jacobian((0.0, 1.0)), "joint_positions: expected 6 values, got 2"),
    ("ragged rows", lambda: ROBOT.fk([[0.0] * 6, [0.0] * 5]), "q: expected an array of numbers: setting an array element with a sequence"),
    ("outside the limits", lambda: ROBOT.check_limits([0, 0, 4.0, 0, 0, 0]), "joint 2 (`q3`) = 4 is outside its limits [-3.141592653589793, 3.141592653589793]"),
    ("unknown frame", lambda: ROBOT.jacobian(np.zeros(6), frame="tool"), 'invalid argument `frame`: expected "world" or "end-effector", got "tool"'),
    ("threads = 0", lambda: ROBOT.fk(np.zeros((3, 6)), threads=0), "invalid argument `threads`: must be >= 1 (or None for every core), got 0"),
    ("threads < 0", lambda: ROBOT.ik_batch(T[None], threads=-2), "invalid argument `threads`: must be >= 1 (or None for every core), got -2"),
    # robots and files
    ("unknown robot", lambda: armkit.Robot.builtin("nope"), "unknown robot `nope`; the built-in robots are: puma560, ur5"),
    ("unknown tip link", lambda: armkit.Robot.from_urdf(DATA / "urdf" / "ur5.urdf", tip="nolink"), "the tip link `nolink` does not exist; the links are: base_link"),
    ("empty base link", lambda: armkit.Robot.from_urdf(DATA / "urdf" / "ur5.urdf", base=" "), "invalid argument `base`: the link name is empty"),
    # IK options and targets
    ("unknown solver", lambda: ROBOT.ik(T, solver="magic"), "invalid argument `solver`: unknown IK solver `magic`; expected auto, analytic, lm, nr, dls or sri"),
    ("no analytic solver", lambda: armkit.Robot.builtin("gantry9").ik(T, solver="analytic"), "`gantry9` has no analytic solver: class other"),
    ("unknown representatives", lambda: ROBOT.ik_solutions(T, representatives="all"), 'invalid argument `representatives`: unknown value `all`; expected "nearest" or "every"'),
    ("negative tolerance", lambda: ROBOT.ik(T, position_tolerance=-1), "invalid argument `position_tolerance`: must be finite and > 0, got -1"),
    ("NaN tolerance", lambda: ROBOT.ik(T, orientation_tolerance=float("nan")), "invalid argument `orientation_tolerance`: must be finite and > 0, got NaN"),
    ("zero budget", lambda: ROBOT.ik(T, time_budget=0), "invalid argument `time_budget`: must be finite and > 0, got 0"),
    ("zero iterations", lambda: ROBOT.ik(T, max_iterations=0), "invalid argument `max_iterations`: must be >= 1"),
    ("three task weights", lambda: ROBOT.ik(T, task_weights=[1, 1, 1]), "task_weights: expected 6 values, got 3"),
    ("all weights zero", lambda: ROBOT.ik(T, task_weights=[0] * 6), "invalid argument `task_weights`: at least one task component must have a weight > 0"),
    ("target of the wrong shape", lambda: ROBOT.ik(np.eye(3)), "T: expected an array of shape (4, 4), got shape (3, 3)"),
    ("target's last row", lambda: ROBOT.ik(np.ones((4, 4))), "invalid argument `T`: last row must be [0, 0, 0, 1], got [1.0, 1.0, 1.0, 1.0]"),
    ("target not rigid", lambda: ROBOT.ik(NOT_RIGID), "invalid argument `T`: rotation block is not orthonormal"),
    ("target with NaN", lambda: ROBOT.ik(np.full((4, 4), np.nan)), "invalid argument `T`: has a non-finite entry"),
    ("start of the wrong length", lambda: ROBOT.ik(T, q0=[0.0] * 3), "joint_positions: expected 6 values, got 3"),
    ("targets of the wrong shape", lambda: ROBOT.ik_batch(np.zeros((3, 4))), "Ts: expected an array of shape (N, 4, 4), got shape (3, 4)"),
    ("one bad target in a batch", lambda: ROBOT.ik_batch(np.stack([T, T, NOT_RIGID])), "Ts[2]: invalid argument `T`: rotation block is not orthonormal"),
    ("starts of the wrong shape", lambda: ROBOT.ik_batch(np.stack([T, T]), q0=np.zeros((3, 6))), "q0: expected an array of shape (6,) or (2, 6), got shape (3, 6)"),
    ("NaN start in a batch", lambda: ROBOT.ik_batch(np.stack([T, T]), q0=[[0.0] * 6, [np.nan] * 6]), "Ts[1]: joint_positions[0] is not finite (NaN)"),
]


@pytest.mark.parametrize("name, call, message", CASES, ids=[c[0] for c in CASES])
def test_bad_input_raises_value_error_with_the_library_message(name, call, message):
    with pytest.raises(ValueError, match=re.escape(message)):
        call()


@pytest.mark.parametrize("load", [armkit.Robot.from_urdf, armkit.Robot.from_file])
def test_missing_file_raises_file_not_found(load, tmp_path):
    path = tmp_path / "missing.urdf"
    with pytest.raises(FileNotFoundError, match=re.escape(f"{path}: cannot read the file: No such file or directory")):
        load(path)


def test_malformed_urdf_names_the_line(tmp_path):
    path = tmp_path / "bad.urdf"
    path.write_text(
        "<robot name='x'>\n<link name='a'/>\n<joint name='j' type='revolute'><parent link='a'/><child link='b'/></joint>\n</robot>"
    )
    with pytest.raises(ValueError, match=re.escape(f"{path}: joint `j` (line 3): its child link `b` does not exist")):
        armkit.Robot.from_urdf(path)


def test_malformed_description_names_the_line_and_column(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text("name = 'x'\nconvention = 'standard'\n[[links]]\ntype = 'R'\nd = 'abc'\n")
    with pytest.raises(ValueError, match=re.escape(f"{path}: line 5, column 5 (`d = 'abc'`): invalid type: string \"abc\", expected f64")):
        armkit.Robot.from_file(path)


def test_unreachable_target_is_a_status_not_an_exception():
    far = T.copy()
    far[:3, 3] = [5.0, 0.0, 0.0]  # 5 m away: the UR5 reaches about 1 m
    result = ROBOT.ik(far, time_budget=0.002)
    assert result.status == "not_converged" and not result.converged
    assert result.position_error > 3.0
    assert result.solutions.shape == (0, 6)
    ROBOT.check_limits(result.q)  # the best effort is within the limits
    Q, converged = ROBOT.ik_batch(np.stack([T, far]), time_budget=None, max_restarts=20)
    assert converged.tolist() == [True, False]
    ROBOT.check_limits(Q[1])


@pytest.mark.parametrize(
    "call, what",
    [
        (lambda ur5: ur5.fk(np.zeros(6) + 1j), "complex"),
        (lambda ur5: ur5.jacobian(np.zeros(6, dtype=complex)), "complex"),
        (lambda ur5: ur5.fk(np.zeros(6, dtype=bool)), "bool"),
        (lambda ur5: ur5.fk([True, False, 0.0, 0.0, 0.0, 0.0]), "bool"),
    ],
)
def test_complex_and_bool_arrays_are_refused(call, what):
    ur5 = armkit.Robot.builtin("ur5")
    with pytest.raises(TypeError, match=f"got a {what} array"):
        call(ur5)


def test_a_ten_billion_value_request_is_refused_quickly():
    import time

    ur5 = armkit.Robot.builtin("ur5")
    huge = np.broadcast_to(np.zeros(6), (4_000_000_000, 6))  # 2.4e10 values, no memory
    start = time.monotonic()
    with pytest.raises(MemoryError, match="would hold 24000000000 values"):
        ur5.fk(huge)
    assert time.monotonic() - start < 1.0
