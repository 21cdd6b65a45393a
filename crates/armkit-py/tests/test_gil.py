"""Batched calls release the GIL: another Python thread keeps running while
a long batched call runs on this one."""

import threading
import time

import numpy as np

import armkit


def progress_of_another_thread_during(call):
    """How many loop turns a counting Python thread makes while `call` runs."""
    counter = [0]
    stop = threading.Event()

    def count():
        while not stop.is_set():
            counter[0] += 1

    worker = threading.Thread(target=count)
    worker.start()
    time.sleep(0.05)  # let it run
    before = counter[0]
    started = time.perf_counter()
    call()
    elapsed = time.perf_counter() - started
    during = counter[0] - before
    stop.set()
    worker.join()
    return during, elapsed


def test_batched_fk_releases_the_gil():
    robot = armkit.Robot.builtin("panda")
    Q = np.random.default_rng(0).uniform(robot.lower, robot.upper, (400_000, robot.dof))
    during, elapsed = progress_of_another_thread_during(lambda: robot.fk(Q, threads=1))
    assert elapsed > 0.02, "the call was too short to tell"
    # A thread holding the GIL for the whole call would allow no turn at
    # all; a pure-Python loop makes millions of turns per second.
    assert during > 10_000, f"{during} turns in {elapsed:.3f} s"


def test_batched_ik_releases_the_gil():
    robot = armkit.Robot.builtin("ur5")
    _, Ts = robot.benchmark_targets(2000, seed=1)
    # The numeric solver (~15 us a pose): the default `auto` takes the UR5's
    # closed form, ~2 us a pose, too short a call to tell on a fast machine.
    during, elapsed = progress_of_another_thread_during(
        lambda: robot.ik_batch(Ts, solver="lm", threads=1)
    )
    assert elapsed > 0.01, "the call was too short to tell"
    assert during > 10_000, f"{during} turns in {elapsed:.3f} s"
