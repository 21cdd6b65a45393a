"""Reachability maps (armkit.reach): the robot as its description text
(pickle, Dask workers), local builds, Dask builds equal to the local one
(also when a worker dies mid-build), .npz and Zarr round trips, bad input.

The Dask tests skip, with the reason, where dask.distributed is not
installed (scripts/test-all.sh installs it); Zarr likewise."""

import pickle

import numpy as np
import pytest

import armkit

from conftest import DATA

Q = [0.1, -1.2, 1.0, -0.5, 1.5, 0.3]


def same_model(a, b, dof):
    """Same name, joints, limits and forward kinematics at a few configurations."""
    assert (a.name, a.dof, a.joint_names) == (b.name, b.dof, b.joint_names)
    np.testing.assert_array_equal(a.lower, b.lower)
    np.testing.assert_array_equal(a.upper, b.upper)
    rng = np.random.default_rng(7)
    Q = rng.uniform(-1.0, 1.0, size=(5, dof))
    np.testing.assert_array_equal(a.fk(Q), b.fk(Q))


@pytest.mark.parametrize(
    "make",
    [
        lambda: armkit.Robot.builtin("ur5"),
        lambda: armkit.Robot.builtin("Panda"),
        lambda: armkit.Robot.from_urdf(DATA / "urdf" / "al5d.urdf"),
        lambda: armkit.Robot.from_urdf(DATA / "urdf" / "ur5.urdf", tip="tool0"),
        lambda: armkit.Robot.from_file(DATA / "reference_ur5_dh.json"),
    ],
    ids=["builtin", "builtin-any-case", "urdf", "urdf-chain", "dh-json"],
)
def test_robot_pickles_and_rebuilds_from_its_description(make):
    robot = make()
    again = pickle.loads(pickle.dumps(robot))
    assert isinstance(again, armkit.Robot)
    same_model(robot, again, robot.dof)
    text = robot.description()
    assert again.description() == text
    same_model(robot, armkit.Robot.from_description(text), robot.dof)


def test_description_of_a_builtin_is_its_name_and_of_a_dh_file_its_text():
    assert armkit.Robot.builtin("ur5").description() == "ur5"
    path = DATA / "reference_ur5_dh.json"
    assert armkit.Robot.from_file(path).description() == path.read_text()


def test_urdf_description_names_a_chosen_chain_and_only_then():
    path = DATA / "urdf" / "al5d.urdf"
    assert armkit.Robot.from_urdf(path).description() == path.read_text()
    chain = armkit.Robot.from_urdf(DATA / "urdf" / "panda.urdf", base="panda_link0", tip="panda_link8")
    text = chain.description()
    assert text.startswith('<!-- armkit chain base="panda_link0" tip="panda_link8" -->\n<')
    # Without the comment the panda's tree has three leaves: no default chain.
    with pytest.raises(ValueError, match="choose the tip link"):
        armkit.Robot.from_description(text.split("-->", 1)[1])
    assert armkit.Robot.from_description(text).joint_names == chain.joint_names


def test_toml_description_round_trips():
    text = '\n'.join(
        [
            'name = "planar2r"',
            'convention = "standard"',
            "[[links]]",
            'type = "R"',
            "d = 0.0",
            "a = 0.5",
            "alpha = 0.0",
            "qlim = [-1.0, 1.0]",
            "[[links]]",
            'type = "R"',
            "d = 0.0",
            "a = 0.4",
            "alpha = 0.0",
            "qlim = [-2.0, 2.0]",
        ]
    )
    robot = armkit.Robot.from_description(text)
    assert (robot.name, robot.dof, robot.description()) == ("planar2r", 2, text)
    T = pickle.loads(pickle.dumps(robot)).fk([0.3, -0.2])
    np.testing.assert_allclose(T[:2, 3], [0.5 * np.cos(0.3) + 0.4 * np.cos(0.1), 0.5 * np.sin(0.3) + 0.4 * np.sin(0.1)], atol=1e-12)


@pytest.mark.parametrize(
    "text, message",
    [
        ("", "the text is empty"),
        ("   \n", "the text is empty"),
        ("nosuchrobot", "nosuchrobot"),
        ("<robot name='x'>", "<description>"),
        ("{\"convention\": \"standard\"}", "links"),
        ('convention = "standard"\nlinks = []', "empty chain"),
        ('<!-- armkit chain base="a" -- <robot/>', "not closed"),
        ('<!-- armkit chain root="a" --> <robot/>', "expected base and tip"),
    ],
)
def test_bad_descriptions_raise_value_error_naming_the_problem(text, message):
    with pytest.raises(ValueError, match=message):
        armkit.Robot.from_description(text)
