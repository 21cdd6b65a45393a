"""IK results verified by forward kinematics, within the joint limits;
closed-form solutions all reproduce the target; batched equals looped."""

import numpy as np
import pytest

import armkit


def pose_errors(robot, q, T):
    """Position (m) and orientation (rad) error of FK(q) from T."""
    reached = robot.fk(q)
    position = np.linalg.norm(reached[:3, 3] - T[:3, 3])
    R = T[:3, :3] @ reached[:3, :3].T
    angle = np.arccos(np.clip((np.trace(R) - 1) / 2, -1.0, 1.0))
    return position, angle


def within_limits(robot, q):
    return np.all(q >= robot.lower) and np.all(q <= robot.upper)


@pytest.mark.parametrize("name", ["ur5", "panda", "gantry9", "stanford"])
def test_numeric_ik_reaches_targets_checked_by_fk(name):
    robot = armkit.Robot.builtin(name)
    _, Ts = robot.benchmark_targets(20, seed=5)
    for T in Ts:
        # No time budget: a loaded machine cannot cut a solve short.
        result = robot.ik(T, solver="lm", time_budget=None)
        assert result.converged and result.status == "converged" and result.solver == "lm"
        position, angle = pose_errors(robot, result.q, T)
        assert position <= 1e-6 and angle <= 1e-6
        assert result.position_error <= 1e-6 and result.orientation_error <= 1e-6
        assert abs(position - result.position_error) < 1e-9
        assert within_limits(robot, result.q)
        assert np.array_equal(result.solutions, result.q[None])


def test_closed_form_gives_every_solution_each_checked_by_fk():
    robot = armkit.Robot.builtin("puma560")
    q = np.array([0.3, 0.6, -1.9, 0.4, 0.8, -0.5])
    T = robot.fk(q)
    result = robot.ik(T, q0=q, solver="closed-form")  # an alias of "analytic"
    assert result.solver == "analytic" and result.converged
    np.testing.assert_allclose(result.q, q, atol=1e-9)  # nearest the start first
    assert result.solutions.shape[0] >= 2
    for solution in result.solutions:
        position, angle = pose_errors(robot, solution, T)
        assert position < 1e-10 and angle < 1e-7
        assert within_limits(robot, solution)
    automatic = robot.ik(T, q0=q)  # auto: analytic for a PUMA
    assert automatic.solver == "analytic" and automatic.converged
    np.testing.assert_allclose(robot.fk(automatic.q), T, atol=1e-9)


@pytest.mark.parametrize("solver", ["nr", "dls", "sri"])
def test_other_numeric_solvers_report_honestly(solver):
    robot = armkit.Robot.builtin("ur5")
    _, Ts = robot.benchmark_targets(5, seed=1)
    for T in Ts:
        result = robot.ik(T, solver=solver, time_budget=0.02)
        position, angle = pose_errors(robot, result.q, T)
        if result.converged:
            assert position <= 1e-6 and angle <= 1e-6
        else:
            assert max(result.position_error, result.orientation_error) > 1e-6
        assert within_limits(robot, result.q)


def test_position_only_task_weights():
    robot = armkit.Robot.builtin("panda")
    _, Ts = robot.benchmark_targets(5, seed=9)
    for T in Ts:
        # LM: the analytic route of auto solves the whole pose.
        result = robot.ik(T, solver="lm", task_weights=[1, 1, 1, 0, 0, 0], time_budget=None)
        assert result.converged and result.orientation_error == 0.0
        assert np.linalg.norm(robot.fk(result.q)[:3, 3] - T[:3, 3]) <= 1e-6


def test_ik_batch_on_ur5_converges_everywhere_and_equals_looped():
    robot = armkit.Robot.builtin("ur5")
    _, Ts = robot.benchmark_targets(300, seed=42)
    # No time budget: every solve is a deterministic function of its inputs.
    options = dict(time_budget=None, max_restarts=200)
    Q, converged = robot.ik_batch(Ts, **options)
    assert Q.shape == (300, 6) and converged.shape == (300,) and converged.dtype == bool
    assert converged.all()
    reached = robot.fk(Q)
    assert np.abs(reached[:, :3, 3] - Ts[:, :3, 3]).max() <= 1e-6
    assert np.all(Q >= robot.lower) and np.all(Q <= robot.upper)
    looped = np.array([robot.ik(T, **options).q for T in Ts[:40]])
    assert np.array_equal(Q[:40], looped)
    Q1, _ = robot.ik_batch(Ts[:40], threads=1, **options)
    Q3, _ = robot.ik_batch(Ts[:40], threads=3, **options)
    assert np.array_equal(Q1, Q[:40]) and np.array_equal(Q3, Q[:40])


def test_ik_batch_with_one_start_per_target_stays_near_it():
    robot = armkit.Robot.builtin("ur5")
    Q0, Ts = robot.benchmark_targets(50, seed=3)
    Q, converged = robot.ik_batch(Ts, q0=Q0, time_budget=None)
    assert converged.all()
    # Started at the answer, the solver stays there.
    np.testing.assert_allclose(Q, Q0, atol=1e-6)
    Q, converged = robot.ik_batch(Ts, q0=robot.neutral_configuration(), time_budget=None)
    assert converged.all()


def test_changing_options_between_calls_gives_what_a_fresh_robot_gives():
    """Robot.ik reuses its solver while the options stay the same."""
    robot = armkit.Robot.builtin("panda")
    _, Ts = robot.benchmark_targets(6, seed=4)
    # No time budget: every answer is a deterministic function of the inputs.
    options = [dict(), dict(task_weights=[1, 1, 1, 0, 0, 0]), dict(solver="dls", max_restarts=5), dict(seed=3)]
    for T in Ts:
        for kwargs in options:
            reused = robot.ik(T, time_budget=None, **kwargs)
            fresh = armkit.Robot.builtin("panda").ik(T, time_budget=None, **kwargs)
            assert reused.status == fresh.status and reused.solver == fresh.solver
            assert np.array_equal(reused.q, fresh.q)


@pytest.mark.parametrize("name", ["ur5", "panda", "puma560", "stanford"])
def test_auto_solver_reaches_targets_checked_by_fk(name):
    robot = armkit.Robot.builtin(name)
    _, Ts = robot.benchmark_targets(30, seed=8)
    Q, converged = robot.ik_batch(Ts, time_budget=None)
    assert converged.all()
    assert np.abs(robot.fk(Q) - Ts).max() <= 2e-6
    assert np.all(Q >= robot.lower) and np.all(Q <= robot.upper)


# The names of ``armkit ik --solver`` (the CLI's test checks its list against
# the library's ``SolverName::ALL``, which this message is built from).
SOLVER_NAMES = ["auto", "analytic", "lm", "nr", "dls", "sri"]


def test_solver_names_are_the_cli_vocabulary():
    robot = armkit.Robot.builtin("ur5")
    q = np.array([0.4, -1.1, 1.3, -0.6, 1.4, 0.2])
    T = robot.fk(q)
    for name in SOLVER_NAMES + ["closed-form"]:
        result = robot.ik(T, q0=q, solver=name, time_budget=None)
        assert result.converged, name
    with pytest.raises(ValueError, match="expected " + ", ".join(SOLVER_NAMES[:-1]) + " or " + SOLVER_NAMES[-1]):
        robot.ik(T, solver="magic")


def test_solutions_hold_every_distinct_analytic_solution():
    robot = armkit.Robot.builtin("ur5")
    q = np.array([0.4, -1.1, 1.3, -0.6, 1.4, 0.2])
    T = robot.fk(q)
    for solver in ["auto", "analytic"]:
        result = robot.ik(T, q0=q, solver=solver)
        assert result.converged and result.solutions.shape == (8, 6), solver
        np.testing.assert_allclose(result.q, q, atol=1e-9)
        wrapped = np.angle(np.exp(1j * result.solutions))
        for i in range(8):
            for j in range(i):
                assert np.abs(np.angle(np.exp(1j * (wrapped[i] - wrapped[j])))).max() > 1e-6
        for solution in result.solutions:
            np.testing.assert_allclose(robot.fk(solution), T, atol=1e-9)
    distinct = robot.ik_solutions(T, q0=q)
    every = robot.ik_solutions(T, q0=q, representatives="every")
    assert len(distinct) == 8 and len(every) >= 8 * 16
