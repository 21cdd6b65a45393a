"""Dynamics against Pinocchio's reference (RNEA, CRBA, ABA, gravity,
Coriolis, kinetic energy) at 1e-9 relative, one state at a time and
batched; batched equals looped; ABA undoes RNEA; bad input."""

import json
import re

import numpy as np
import pytest

import armkit
from armkit import dynamics
from conftest import DATA, data_file

CHAINS = [("ur5", "ur5.urdf", "base_link", "tool0"), ("panda", "panda.urdf", "panda_link0", "panda_link8")]


def load(name):
    with open(data_file(f"reference_dynamics_{name}.json")) as f:
        ref = json.load(f)
    return {key: np.array([s[key] for s in ref["samples"]]) for key in ref["samples"][0]}, ref


def close(actual, expected):
    scale = max(1.0, np.abs(expected).max())
    np.testing.assert_allclose(actual, expected, rtol=0, atol=1e-9 * scale)


@pytest.mark.parametrize("name, urdf, base, tip", CHAINS)
def test_dynamics_equal_pinocchio(name, urdf, base, tip):
    robot = armkit.Robot.from_urdf(DATA / "urdf" / urdf, base=base, tip=tip)
    ref, raw = load(name)
    g = list(np.array(json.loads(raw["gravity"]) if isinstance(raw["gravity"], str) else raw["gravity"], float))
    for i in range(len(ref["q"])):
        q, v, a = ref["q"][i], ref["v"][i], ref["a"][i]
        close(dynamics.rnea(robot, q, v, a, gravity=g), ref["tau"][i])
        close(dynamics.mass_matrix(robot, q), ref["mass_matrix"][i])
        close(dynamics.gravity_torques(robot, q, gravity=g), ref["gravity"][i])
        close(dynamics.coriolis_torques(robot, q, v), ref["coriolis"][i])
        close(dynamics.aba(robot, q, v, ref["tau_in"][i], gravity=g), ref["ddq"][i])
        close(dynamics.kinetic_energy(robot, q, v), ref["kinetic_energy"][i])
    # Batched: the same numbers, bit for bit.
    tau = dynamics.rnea(robot, ref["q"], ref["v"], ref["a"], gravity=g)
    close(tau, ref["tau"])
    for threads in (1, 2, 3):
        assert np.array_equal(dynamics.rnea(robot, ref["q"], ref["v"], ref["a"], gravity=g, threads=threads), tau)
    assert np.array_equal(dynamics.mass_matrix(robot, ref["q"]), np.array([dynamics.mass_matrix(robot, q) for q in ref["q"]]))
    close(dynamics.aba(robot, ref["q"], ref["v"], ref["tau_in"], gravity=g), ref["ddq"])
    close(dynamics.kinetic_energy(robot, ref["q"], ref["v"]), ref["kinetic_energy"])


PANDA_URDF = ("panda.urdf", "panda_link0", "panda_link8")


def panda():
    urdf, base, tip = PANDA_URDF
    return armkit.Robot.from_urdf(DATA / "urdf" / urdf, base=base, tip=tip)


def test_aba_undoes_rnea_on_a_large_batch():
    robot = panda()
    rng = np.random.default_rng(11)
    Q = rng.uniform(robot.lower, robot.upper, (2000, 7))
    V = rng.uniform(-1, 1, (2000, 7))
    A = rng.uniform(-2, 2, (2000, 7))
    tau = dynamics.rnea(robot, Q, V, A)
    np.testing.assert_allclose(dynamics.aba(robot, Q, V, tau), A, atol=1e-8)
    M = dynamics.mass_matrix(robot, Q)
    np.testing.assert_allclose(M, np.transpose(M, (0, 2, 1)), atol=1e-12)
    assert np.all(np.linalg.eigvalsh(M) > 0)


def test_dynamics_bad_input():
    robot = panda()
    q = np.zeros(7)
    with pytest.raises(ValueError, match=re.escape("joint_velocities: expected 7 values, got 6")):
        dynamics.rnea(robot, q, np.zeros(6), q)
    with pytest.raises(ValueError, match=re.escape("v: expected an array of shape (3, 7), got shape (2, 7)")):
        dynamics.rnea(robot, np.zeros((3, 7)), np.zeros((2, 7)), np.zeros((3, 7)))
    with pytest.raises(ValueError, match=re.escape("q[1]: joint_positions[0] is not finite (NaN)")):
        dynamics.mass_matrix(robot, [[0.0] * 7, [np.nan] * 7])
    with pytest.raises(ValueError, match=re.escape("gravity: expected 3 values, got 2")):
        dynamics.gravity_torques(robot, q, gravity=[0.0, -9.81])
    q6 = np.zeros(6)
    with pytest.raises(ValueError, match=re.escape("invalid model: link 0 (`q1`), field `mass`: model `puma560` has no mass properties")):
        dynamics.rnea(armkit.Robot.builtin("puma560"), q6, q6, q6)  # the DH PUMA 560 has no masses
    # gantry9-flex (the beam coupling) has dynamics in its 9 independent joints.
    with pytest.raises(ValueError, match=re.escape("expected 9 values, got 8")):
        dynamics.mass_matrix(armkit.Robot.builtin("gantry9-flex"), np.zeros(8))


def test_coupled_model_mass_matrix():
    # The flexible gantry's dynamics fold the beam coupling (M' H M): the
    # mass matrix is 9 x 9, symmetric and positive definite.
    flex = armkit.Robot.builtin("gantry9-flex")
    q = [1.0, 2.0, 0.5, 0.0, 0.3, -0.2, 0.1, 0.5, 0.0]
    m = dynamics.mass_matrix(flex, q)
    assert m.shape == (9, 9)
    np.testing.assert_allclose(m, m.T, rtol=0, atol=1e-9 * np.abs(m).max())
    assert np.linalg.eigvalsh(m).min() > 0.0


def test_gravity_between_calls_on_the_cached_workspace():
    robot = panda()
    q = [0.1, -0.5, 0.2, -2.0, 0.1, 1.5, 0.8]  # a list: the path without NumPy
    g = dynamics.gravity_torques(robot, q)
    assert np.abs(g).max() > 1.0
    assert np.array_equal(dynamics.gravity_torques(robot, q, gravity=[0.0, 0.0, 0.0]), np.zeros(7))
    np.testing.assert_allclose(dynamics.gravity_torques(robot, q, gravity=[0.0, 0.0, -2 * 9.81]), 2 * g, rtol=1e-12)
    assert np.array_equal(dynamics.gravity_torques(robot, np.array(q)), g)
    # RNEA at rest is gravity; the same from a batch of one.
    assert np.array_equal(dynamics.rnea(robot, q, [0.0] * 7, [0.0] * 7), g)
    assert np.array_equal(dynamics.rnea(robot, [q], [[0.0] * 7], [[0.0] * 7])[0], g)


def published(chain):
    """The chain of reference_dynamics_<chain>.json (Pinocchio on a published URDF) and its samples."""
    with open(data_file(f"reference_dynamics_{chain}.json")) as f:
        ref = json.load(f)
    robot = armkit.Robot.from_urdf(DATA / ref["urdf"], base=ref["base"], tip=ref["tip"])
    return robot, ref["samples"]


@pytest.mark.parametrize("chain", ["al5d", "human_leg", "bolt_leg"])
def test_published_chains_equal_pinocchio(chain):
    # AL5D: M singular everywhere; human leg: massless links between joints;
    # Bolt's leg: a zero-mass foot with an inertia tensor.
    robot, samples = published(chain)
    for s in samples:
        np.testing.assert_allclose(dynamics.rnea(robot, s["q"], s["v"], s["a"]), s["tau"], rtol=0, atol=1e-8)
        np.testing.assert_allclose(dynamics.mass_matrix(robot, s["q"]), s["mass_matrix"], rtol=0, atol=1e-8)
        np.testing.assert_allclose(dynamics.gravity_torques(robot, s["q"]), s["gravity"], rtol=0, atol=1e-8)
        if chain != "al5d":
            np.testing.assert_allclose(dynamics.aba(robot, s["q"], s["v"], s["tau"]), s["a"], rtol=0, atol=1e-9)


def test_forward_dynamics_on_a_singular_mass_matrix_is_a_value_error():
    robot, samples = published("al5d")
    message = re.escape("the mass matrix is singular at joint 3 (`j4`)")
    qs = [s["q"] for s in samples] + list(np.random.default_rng(32).uniform(-1.5, 1.5, (200, 4)))
    for q in qs:
        with pytest.raises(ValueError, match=message):
            dynamics.aba(robot, q, np.zeros(4), np.full(4, 0.1))
    # Batched: the row is named, and no array comes back.
    with pytest.raises(ValueError, match=r"q\[0\]: .*" + message):
        dynamics.aba(robot, np.array(qs), np.zeros((len(qs), 4)), np.full((len(qs), 4), 0.1))


def test_the_stub_names_exactly_the_builtins_with_dynamics():
    """dynamics.pyi's list of built-ins with mass properties is what the code does."""
    import armkit.dynamics as dyn_module
    from conftest import REPO

    stub = (REPO / "crates/armkit-py/python/armkit/dynamics.pyi").read_text()
    listed = stub[stub.index("the built-ins with them:") :].split(")")[0]
    named = set(re.findall(r"``([a-z0-9-]+)``", listed))
    runs = set()
    for name in armkit.builtin_robots():
        robot = armkit.Robot.builtin(name)
        try:
            dyn_module.rnea(robot, np.zeros(robot.dof), np.zeros(robot.dof), np.zeros(robot.dof))
            runs.add(name)
        except ValueError as error:
            assert "no mass properties" in str(error), (name, error)
    assert named == runs
