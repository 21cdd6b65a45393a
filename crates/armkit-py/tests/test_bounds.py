"""Counts and periods have documented ranges checked before any work; a
request too large for memory is refused quickly with the size it needs;
values of the wrong type name the keyword the caller wrote."""

import re
import time

import numpy as np
import pytest

import armkit
from armkit import singularity, study


def seed_004_line():
    arm = armkit.Robot.builtin("space6r")
    q_start, goal = singularity.line_through(arm, [0.4, 1.2, -0.5, 0.6, 0.0, -0.3], [0.5, -0.3, 0.4, 0.0, 0.8, 0.0])
    return arm, q_start, goal


@pytest.mark.parametrize(
    "dt, duration, shown",
    [
        (1e-12, 20.0, "duration 20 s / dt 1e-12 s = 2e13 control periods"),  # 2e13 samples: far beyond memory
        (2e-9, 20.0, "duration 20 s / dt 2e-9 s = 1e10 control periods"),  # the 10^10-element request
        (0.01, 1e300, "duration 1e300 s / dt 0.01 s = 1e302 control periods"),
    ],
)
def test_track_line_refuses_more_periods_than_a_run_takes(dt, duration, shown):
    arm, q_start, goal = seed_004_line()
    start = time.monotonic()
    with pytest.raises(ValueError, match=re.escape(f"invalid argument `dt`: {shown}: at most 1000000 (a run records every period: ")):
        singularity.track_line(arm, q_start, goal, method="plain", duration=duration, acceleration_time=4.0, dt=dt)
    assert time.monotonic() - start < 1.0


def test_track_line_refuses_an_unbounded_knot_stride():
    arm, q_start, goal = seed_004_line()
    with pytest.raises(ValueError, match=re.escape("invalid argument `k`: the knot stride must be in 1..=1000000")):
        singularity.track_line(arm, q_start, goal, method="avoidance", k=10**7)


def test_a_ten_billion_row_batch_is_refused_quickly():
    ur5 = armkit.Robot.builtin("ur5")
    rows = 10**10 // 6 + 1  # 10^10 values, broadcast: no memory behind them
    huge = np.broadcast_to(np.zeros(6), (rows, 6))
    for call in (ur5.fk, ur5.jacobian):
        start = time.monotonic()
        with pytest.raises(MemoryError, match=re.escape(f"would hold {rows * 6} values")):
            call(huge)
        assert time.monotonic() - start < 1.0


def test_study_option_of_the_wrong_type_names_the_keyword():
    with pytest.raises(ValueError, match=re.escape('invalid argument `payload`: study `distribution`: invalid type: string "heavy", expected f64')):
        study.run("distribution", payload="heavy")
    for bad in (float("nan"), float("inf"), [1.0, float("-inf")]):
        with pytest.raises(ValueError, match=re.escape("invalid argument `payload`: study `distribution`: must be finite: NaN and infinities are refused")):
            study.run("distribution", payload=bad)
    with pytest.raises(ValueError, match=re.escape('invalid argument `mass`: study `beam-table`: invalid type: sequence, expected f64')):
        study.run("beam-table", gravity=10.0, mass=[1, 2])


def test_space_robot_study_refuses_a_picosecond_step():
    with pytest.raises(ValueError, match=re.escape("invalid argument `dt`: duration 10 s / dt 1e-12 s = 1e13 control periods: at most 1000000")):
        study.run("space-robot", dt=1e-12, duration=10.0)


@pytest.mark.parametrize("duration, shown", [(1e-300, "1e-300"), (1e300, "1e300"), (0.0, "0"), (float("nan"), "NaN")])
def test_profiles_refuse_a_duration_outside_their_range(duration, shown):
    message = f"invalid argument `duration`: must be in [0.001, 1e6] s, got {shown} s"
    for make in (
        lambda: armkit.Trajectory.cubic([0.0], [1.0], duration),
        lambda: armkit.Trajectory.quintic([0.0], [1.0], duration),
        lambda: armkit.Trajectory.trapezoidal([0.0], [1.0], duration, 1e-4),
    ):
        with pytest.raises(ValueError, match=re.escape(message)):
            make()
