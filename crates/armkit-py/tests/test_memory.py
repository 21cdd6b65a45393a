"""Memory stays flat over a million calls: no reference, array or workspace
is leaked per call (a leak of one 4 x 4 array per call would be 100+ MB)."""

import numpy as np

import armkit


def resident_bytes():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * 4096


def test_memory_is_flat_over_a_million_calls():
    robot = armkit.Robot.builtin("ur5")
    q = np.array([0.1, -1.2, 1.0, -0.5, 1.5, 0.3])
    Q = np.tile(q, (16, 1))
    T = robot.fk(q)
    fk, jacobian, ik = robot.fk, robot.jacobian, robot.ik
    for _ in range(20_000):  # warm up: allocator pools, caches
        fk(q)
        jacobian(q)
    before = resident_bytes()
    for _ in range(500_000):
        fk(q)
        jacobian(q)
    for _ in range(20_000):
        fk(Q)
        robot.ik_batch(T[None], q0=q)
        ik(T, q0=q)
        try:
            fk([np.nan] * 6)
        except ValueError:
            pass
    grown = resident_bytes() - before
    assert grown < 4 * 2**20, f"resident memory grew by {grown / 2**20:.1f} MiB over 1 060 000 calls"
