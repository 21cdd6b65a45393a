#!/usr/bin/env python3
"""The reachability map build's scaling: a UR5 map built locally on one and
two threads, and on a Dask LocalCluster of one and two worker processes
(one thread each), each build checked equal to the first.

Not a test: a measurement. Needs armkit with its dask extra:

    python crates/armkit-py/bench/reach_scaling.py [--resolution 0.1] [--orientations 50] [--chunk-seconds 0.5]

Each row: wall-clock time, CPU time (this process plus the Dask workers'
processes, from psutil) and IK calls per second of wall time. Cluster
start-up is not timed; the workers have built one small map first (imports
and the robot's first parse are not timed either).
"""

import argparse
import os
import time

import numpy as np
import psutil

import armkit
import armkit.reach


def cpu_seconds(pids):
    total = 0.0
    for pid in pids:
        t = psutil.Process(pid).cpu_times()
        total += t.user + t.system
    return total


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--robot", default="ur5")
    parser.add_argument("--resolution", type=float, default=0.1)
    parser.add_argument("--orientations", type=int, default=50)
    parser.add_argument("--chunk-seconds", type=float, default=0.5)
    args = parser.parse_args()
    robot = armkit.Robot.builtin(args.robot)
    options = dict(resolution=args.resolution, orientations=args.orientations, progress=False)
    rows, first = [], None

    def record(label, build, pids):
        nonlocal first
        cpu0, wall0 = cpu_seconds(pids), time.perf_counter()
        m = build()
        wall, cpu = time.perf_counter() - wall0, cpu_seconds(pids) - cpu0
        if first is None:
            first = m
        same = all(np.array_equal(getattr(m, k), getattr(first, k)) for k in ("reachable", "solutions", "manipulability"))
        rows.append((label, wall, cpu, m.calls / wall, same))

    me = [os.getpid()]
    for threads in (1, 2):
        record(f"local, {threads} thread(s)", lambda: armkit.reach.build(robot, threads=threads, **options), me)
    from distributed import Client, LocalCluster

    for workers in (1, 2):
        with LocalCluster(n_workers=workers, processes=True, threads_per_worker=1, dashboard_address=None) as cluster:
            with Client(cluster) as client:
                armkit.reach.build(robot, client=client, resolution=0.3, orientations=8, progress=False)
                pids = me + list(client.run(os.getpid).values())
                record(
                    f"Dask, {workers} worker(s)",
                    lambda: armkit.reach.build(robot, client=client, chunk_seconds=args.chunk_seconds, **options),
                    pids,
                )
    print(f"{args.robot} map: {first.summary()}")
    print(f"{'build':<22} {'wall s':>8} {'CPU s':>8} {'calls/s':>12}  same map")
    for label, wall, cpu, rate, same in rows:
        print(f"{label:<22} {wall:>8.2f} {cpu:>8.2f} {rate:>12,.0f}  {'yes' if same else 'NO'}")


if __name__ == "__main__":
    main()
