"""Soak: four threads call batched FK, Jacobians, IK and dynamics for a
while, valid and invalid inputs mixed; every batched answer must equal the
one-at-a-time answers, every invalid input must raise the exception naming
its argument, and the process's resident memory must stay flat.

Opt-in (it runs for minutes): set ARMKIT_SOAK_SECONDS, e.g.

    ARMKIT_SOAK_SECONDS=600 python -m pytest -q -s crates/armkit-py/tests/test_soak.py

It prints the calls made per thread and the resident set size (RSS, MiB)
sampled every second: its minimum, maximum, and the maximum over the first
and the last tenth of the run. Linux only (reads /proc/self/statm).
"""

import os
import re
import threading
import time

import numpy as np
import pytest

import armkit
from armkit import dynamics
from conftest import DATA

SECONDS = float(os.environ.get("ARMKIT_SOAK_SECONDS", "0"))

pytestmark = pytest.mark.skipif(SECONDS <= 0, reason="soak test: set ARMKIT_SOAK_SECONDS to run it")


def rss_mib():
    with open("/proc/self/statm") as f:
        pages = int(f.read().split()[1])
    return pages * os.sysconf("SC_PAGE_SIZE") / 2**20


def expect(error, message, call):
    try:
        call()
    except error as e:
        assert message in str(e), f"{message!r} not in {e!r}"
    else:
        raise AssertionError(f"no {error.__name__} ({message})")


def fk_worker(rng, robot):
    Q = rng.uniform(robot.lower, robot.upper, size=(int(rng.integers(1, 200)), robot.dof))
    batch = robot.fk(Q, threads=2)
    i = int(rng.integers(len(Q)))
    # 1e-14: the batched kernels fuse multiply-adds the single call rounds twice.
    np.testing.assert_allclose(batch[i], robot.fk(Q[i]), rtol=0, atol=1e-14)
    bad = Q.copy()
    bad[i, int(rng.integers(robot.dof))] = np.nan
    expect(ValueError, f"q[{i}]: joint_positions[", lambda: robot.fk(bad))
    expect(TypeError, "complex", lambda: robot.fk(Q + 1j))


def jacobian_worker(rng, robot):
    Q = rng.uniform(robot.lower, robot.upper, size=(int(rng.integers(1, 200)), robot.dof))
    batch = robot.jacobian(Q, threads=2)
    i = int(rng.integers(len(Q)))
    np.testing.assert_allclose(batch[i], robot.jacobian(Q[i]), rtol=0, atol=1e-14)
    expect(ValueError, f"q: expected an array of shape (N, {robot.dof})", lambda: robot.jacobian(np.zeros((3, robot.dof + 1))))
    expect(TypeError, "bool", lambda: robot.jacobian(np.zeros(robot.dof, dtype=bool)))


def ik_worker(rng, robot):
    Q = rng.uniform(robot.lower, robot.upper, size=(int(rng.integers(1, 20)), robot.dof))
    Ts = robot.fk(Q)
    solved, converged = robot.ik_batch(Ts, solver="lm", time_budget=None, threads=2)
    i = int(rng.integers(len(Q)))
    single = robot.ik(Ts[i], solver="lm", time_budget=None)
    assert single.converged == converged[i]
    assert np.array_equal(single.q, solved[i])
    bad = Ts.copy()
    bad[i, 0, 0] = 2.0  # not a rotation
    expect(ValueError, "", lambda: robot.ik_batch(bad, solver="lm"))
    expect(ValueError, "invalid argument `position_tolerance`", lambda: robot.ik(Ts[i], position_tolerance=-1.0))


def dynamics_worker(rng, robot):
    n = int(rng.integers(1, 100))
    Q = rng.uniform(robot.lower, robot.upper, size=(n, robot.dof))
    V = rng.normal(size=(n, robot.dof))
    A = rng.normal(size=(n, robot.dof))
    tau = dynamics.rnea(robot, Q, V, A, threads=2)
    i = int(rng.integers(n))
    assert np.array_equal(tau[i], dynamics.rnea(robot, Q[i], V[i], A[i]))
    M = dynamics.mass_matrix(robot, Q, threads=2)
    assert np.array_equal(M[i], dynamics.mass_matrix(robot, Q[i]))
    np.testing.assert_allclose(dynamics.aba(robot, Q[i], V[i], tau[i]), A[i], atol=1e-6)
    expect(ValueError, "", lambda: dynamics.rnea(robot, Q, V[:-1] if n > 1 else V[:, :-1], A))
    expect(TypeError, "complex", lambda: dynamics.aba(robot, Q[i], V[i] + 1j, tau[i]))


def test_soak_four_threads():
    panda = armkit.Robot.from_urdf(DATA / "urdf" / "panda.urdf", base="panda_link0", tip="panda_link8")
    ur5 = armkit.Robot.builtin("ur5")
    workers = [(fk_worker, ur5), (jacobian_worker, panda), (ik_worker, ur5), (dynamics_worker, panda)]
    deadline = time.monotonic() + SECONDS
    counts = [0] * len(workers)
    failures = []

    def run(index, worker, robot):
        rng = np.random.default_rng(index)
        try:
            while time.monotonic() < deadline:
                worker(rng, robot)
                counts[index] += 1
        except BaseException as e:  # reported by the main thread
            failures.append((worker.__name__, repr(e)))

    threads = [threading.Thread(target=run, args=(i, w, r)) for i, (w, r) in enumerate(workers)]
    samples = []
    for t in threads:
        t.start()
    while any(t.is_alive() for t in threads):
        samples.append(rss_mib())
        time.sleep(1.0)
    for t in threads:
        t.join()
    tenth = max(1, len(samples) // 10)
    print(
        f"\nsoak {SECONDS:.0f} s: calls per thread {dict(zip([w.__name__ for w, _ in workers], counts))}; "
        f"RSS MiB min {min(samples):.1f} max {max(samples):.1f}, "
        f"first tenth max {max(samples[:tenth]):.1f}, last tenth max {max(samples[-tenth:]):.1f}"
    )
    assert not failures, failures
    assert all(c > 0 for c in counts)
    # Flat: the last tenth of the run holds no more than the first plus 32 MiB.
    assert max(samples[-tenth:]) <= max(samples[:tenth]) + 32.0
