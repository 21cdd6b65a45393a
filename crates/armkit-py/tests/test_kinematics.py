"""FK and Jacobian against the reference data (Robotics Toolbox for the DH
robots, Pinocchio for the URDF ones) at 1e-12 / 1e-9, one call at a time and
batched; batched equals looped; every input layout gives the same answer."""

import numpy as np
import pytest

import armkit
from conftest import DATA, data_file, reference

POSE_TOLERANCE = 1e-12
JACOBIAN_TOLERANCE = 1e-9
BATCHED_TOLERANCE = 1e-14

BUILTIN = [
    ("puma560", "reference_puma560_dh.json"),
    ("ur5", "reference_ur5_dh.json"),
    ("stanford", "reference_stanford_dh.json"),
    ("panda", "reference_panda_mdh_rtb.json"),
]
URDF = [
    ("panda.urdf", "panda_link0", "panda_link8", "reference_panda.json"),
    ("ur5.urdf", "base_link", "tool0", "reference_ur5.json"),
    ("iiwa14.urdf", "base_link", "tool0", "reference_iiwa14.json"),
]


def robots_with_references():
    for name, ref in BUILTIN:
        yield pytest.param(lambda name=name: armkit.Robot.builtin(name), ref, id=f"builtin-{name}")
        yield pytest.param(
            lambda ref=ref: armkit.Robot.from_file(data_file(ref)), ref, id=f"file-{ref}"
        )
    for urdf, base, tip, ref in URDF:
        yield pytest.param(
            lambda urdf=urdf, base=base, tip=tip: armkit.Robot.from_urdf(DATA / "urdf" / urdf, base=base, tip=tip),
            ref,
            id=f"urdf-{urdf}",
        )


@pytest.mark.parametrize("make_robot, ref_name", list(robots_with_references()))
def test_fk_and_jacobian_equal_the_reference(make_robot, ref_name):
    robot = make_robot()
    ref = reference(ref_name)
    assert robot.dof == ref["dof"]
    for q, pose, jac in zip(ref["Q"], ref["poses"], ref["jacobians"]):
        np.testing.assert_allclose(robot.fk(q), pose, rtol=0, atol=POSE_TOLERANCE)
        np.testing.assert_allclose(robot.jacobian(q), jac, rtol=0, atol=JACOBIAN_TOLERANCE)
    np.testing.assert_allclose(robot.fk(ref["Q"]), ref["poses"], rtol=0, atol=POSE_TOLERANCE)
    np.testing.assert_allclose(robot.jacobian(ref["Q"]), ref["jacobians"], rtol=0, atol=JACOBIAN_TOLERANCE)


def test_batched_equals_looped_on_every_thread_count(ur5):
    rng = np.random.default_rng(7)
    Q = rng.uniform(ur5.lower, ur5.upper, (5000, ur5.dof))
    looped_T = np.array([ur5.fk(q) for q in Q])
    looped_J = np.array([ur5.jacobian(q) for q in Q])
    looped_Je = np.array([ur5.jacobian(q, frame="end-effector") for q in Q])
    for threads in (None, 1, 2, 3):
        for batched, looped in [
            (ur5.fk(Q, threads=threads), looped_T),
            (ur5.jacobian(Q, threads=threads), looped_J),
            (ur5.jacobian(Q, frame="end-effector", threads=threads), looped_Je),
        ]:
            assert batched.shape == looped.shape
            np.testing.assert_allclose(batched, looped, rtol=0, atol=BATCHED_TOLERANCE)


def test_end_effector_jacobian_is_the_world_one_in_tool_axes(ur5):
    q = np.array([0.3, -1.1, 1.2, -0.4, 1.3, 0.2])
    R = ur5.fk(q)[:3, :3]
    J = ur5.jacobian(q)
    Je = ur5.jacobian(q, frame="end-effector")
    np.testing.assert_allclose(Je[:3], R.T @ J[:3], atol=1e-14)
    np.testing.assert_allclose(Je[3:], R.T @ J[3:], atol=1e-14)


def test_jacobian_equals_finite_differences_of_fk():
    robot = armkit.Robot.builtin("gantry9")
    q = robot.neutral_configuration() + 0.1
    J = robot.jacobian(q)
    h = 1e-6
    T = robot.fk(q)
    for j in range(robot.dof):
        dq = np.zeros(robot.dof)
        dq[j] = h
        Tp, Tm = robot.fk(q + dq), robot.fk(q - dq)
        np.testing.assert_allclose(J[:3, j], (Tp[:3, 3] - Tm[:3, 3]) / (2 * h), atol=1e-8)
        dR = (Tp[:3, :3] - Tm[:3, :3]) / (2 * h) @ T[:3, :3].T  # skew(omega)
        np.testing.assert_allclose(J[3:, j], [dR[2, 1], dR[0, 2], dR[1, 0]], atol=1e-8)


def test_every_input_layout_gives_the_same_result(ur5):
    rng = np.random.default_rng(3)
    Q = rng.uniform(-2, 2, (64, 6))
    expected = ur5.fk(Q)
    layouts = {
        "list": Q.tolist(),
        "fortran": np.asfortranarray(Q),
        "strided rows": np.repeat(Q, 2, axis=0)[::2],
        "strided columns": np.repeat(Q, 3, axis=1)[:, ::3],
        "transposed view": np.ascontiguousarray(Q.T).T,
        "big-endian": Q.astype(">f8"),
        "negative stride": Q[::-1][::-1],
    }
    for name, Qx in layouts.items():
        assert np.array_equal(ur5.fk(Qx), expected), name
        assert np.array_equal(ur5.jacobian(Qx), ur5.jacobian(Q)), name
    q = Q[5]
    single = ur5.fk(q)
    np.testing.assert_allclose(single, expected[5], rtol=0, atol=BATCHED_TOLERANCE)
    for name, qx in {
        "list": q.tolist(),
        "tuple": tuple(q),
        "strided": np.repeat(q, 2)[::2],
        "reversed twice": q[::-1][::-1],
        "column of a Fortran array": np.asfortranarray(Q)[5],
    }.items():
        assert np.array_equal(ur5.fk(qx), single), name
    # Lists mixing Python ints, floats and NumPy scalars.
    mixed = [int(round(v)) for v in q[:3]] + [np.float64(q[3]), np.int64(round(q[4])), float(q[5])]
    assert np.array_equal(ur5.fk(mixed), ur5.fk(np.array(mixed, dtype=float)))
    # float32 and integers are numbers too: converted to float64 first.
    Q32 = Q.astype(np.float32)
    assert np.array_equal(ur5.fk(Q32), ur5.fk(Q32.astype(np.float64)))
    assert np.array_equal(ur5.fk([0, 1, 0, 1, 0, 1]), ur5.fk([0.0, 1.0, 0.0, 1.0, 0.0, 1.0]))


def test_results_are_new_c_ordered_arrays(ur5):
    q = np.zeros(6)
    T1, T2 = ur5.fk(q), ur5.fk(q)
    assert T1.flags.c_contiguous and T1.dtype == np.float64 and T1.shape == (4, 4)
    T1[0, 0] = 42.0
    assert T2[0, 0] != 42.0
    assert ur5.fk(np.zeros((0, 6))).shape == (0, 4, 4)
    assert ur5.jacobian(np.zeros((3, 6))).shape == (3, 6, 6)


def test_model_properties():
    robot = armkit.Robot.builtin("panda")
    assert robot.dof == 7 and robot.name == "panda"
    assert len(robot.joint_names) == 7
    assert robot.lower.shape == robot.upper.shape == (7,)
    assert np.all(robot.lower < robot.upper)
    np.testing.assert_allclose(robot.neutral_configuration(), (robot.lower + robot.upper) / 2)
    assert "ur5" in armkit.builtin_robots() and "gantry9" in armkit.builtin_robots()
    urdf = armkit.Robot.from_urdf(DATA / "urdf" / "panda.urdf", tip="panda_link8")
    assert urdf.joint_names[0] == "panda_joint1"
    assert repr(urdf) == "Robot('panda', dof=7)"


def test_mimic_joints_follow_their_leaders():
    """A URDF chain with mimic joints: dof counts the independent joints;
    the Jacobian (J = J0 M) equals finite differences of FK; IK and batches work."""
    robot = armkit.Robot.from_urdf(DATA / "urdf" / "mimicbot.urdf", tip="fingertip")
    assert robot.dof == 7 and robot.joint_names[-1] == "knuckle"
    q = robot.neutral_configuration() + 0.05
    J = robot.jacobian(q)
    h = 1e-6
    for j in range(robot.dof):
        dq = np.zeros(robot.dof)
        dq[j] = h
        np.testing.assert_allclose(J[:3, j], (robot.fk(q + dq)[:3, 3] - robot.fk(q - dq)[:3, 3]) / (2 * h), atol=1e-8)
    Q = np.random.default_rng(2).uniform(np.maximum(robot.lower, -3), np.minimum(robot.upper, 3), (200, 7))
    looped = np.array([robot.fk(x) for x in Q])
    np.testing.assert_allclose(robot.fk(Q), looped, rtol=0, atol=BATCHED_TOLERANCE)
    goal = robot.fk(q + 0.1)
    result = robot.ik(goal, time_budget=None)
    assert result.converged
    np.testing.assert_allclose(robot.fk(result.q), goal, atol=1e-6)


def test_fk_all_equals_pinocchio_joint_placements():
    """robot.fk_all(q), one configuration and batched, against Pinocchio's
    oMi on the UR5 and Panda URDF chains (tests/data/reference_frames.json)."""
    import json

    with open(data_file("reference_frames.json")) as f:
        chains = json.load(f)["chains"]
    for chain in chains:
        robot = armkit.Robot.from_urdf(DATA / chain["urdf"], base=chain["base"], tip=chain["tip"])
        assert robot.frame_names == chain["joint_names"]
        Q = np.array([s["q"] for s in chain["samples"]])
        expected = np.array([s["placements"] for s in chain["samples"]]).reshape(len(Q), -1, 4, 4)
        batched = robot.fk_all(Q)
        assert batched.shape == expected.shape
        assert np.abs(batched - expected).max() < POSE_TOLERANCE
        for q, frames in zip(Q, expected):
            assert np.abs(robot.fk_all(q) - frames).max() < POSE_TOLERANCE
    # The DH UR5's last frame is its flange, the end effector.
    ur5 = armkit.Robot.builtin("ur5")
    q = np.array([0.1, -1.2, 1.0, -0.5, 1.5, 0.3])
    assert np.abs(ur5.fk_all(q)[-1] - ur5.fk(q)).max() < 1e-15
    with pytest.raises(ValueError, match="expected 6 values, got 5"):
        ur5.fk_all(np.zeros(5))
