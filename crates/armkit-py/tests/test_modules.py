"""Trajectories, redundancy, the continuous path, the MPC planner, the
beam, the space robot and singularity detection from Python, each checked
against an independent computation or the library's invariants."""

import re

import numpy as np
import pytest

import armkit
from armkit import redundancy, singularity

GANTRY_Q = np.array([3.0, 2.5, 1.0, 0.3, 0.4, -0.5, 0.2, 0.8, 0.1])
TWIST = np.array([0.1, 0.0, -0.05, 0.0, 0.0, 0.0])


def test_trapezoid_of_seed_004():
    traj = armkit.Trajectory.trapezoidal([0.0, 1.0], [1.6, -0.6], 20.0, 4.0)
    q, qd, qdd = traj.sample(10.0)
    np.testing.assert_allclose(q, [0.8, 0.2], atol=1e-12)
    np.testing.assert_allclose(qd, [1.6 / 16, -1.6 / 16], atol=1e-12)  # cruise: d / (T - ta)
    np.testing.assert_allclose(qdd, [0.0, 0.0], atol=1e-12)
    q, qd, _ = traj.sample(2.0)  # ramp: a t^2 / 2, a = d / (ta (T - ta))
    np.testing.assert_allclose(q[0], 0.5 * 1.6 / (4 * 16) * 4.0, atol=1e-12)
    assert traj.duration == 20.0 and traj.dof == 2


def test_sampling_an_array_of_times_equals_a_loop():
    traj = armkit.Trajectory.quintic([0.0, 0.5, -1.0], [1.0, 0.0, 1.0], 3.0)
    t = np.linspace(-0.5, 3.5, 41)
    Q, Qd, Qdd = traj.sample(t)
    assert Q.shape == (41, 3)
    for i, ti in enumerate(t):
        q, qd, qdd = traj.sample(ti)
        assert np.array_equal(Q[i], q) and np.array_equal(Qd[i], qd) and np.array_equal(Qdd[i], qdd)
    # Velocity is the derivative of position (central differences).
    h = 1e-6
    np.testing.assert_allclose(traj.sample(1.3)[1], (traj.sample(1.3 + h)[0] - traj.sample(1.3 - h)[0]) / (2 * h), atol=1e-7)


def test_spline_passes_through_its_points():
    times = [0.0, 1.0, 2.5, 4.0]
    points = np.array([[0.0, 1.0], [0.5, 0.5], [1.5, -0.2], [1.0, 0.0]])
    traj = armkit.Trajectory.spline(times, points)
    for t, p in zip(times, points):
        np.testing.assert_allclose(traj.sample(t)[0], p, atol=1e-12)
    np.testing.assert_allclose(traj.knots, times)


def test_minimum_time_respects_the_limits():
    traj = armkit.Trajectory.minimum_time([0.0, 0.0], [2.0, -1.0], [1.0, 1.0], [2.0, 2.0])
    _, Qd, Qdd = traj.sample(np.linspace(0, traj.duration, 2001))
    assert np.abs(Qd).max() <= 1.0 + 1e-9 and np.abs(Qdd).max() <= 2.0 + 1e-9
    assert traj.duration == pytest.approx(2.0 / 1.0 + 1.0 / 2.0)  # cruise-limited: d / v + v / a


def test_trajectory_bad_input():
    with pytest.raises(ValueError, match=re.escape("invalid argument `shape`")):
        armkit.Trajectory.minimum_time([0.0], [1.0], [1.0], [1.0], shape="sine")
    with pytest.raises(ValueError, match="duration"):
        armkit.Trajectory.cubic([0.0], [1.0], -1.0)
    with pytest.raises(ValueError, match=re.escape("v_start: expected 2 values, got 1")):
        armkit.Trajectory.cubic([0.0, 0.0], [1.0, 1.0], 1.0, v_start=[0.0])
    with pytest.raises(ValueError, match=re.escape("t[0] is not finite")):
        armkit.Trajectory.cubic([0.0], [1.0], 1.0).sample(np.nan)


def test_weighted_least_norm_realizes_the_twist_and_locks_joints():
    gantry = armkit.Robot.builtin("gantry9")
    J = gantry.jacobian(GANTRY_Q)
    weights = [100, 10, 10, 1, 1, 1, 1, 1, 1]
    q_dot = redundancy.weighted_least_norm(gantry, GANTRY_Q, TWIST, weights=weights)
    np.testing.assert_allclose(J @ q_dot, TWIST, atol=1e-10)
    # The closed form A^-1 J' (J A^-1 J')^-1 V.
    Ainv = np.diag(1.0 / np.array(weights, float))
    np.testing.assert_allclose(q_dot, Ainv @ J.T @ np.linalg.solve(J @ Ainv @ J.T, TWIST), atol=1e-10)
    locked = redundancy.weighted_least_norm(gantry, GANTRY_Q, TWIST, weights=[np.inf, 1, 1, 1, 1, 1, 1, 1, 1])
    assert locked[0] == 0.0
    np.testing.assert_allclose(J @ locked, TWIST, atol=1e-10)
    with pytest.raises(ValueError, match=re.escape("weight of joint 1 must be finite and > 0, got -1")):
        redundancy.weighted_least_norm(gantry, GANTRY_Q, TWIST, weights=[1, -1, 1, 1, 1, 1, 1, 1, 1])


def test_energy_optimal_distribution_spends_the_least_energy():
    """Seed 001: the energy-optimal distribution minimizes sum (tau_i q_dot_i)^2
    (each |tau_i| floored at 5 % of the largest, so that joints holding no
    load still count) among all distributions realizing the twist."""
    gantry = armkit.Robot.builtin("gantry9")
    q_dot, torques, energy = redundancy.energy_optimal(gantry, GANTRY_Q, TWIST, payload=50.0)
    np.testing.assert_allclose(gantry.jacobian(GANTRY_Q) @ q_dot, TWIST, atol=1e-10)
    np.testing.assert_allclose(torques, redundancy.joint_torques(gantry, GANTRY_Q, payload=50.0))
    assert energy == pytest.approx(redundancy.energy_measure(q_dot, torques))
    minimum_norm = redundancy.weighted_least_norm(gantry, GANTRY_Q, TWIST)
    assert energy < redundancy.energy_measure(minimum_norm, torques)
    # Any other solution of J q_dot = V (plus a null-space motion) costs more.
    floored = np.maximum(np.abs(torques), 0.05 * np.abs(torques).max())
    cost = lambda v: np.sum((floored * v) ** 2)
    J = gantry.jacobian(GANTRY_Q)
    null = np.linalg.svd(J)[2][6:].T
    rng = np.random.default_rng(0)
    for _ in range(20):
        other = q_dot + null @ rng.normal(scale=0.01, size=null.shape[1])
        np.testing.assert_allclose(J @ other, TWIST, atol=1e-10)
        assert cost(other) > cost(q_dot)


def test_continuous_path_of_seed_002_meets_its_tolerance():
    arm4 = armkit.Robot.builtin("arm4")
    q0 = arm4.neutral_configuration()
    goal = arm4.fk(q0 + 0.3)
    result = armkit.continuous_path(arm4, q0, goal, 2.0, tolerance=1e-4)
    assert result.status == "tolerance_met" and result.ik_method.startswith("seed 002")
    traj = result.trajectory
    assert result.configurations.shape == (len(traj.knots), 4)
    # FK of the joint trajectory follows the Cartesian path (position task
    # for a 4-DOF arm) at the knots exactly and between them within the
    # measured interior error.
    for t, q in zip(traj.knots, result.configurations):
        np.testing.assert_allclose(arm4.fk(q)[:3, 3], result.path_poses(t)[:3, 3], atol=1e-9)
    t = np.linspace(0.0, 2.0, 401)
    reached = arm4.fk(traj.sample(t)[0])[:, :3, 3]
    wanted = result.path_poses(t)[:, :3, 3]
    error = np.linalg.norm(reached - wanted, axis=1).max()
    assert error <= result.interior_position_error + 1e-12
    assert result.checked_position_error <= 1e-4


def test_mpc_reaches_the_target_within_the_limits():
    panda = armkit.Robot.builtin("panda")
    q = np.array([0.0, -0.3, 0.0, -2.2, 0.0, 2.0, 0.8])
    target = panda.fk(q)
    target[:3, 3] += [0.05, -0.05, 0.05]
    planner = armkit.MpcPlanner(panda, orientation=False)
    run = planner.run(target, q)
    assert run["converged"] and run["final_position_error"] < 1e-4
    assert run["max_velocity_violation"] == 0.0 and run["max_position_violation"] == 0.0
    np.testing.assert_allclose(panda.fk(run["q"][-1])[:3, 3], target[:3, 3], atol=1e-4)
    assert run["q"].shape == (len(run["time"]), 7)
    # Stepping by hand: integrate the commanded velocities (the plant).
    with pytest.raises(ValueError, match=re.escape("MpcPlanner.step: no target; call set_target(T) first")):
        planner.step(q)
    planner.set_target(target)
    for _ in range(100):
        step = planner.step(q)
        assert step["status"] == "solved"
        q = q + 0.05 * step["velocity"]
    assert planner.step(q)["position_error"] < 1e-4
    # Clarabel, seed 000's planner as printed (no reach aid), the same target.
    clarabel = armkit.MpcPlanner(panda, orientation=False, solver="clarabel", reach=False)
    assert clarabel.solver == "clarabel"
    run = clarabel.run(target, [0.0, -0.3, 0.0, -2.2, 0.0, 2.0, 0.8])
    assert run["converged"] and run["max_position_violation"] == 0.0
    with pytest.raises(ValueError, match=re.escape("invalid argument `solver`: unknown QP solver `cvx`")):
        armkit.MpcPlanner(panda, solver="cvx")
    # Actuators of limited precision (seed 000 Example 3's plant): rotary
    # axes resting only on 0.01 rad steps from the start.
    q0 = np.array([0.0, -0.3, 0.0, -2.2, 0.0, 2.0, 0.8])
    coarse = planner.run(target, q0, max_steps=200, rotary_resolution=0.01)
    steps = (coarse["q"] - q0) / 0.01
    np.testing.assert_allclose(steps, np.round(steps), atol=1e-9)
    assert np.abs(steps).max() >= 1.0  # the axes moved
    with pytest.raises(ValueError, match=re.escape("plant.rotary.deadband")):
        planner.run(target, q0, rotary_deadband=-1.0)



def test_mpc_strict_priority_moves_a_lower_level_only_for_what_remains():
    # Seed 000 sec 4.4 read as a strict priority on the Panda: joints 1-4
    # (weight 1) first, joints 5-7 (weight 10) only for what remains.
    panda = armkit.Robot.builtin("panda")
    q0 = np.array([0.0, -0.3, 0.0, -2.2, 0.0, 2.0, 0.8])
    target = panda.fk(q0)
    target[:3, 3] += [0.05, -0.05, 0.05]
    weights = [1.0] * 4 + [10.0] * 3
    strict = armkit.MpcPlanner(panda, orientation=False, increment_weights=weights, reach=False, priority="strict")
    weighted = armkit.MpcPlanner(panda, orientation=False, increment_weights=weights, reach=False)
    assert "strict priority" in strict.solver
    strict_run = strict.run(target, q0)
    weighted_run = weighted.run(target, q0)
    assert strict_run["converged"] and strict_run["max_velocity_violation"] == 0.0
    # The first step: the strict answer differs from the weighted one.
    strict.set_target(target)
    weighted.set_target(target)
    assert np.abs(strict.step(q0)["velocity"] - weighted.step(q0)["velocity"]).max() > 1e-6
    with pytest.raises(ValueError, match=re.escape("invalid argument `priority`: unknown priority mode `lexical`")):
        armkit.MpcPlanner(panda, priority="lexical")
    assert weighted_run["converged"]

def test_beam_deflection_is_the_textbook_one():
    E, I, L, P = 200e9, 0.2**4 / 12, 10.0, 4000.0
    beam = armkit.Beam(L, E, I)
    assert beam.deflection(L / 2, [[L / 2, P]]) == pytest.approx(P * L**3 / (48 * E * I), rel=1e-12)
    a, x = 3.0, 7.0  # load at a, deflection at x > a: P a (L - x) (2 L x - x^2 - a^2) / (6 E I L)
    assert beam.deflection(x, [[a, P]]) == pytest.approx(P * a * (L - x) * (2 * L * x - x**2 - a**2) / (6 * E * I * L), rel=1e-12)
    assert beam.slope(L / 2, [[L / 2, P]]) == pytest.approx(0.0, abs=1e-15)
    with pytest.raises(ValueError, match=re.escape("invalid argument `length`: must be finite and > 0, got -1")):
        armkit.Beam(-1.0, E, I)


def test_space_robot_base_reacts_as_its_mode_says():
    space = armkit.SpaceRobot.space6r()
    q = np.array([0.1, 0.5, -0.3, 0.2, 0.4, 0.1])
    rates = np.array([0.2, -0.1, 0.3, 0.1, -0.2, 0.1])
    base, q1 = space.step(q, rates, 0.01)
    np.testing.assert_allclose(q1, q + 0.01 * rates, atol=1e-12)
    np.testing.assert_allclose(base[:3, :3], np.eye(3), atol=1e-15)  # attitude held
    assert np.linalg.norm(base[:3, 3]) > 0  # the base moved
    base, _ = space.step(q, rates, 0.01, mode="free-floating")
    assert np.abs(base[:3, :3] - np.eye(3)).max() > 1e-9  # the base turned
    J = space.generalized_jacobian(q)
    assert J.shape == (6, 6)
    for dt, shown in [(0.0, "0"), (-0.01, "-0.01"), (1e300, "1e300"), (float("nan"), "NaN")]:
        with pytest.raises(ValueError, match=re.escape(f"invalid argument `dt`: must be > 0 and <= 1 s, got {shown} s")):
            space.step(q, rates, dt)
    with pytest.raises(ValueError, match=re.escape('invalid argument `mode`: expected "attitude-held" or "free-floating", got "fixed"')):
        space.generalized_jacobian(q, mode="fixed")


def test_singularity_classification():
    puma = armkit.Robot.builtin("puma560")
    wrist = singularity.classify(puma, [0.3, 0.5, -0.4, 0.2, 0.0, 0.1])
    assert wrist["kinds"] == ["wrist"] and wrist["rank"] == 5 and wrist["singular"]
    assert abs(wrist["determinant"]) < 1e-12
    regular = singularity.classify(puma, [0.3, 0.5, -0.4, 0.2, 0.7, 0.1])
    assert regular["kinds"] == [] and regular["rank"] == 6 and not regular["singular"]
    np.testing.assert_allclose(regular["singular_values"], np.linalg.svd(puma.jacobian([0.3, 0.5, -0.4, 0.2, 0.7, 0.1]), compute_uv=False))
    np.testing.assert_allclose(regular["determinant"], np.linalg.det(puma.jacobian([0.3, 0.5, -0.4, 0.2, 0.7, 0.1])), rtol=1e-9)


def test_seed_004_avoidance_crosses_the_wrist_singularity_slowly():
    arm = armkit.Robot.builtin("space6r")
    q_start, goal = singularity.line_through(arm, [0.4, 1.2, -0.5, 0.6, 0.0, -0.3], [0.5, -0.3, 0.4, 0.0, 0.8, 0.0])
    through = arm.fk([0.4, 1.2, -0.5, 0.6, 0.0, -0.3])
    start = arm.fk(q_start)
    np.testing.assert_allclose((start[:3, 3] + goal[:3, 3]) / 2, through[:3, 3], atol=1e-9)  # midpoint
    plain = singularity.track_line(arm, q_start, goal, method="plain")
    avoid = singularity.track_line(arm, q_start, goal, method="avoidance", k=5)
    assert plain["status"] == avoid["status"] == "completed"
    assert plain["peak_joint_rate"] > 10.0  # seed 004 Fig 5: the rates blow up
    assert avoid["peak_joint_rate"] < 0.1 and avoid["ik_solves"] > 0
    assert avoid["max_position_error"] < 1e-6
    assert np.abs(avoid["joint_rates"]).max() == pytest.approx(avoid["peak_joint_rate"])
    assert avoid["q"].shape == (len(avoid["time"]), 6) and avoid["in_region"].any()
    np.testing.assert_allclose(np.abs(plain["position_error"]).max(), plain["max_position_error"])
    # Plain tracking: each rate is held over one period (dt = 0.01 s).
    np.testing.assert_allclose(np.diff(plain["q"], axis=0), plain["joint_rates"][:-1] * 0.01, atol=1e-12)
    np.testing.assert_allclose(arm.fk(avoid["q"][-1]), goal, atol=1e-9)
    with pytest.raises(ValueError, match=re.escape("invalid argument `k`: the knot stride must be in 1..=1000000")):
        singularity.track_line(arm, q_start, goal, method="avoidance", k=0)
    # Seed 004's rule by default: the largest |det J| where the plain run's
    # joints jump by more than eps_dq in one period; a given threshold is kept.
    jumps = (np.abs(plain["joint_rates"]) * 0.01 > 0.005).any(axis=1)
    assert avoid["threshold_rule"] == "calibrated"
    assert avoid["determinant_threshold"] == pytest.approx(plain["determinant"][jumps].max(), rel=1e-12)
    given = singularity.track_line(arm, q_start, goal, method="avoidance", determinant_threshold=0.004)
    assert (given["threshold_rule"], given["determinant_threshold"]) == ("given", 0.004)
    assert given["time_in_singular_region"] > avoid["time_in_singular_region"]


def test_near_miss_lines_joint_region_plan_and_clamped_dls():
    # A line missing the singular pose by 3 mm (the study's sweep): the
    # region's knots cannot all be reached; planning them together errs no
    # more than knot by knot, and the clamped DLS keeps the speed limit.
    arm = armkit.Robot.builtin("space6r")
    through, direction = [0.4, 1.2, -0.5, 0.6, 0.0, -0.3], [0.5, -0.3, 0.4, 0.0, 0.8, 0.0]
    on_line, _ = singularity.line_through(arm, through, direction)
    q_start, goal = singularity.line_through(arm, through, direction, miss=0.003)
    assert np.abs(q_start - on_line).max() > 1e-6  # the line moved
    joint = singularity.track_line(arm, q_start, goal, region_plan="joint")
    greedy = singularity.track_line(arm, q_start, goal, region_plan="greedy")
    assert joint["max_position_error"] <= greedy["max_position_error"] + 1e-12
    assert joint["max_position_error"] < greedy["max_position_error"]  # the sweep: 2.7 vs 5.0 mm
    clamped = singularity.track_line(arm, q_start, goal, method="dls_clamped", max_rate=0.5)
    dls = singularity.track_line(arm, q_start, goal, method="dls")
    assert dls["peak_joint_rate"] > 0.5 >= clamped["peak_joint_rate"] - 1e-12
    with pytest.raises(ValueError, match="region_plan"):
        singularity.track_line(arm, q_start, goal, region_plan="together")
    with pytest.raises(ValueError, match="max_rate"):
        singularity.track_line(arm, q_start, goal, method="dls_clamped", max_rate=0.0)


def test_as_printed_exact_knots_and_open_loop_tracking():
    # Seed 004's knots as printed (exact Newton solutions, no rate bound) on
    # the 3 mm near miss: far smaller error than the rate-bounded joint plan,
    # at wrist rates beyond its 0.5 rad/s. Open loop (V = V_d) lets the
    # error grow where next-pose feedback corrects it each period.
    arm = armkit.Robot.builtin("space6r")
    through, direction = [0.4, 1.2, -0.5, 0.6, 0.0, -0.3], [0.5, -0.3, 0.4, 0.0, 0.8, 0.0]
    q_start, goal = singularity.line_through(arm, through, direction, miss=0.003)
    exact = singularity.track_line(arm, q_start, goal, k=1, region_plan="exact")
    joint = singularity.track_line(arm, q_start, goal, k=1, region_plan="joint")
    assert exact["peak_joint_rate"] > 0.5 >= joint["peak_joint_rate"] - 1e-12
    assert exact["max_position_error"] < 1e-2 * joint["max_position_error"]
    q_far, goal_far = singularity.line_through(arm, through, direction, miss=0.03)
    open_loop = singularity.track_line(arm, q_far, goal_far, method="plain", feedback="open-loop")
    closed = singularity.track_line(arm, q_far, goal_far, method="plain", feedback="next-pose")
    assert open_loop["final_position_error"] > 100 * max(closed["final_position_error"], 1e-12)
    with pytest.raises(ValueError, match="feedback"):
        singularity.track_line(arm, q_start, goal, feedback="closed")


def test_the_reference_method_separation_by_name():
    # Seed 004's reference [9]: singularity separation with a damped
    # reciprocal, selected by name; it crosses the wrist singularity with
    # bounded rates where plain tracking blows up, and refuses other names.
    arm = armkit.Robot.builtin("space6r")
    q_start, goal = singularity.line_through(arm, [0.4, 1.2, -0.5, 0.6, 0.0, -0.3], [0.5, -0.3, 0.4, 0.0, 0.8, 0.0])
    plain = singularity.track_line(arm, q_start, goal, method="plain")
    separation = singularity.track_line(arm, q_start, goal, method="separation")
    assert separation["status"] == "completed"
    assert separation["peak_joint_rate"] < plain["peak_joint_rate"]
    with pytest.raises(ValueError, match="separation"):
        singularity.track_line(arm, q_start, goal, method="separated")
