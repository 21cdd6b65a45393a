#!/usr/bin/env python3
"""armkit from Python against Pinocchio's Python bindings, the Robotics
Toolbox for Python and TRAC-IK (pytracik), in one process, where installed.

Not a test: a measurement. Run it in an environment that has armkit and,
for the comparison, the peers (`../shared/peers/setup.sh` makes a venv with
all of them; then `pip install` the armkit wheel into it):

    python crates/armkit-py/bench/bench.py [--robots ur5,panda] [--calls 20000] [--batch 100000] [--ik 1000]

Each row gives the wall-clock time and the CPU time of the calling
thread (`time.thread_time`; "-" where the work runs on other threads): on a
loaded machine the second is what the call costs.

Every library gets the same chain, read from the same URDF
(tests/data/urdf, base to tip as in the reference data), the same random
configurations and the same IK targets (armkit's `benchmark_targets`: FK of
configurations drawn uniformly within the limits, seed 42; every solve
starts from mid-range). Rows:

- per-call FK / Jacobian: best of --reps passes of a Python loop over
  --calls configurations (armkit `robot.fk(q)` returns the (4, 4) array;
  Pinocchio `forwardKinematics` + `updateFramePlacement`, and
  `computeFrameJacobian(..., LOCAL_WORLD_ALIGNED)`; RTB `ETS.fkine` /
  `ETS.jacob0` on the pre-extracted chain, its fastest path);
- batched FK of --batch configurations: armkit `robot.fk(Q)` on one thread
  and on every core; the peers have no batched call, so their figure is the
  per-call loop;
- RNEA per call and batched (armkit `dynamics.rnea`; Pinocchio `rnea`);
- IK per target (a Python loop of single solves) and batched (armkit
  `ik_batch` on one thread and on every core), on the URDF chain and, for
  armkit, on the built-in DH robot of the same name (`armkit bench-ik`'s
  protocol). Success is re-checked here by FK: armkit's at its own
  tolerance, 1e-6 m and 1e-6 rad; the peers' at theirs, 1e-4 m and 1e-3 rad
  (as ../shared/peers/bench_peers.py: RTB stops at E = |e|^2 / 2 < 1e-10,
  TRAC-IK at eps 1e-5).
"""
from __future__ import annotations

import argparse
import math
import os
import platform
import time
import warnings
from pathlib import Path

import numpy as np

import armkit

REPO = Path(__file__).resolve().parents[3]
URDF = REPO / "tests" / "data" / "urdf"
CHAINS = {
    "ur5": ("ur5.urdf", "base_link", "tool0"),
    "panda": ("panda.urdf", "panda_link0", "panda_link8"),
    "iiwa14": ("iiwa14.urdf", "base_link", "tool0"),
}


def timed(fn):
    """(wall-clock s, CPU s of this thread, fn's result). The CPU time counts
    only while this thread runs: on a loaded machine it is what the call
    costs, where the wall clock also counts the time other processes had the core."""
    wall, cpu = time.perf_counter(), time.thread_time()
    result = fn()
    return time.perf_counter() - wall, time.thread_time() - cpu, result


def best_per_call(fn, args, reps):
    """Best over `reps` passes of the mean (wall, CPU) time (s) of fn(a) over args."""
    def one_pass():
        for a in args:
            fn(a)

    runs = [timed(one_pass)[:2] for _ in range(reps)]
    return min(w for w, _ in runs) / len(args), min(c for _, c in runs) / len(args)


def best_call(fn, reps):
    """Best over `reps` runs of fn(): (wall, CPU) s."""
    runs = [timed(fn)[:2] for _ in range(reps)]
    return min(w for w, _ in runs), min(c for _, c in runs)


def pose_errors(robot, Q, Ts):
    """Position (m) and orientation (rad) errors of FK(Q) from the targets."""
    reached = robot.fk(Q)
    position = np.linalg.norm(reached[:, :3, 3] - Ts[:, :3, 3], axis=1)
    R = np.einsum("nij,nkj->nik", Ts[:, :3, :3], reached[:, :3, :3])
    angle = np.arccos(np.clip((np.trace(R, axis1=1, axis2=2) - 1) / 2, -1, 1))
    return position, angle


ARMKIT_TOLERANCE = (1e-6, 1e-6)  # m, rad
PEER_TOLERANCE = (1e-4, 1e-3)


def verified(robot, Q, Ts, tolerance):
    position, angle = pose_errors(robot, np.asarray(Q), Ts)
    return (position <= tolerance[0]) & (angle <= tolerance[1])


IK_BUDGET = 0.005  # s per solve, as TRAC-IK's timeout; --ik-budget changes it
IK_SOLVER = "lm"  # --ik-solver: lm (the figures in the README), auto (analytic where the class allows), ...


def armkit_ik(robot, Ts, q0, label, add):
    """IK rows of armkit: a loop of single solves, then ik_batch on 1 and every core."""
    wall, cpu, results = timed(lambda: [robot.ik(T, q0=q0, solver=IK_SOLVER, time_budget=IK_BUDGET) for T in Ts])
    elapsed = (wall / len(Ts), cpu / len(Ts))
    Q_ik = np.array([r.q for r in results])
    ok = verified(robot, Q_ik, Ts, ARMKIT_TOLERANCE) & np.array([r.converged for r in results])
    add("IK, per target" + label, "armkit", elapsed, f"{100 * ok.mean():.2f} % success")
    for threads, library in ((1, "armkit, 1 thread"), (None, f"armkit, {os.cpu_count()} threads")):
        wall, cpu, (Q_ik, converged) = timed(lambda: robot.ik_batch(Ts, q0=q0, solver=IK_SOLVER, threads=threads, time_budget=IK_BUDGET))
        # On one thread the work runs on this one: its CPU time is the cost.
        elapsed = (wall / len(Ts), cpu / len(Ts) if threads == 1 else None)
        ok = verified(robot, Q_ik, Ts, ARMKIT_TOLERANCE) & converged
        add("IK, batched, per target" + label, library, elapsed, f"{100 * ok.mean():.2f} % success")


def bench_armkit_ik(name, args, add):
    """IK on the built-in robot of that name, if there is one (bench-ik's protocol)."""
    if name not in armkit.builtin_robots():
        return
    robot = armkit.Robot.builtin(name)
    _, Ts = robot.benchmark_targets(args.ik, seed=42)
    armkit_ik(robot, Ts, robot.neutral_configuration(), " (built-in DH model)", add)


class Pinocchio:
    """The base-to-tip chain of a URDF in Pinocchio, joints off the chain locked at 0."""

    def __init__(self, path, base, tip, joint_names):
        import pinocchio as pin

        full = pin.buildModelFromUrdf(str(path))
        lock = [full.getJointId(n) for n in full.names[1:] if n not in joint_names]
        self.model = pin.buildReducedModel(full, lock, pin.neutral(full)) if lock else full
        assert list(self.model.names[1:]) == list(joint_names), "joint order differs from armkit's"
        assert self.model.nq == len(joint_names), "a joint is not a 1-DOF joint"
        self.data = self.model.createData()
        self.tip = self.model.getFrameId(tip)
        self.pin = pin

    def fk(self, q):
        self.pin.forwardKinematics(self.model, self.data, q)
        return self.pin.updateFramePlacement(self.model, self.data, self.tip)

    def jacobian(self, q):
        return self.pin.computeFrameJacobian(self.model, self.data, q, self.tip, self.pin.LOCAL_WORLD_ALIGNED)


def rtb_chain(path, tip):
    import roboticstoolbox as rtb

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        robot = rtb.Robot.URDF(str(path))
    return robot.ets(end=tip)


def trac_ik_solver(path, base, tip, lower, upper, timeout):
    import pytracik

    solver = pytracik.TRAC_IK(base, tip, Path(path).read_text(), timeout, 1e-5, pytracik.SolveType.Speed)
    # pytracik misreads some URDF limits: set armkit's (the URDF's) explicitly.
    pytracik.set_joint_limits(solver, list(lower), list(upper))
    return solver


def quaternion_xyzw(R):
    """Unit quaternion (x, y, z, w) of a rotation matrix (Shepperd's method)."""
    t = np.trace(R)
    if t > 0:
        s = 2 * math.sqrt(1 + t)
        return ((R[2, 1] - R[1, 2]) / s, (R[0, 2] - R[2, 0]) / s, (R[1, 0] - R[0, 1]) / s, s / 4)
    i = int(np.argmax(np.diag(R)))
    j, k = (i + 1) % 3, (i + 2) % 3
    s = 2 * math.sqrt(1 + R[i, i] - R[j, j] - R[k, k])
    q = [0.0, 0.0, 0.0, 0.0]
    q[i] = s / 4
    q[j] = (R[j, i] + R[i, j]) / s
    q[k] = (R[k, i] + R[i, k]) / s
    q[3] = (R[k, j] - R[j, k]) / s
    return tuple(q)


def fmt_time(seconds):
    if seconds is None:
        return "-"
    us = seconds * 1e6
    return f"{us * 1e3:.0f} ns" if us < 1 else f"{us:.2f} us" if us < 100 else f"{us:.0f} us"


def bench_robot(name, args, rows):
    urdf, base, tip = CHAINS[name]
    path = URDF / urdf
    robot = armkit.Robot.from_urdf(path, base=base, tip=tip)
    rng = np.random.default_rng(42)
    Q = rng.uniform(robot.lower, robot.upper, (args.batch, robot.dof))
    qs = list(Q[: args.calls])
    _, Ts = robot.benchmark_targets(args.ik, seed=42)
    q0 = robot.neutral_configuration()
    cores = os.cpu_count()

    def add(what, library, seconds, note=""):
        rows.append((name, what, library, seconds, note))

    # --- armkit
    bench_armkit_ik(name, args, add)
    add("FK, per call", "armkit", best_per_call(robot.fk, qs, args.reps))
    add("Jacobian, per call", "armkit", best_per_call(robot.jacobian, qs, args.reps))
    wall, cpu = best_call(lambda: robot.fk(Q, threads=1), args.reps)
    add(f"FK, batch of {args.batch}, per configuration", "armkit, 1 thread", (wall / args.batch, cpu / args.batch))
    wall, _ = best_call(lambda: robot.fk(Q), args.reps)
    add(f"FK, batch of {args.batch}, per configuration", f"armkit, {cores} threads", (wall / args.batch, None))
    armkit_ik(robot, Ts, q0, "", add)

    # dynamics (RNEA) where the URDF has inertials
    V = rng.uniform(-1, 1, Q.shape)
    A = rng.uniform(-2, 2, Q.shape)
    states = list(zip(Q[: args.calls], V[: args.calls], A[: args.calls]))
    rnea = armkit.dynamics.rnea
    add("RNEA, per call", "armkit", best_per_call(lambda s: rnea(robot, *s), states, args.reps))
    wall, cpu = best_call(lambda: rnea(robot, Q, V, A, threads=1), args.reps)
    add(f"RNEA, batch of {args.batch}, per state", "armkit, 1 thread", (wall / args.batch, cpu / args.batch))

    # --- Pinocchio
    try:
        pinocchio = Pinocchio(path, base, tip, robot.joint_names)
    except ImportError:
        print(f"[{name}] Pinocchio not installed: skipped")
    else:
        add("FK, per call", "Pinocchio (Python)", best_per_call(pinocchio.fk, qs, args.reps))
        add("Jacobian, per call", "Pinocchio (Python)", best_per_call(pinocchio.jacobian, qs, args.reps))
        for q in qs[:10]:  # same chain, same answer
            assert np.abs(pinocchio.fk(q).homogeneous - robot.fk(q)).max() < 1e-12
        pin_rnea = pinocchio.pin.rnea
        model, data = pinocchio.model, pinocchio.data
        for q, v, a in states[:10]:
            assert np.abs(pin_rnea(model, data, q, v, a) - rnea(robot, q, v, a)).max() < 1e-9
        add("RNEA, per call", "Pinocchio (Python)", best_per_call(lambda s: pin_rnea(model, data, *s), states, args.reps))

    # --- Robotics Toolbox
    try:
        ets = rtb_chain(path, tip)
    except ImportError:
        print(f"[{name}] Robotics Toolbox not installed: skipped")
    else:
        few = qs[: max(200, len(qs) // 10)]
        add("FK, per call", "RTB (ETS, C ext.)", best_per_call(ets.fkine, few, args.reps))
        add("Jacobian, per call", "RTB (ETS, C ext.)", best_per_call(ets.jacob0, few, args.reps))
        Tr = ets.fkine(qs[0]).A
        if np.abs(Tr - robot.fk(qs[0])).max() > 1e-9:
            print(f"[{name}] RTB's URDF root differs from the base link: its IK is skipped")
        else:
            wall, cpu, solutions = timed(
                lambda: [ets.ik_LM(T, q0=q0, ilimit=30, slimit=100, tol=1e-10, joint_limits=True) for T in Ts]
            )
            elapsed = (wall / len(Ts), cpu / len(Ts))
            Q_rtb = np.array([s.q for s in solutions])
            ok = verified(robot, Q_rtb, Ts, PEER_TOLERANCE) & np.array([bool(s.success) for s in solutions])
            add("IK, per target", "RTB ik_LM (C++)", elapsed, f"{100 * ok.mean():.2f} % success")

    # --- TRAC-IK
    try:
        trac = trac_ik_solver(path, base, tip, robot.lower, robot.upper, 0.005)
    except ImportError:
        print(f"[{name}] pytracik not installed: skipped")
    else:
        import pytracik

        arguments = [(T[0, 3], T[1, 3], T[2, 3], *quaternion_xyzw(T[:3, :3])) for T in Ts]
        start = np.ascontiguousarray(q0)
        wall, _, answers = timed(lambda: [pytracik.ik(trac, start, *a) for a in arguments])
        # TRAC-IK solves on two threads of its own: this thread's CPU time says nothing.
        elapsed = (wall / len(Ts), None)
        Q_trac = np.array([a[1:] if a[0] > 0 else q0 for a in answers])
        ok = verified(robot, Q_trac, Ts, PEER_TOLERANCE) & np.array([a[0] > 0 for a in answers])
        add("IK, per target", "TRAC-IK (5 ms)", elapsed, f"{100 * ok.mean():.2f} % success")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--robots", default="ur5,panda")
    parser.add_argument("--calls", type=int, default=20000, help="configurations per per-call pass")
    parser.add_argument("--batch", type=int, default=100000, help="configurations of the batched FK")
    parser.add_argument("--ik", type=int, default=1000, help="IK targets")
    parser.add_argument("--reps", type=int, default=5)
    parser.add_argument("--ik-solver", default="lm", help="armkit's IK solver: lm (default), auto, closed-form, nr, dls, sri")
    parser.add_argument("--ik-budget", default="0.005", help="armkit's IK time budget per solve, s, or 'none'")
    args = parser.parse_args()
    global IK_BUDGET, IK_SOLVER
    IK_BUDGET = None if args.ik_budget == "none" else float(args.ik_budget)
    IK_SOLVER = args.ik_solver
    warnings.simplefilter("ignore")
    rows = []
    for name in args.robots.split(","):
        bench_robot(name, args, rows)
    print(f"\narmkit IK solver {IK_SOLVER}, time budget per solve: {IK_BUDGET} s")
    print(f"armkit {armkit.__version__}, numpy {np.__version__}, Python {platform.python_version()}, "
          f"{os.cpu_count()} cores, {platform.processor() or platform.machine()}")
    print("\n| robot | what | library | wall clock | CPU time | note |\n| --- | --- | --- | --- | --- | --- |")
    for robot, what, library, (wall, cpu), note in rows:
        print(f"| {robot} | {what} | {library} | {fmt_time(wall)} | {fmt_time(cpu)} | {note} |")


if __name__ == "__main__":
    main()
