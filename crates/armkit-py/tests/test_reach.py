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


def planar_text(a1=0.5, a2=0.4):
    return "\n".join(
        [
            'name = "planar2r"',
            'convention = "standard"',
            "[[links]]",
            'type = "R"',
            "d = 0.0",
            f"a = {a1}",
            "alpha = 0.0",
            "qlim = [-1.0, 1.0]",
            "[[links]]",
            'type = "R"',
            "d = 0.0",
            f"a = {a2}",
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


# ------------------------------------------------------------------ the maps

import armkit.reach  # noqa: E402

# Small maps, fixed seeds: each builds in well under a second.
SMALL = dict(resolution=0.2, orientations=8, progress=False)
SAMPLED = dict(resolution=0.2, orientations=8, builder="fk-samples", samples=20_000, seed=3, progress=False)


@pytest.fixture(scope="module")
def ur5_map(ur5):
    return armkit.reach.build(ur5, threads=2, **SMALL)


def pose(R, p):
    T = np.eye(4)
    T[:3, :3], T[:3, 3] = R, p
    return T


def assert_same_map(a, b):
    assert a.dims == b.dims and a.spec == b.spec
    np.testing.assert_array_equal(a.origin, b.origin)
    for name in ("reachable", "solutions", "capability", "manipulability", "boundary"):
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name), err_msg=name)
    assert a.calls == b.calls


def test_local_map_arrays_agree_with_each_other_and_with_queries(ur5_map):
    m = ur5_map
    nx, ny, nz = m.dims
    K = m.layout.orientation_count
    assert (m.reachable.shape, m.capability.shape) == ((nx, ny, nz, K), (nx, ny, nz))
    # Capability: the reachable fraction of each cell's orientations.
    np.testing.assert_allclose(m.capability, m.reachable.mean(axis=3), rtol=0, atol=1e-12)
    assert m.reachable_bins == np.count_nonzero(m.reachable) and 0 < m.reachable_bins < m.reachable.size
    assert m.reachable_volume == pytest.approx(m.reachable_cells * 0.2**3) and m.reachable_cells > 0
    # A reachable bin has a solution; an unreachable one none.
    assert np.all((m.solutions > 0) == m.reachable)
    assert np.all((m.manipulability > 0) <= (m.capability > 0))
    # Each bin's centre pose queries as the bin says, for every bin of a few cells.
    R = m.orientations
    cells = [np.unravel_index(i, m.dims) for i in np.flatnonzero(m.capability.reshape(-1) > 0)[::37]]
    cells += [np.unravel_index(i, m.dims) for i in np.flatnonzero(m.capability.reshape(-1) == 0)[::97]]
    Ts = np.array([pose(R[k], m.cell_center(c)) for c in cells for k in range(K)])
    expected = np.array([m.reachable[c][k] for c in cells for k in range(K)])
    np.testing.assert_array_equal(m.bin_reachable(Ts), expected)
    assert m.bin_reachable(Ts[0]) == expected[0]
    # The interpolated query: true inside a block of reachable cells, false
    # inside a block of unreachable ones (every orientation of the 27 cells
    # around a centre), whatever it does near the boundary.
    full = np.ones((3, 3, 3), bool)
    solid, empty = [], []
    for c in np.ndindex(*(d - 2 for d in m.dims)):
        block = m.reachable[c[0] : c[0] + 3, c[1] : c[1] + 3, c[2] : c[2] + 3]
        centre = tuple(i + 1 for i in c)
        if np.all(block):
            solid.append(centre)
        elif not np.any(block):
            empty.append(centre)
    assert solid and empty
    Ts = np.array([pose(R[k], m.cell_center(c)) for c in solid + empty for k in range(K)])
    answers = m.query(Ts)
    assert answers.dtype == bool and answers.shape == (len(Ts),)
    np.testing.assert_array_equal(answers, np.repeat([True] * len(solid) + [False] * len(empty), K))
    assert m.query(Ts[0]) is True
    assert m.query(pose(np.eye(3), [50.0, 0, 0])) is False


def test_the_boundary_is_refined_and_signed_as_the_bins(ur5, ur5_map):
    m = ur5_map
    assert m.boundary.dtype == np.int8 and m.boundary.shape == m.reachable.shape
    np.testing.assert_array_equal(m.boundary > 0, m.reachable)
    assert np.all(np.abs(m.boundary.astype(int)) <= 64) and np.any(np.abs(m.boundary.astype(int)) < 64)
    assert m.spec["boundary"] == {"bisection": {"steps": 6}}
    # A bin with no disagreeing neighbour keeps one cell.
    padded = np.pad(m.reachable, ((1, 1), (1, 1), (1, 1), (0, 0)), mode="edge")
    same = np.ones(m.reachable.shape, bool)
    for axis in range(3):
        for shift in (-1, 1):
            same &= np.roll(padded, shift, axis=axis)[1:-1, 1:-1, 1:-1] == m.reachable
    assert np.all(np.abs(m.boundary[same].astype(int)) == 64)
    # The refinement alone, on the map with the cells' boundary, gives it.
    bits = np.where(m.reachable, 64, -64).astype(np.int8).reshape(-1)
    cells = m._inner.with_boundary(bits)
    np.testing.assert_array_equal(armkit._armkit._reach.refine(ur5, cells).boundary, m.boundary.reshape(-1))
    with pytest.raises(ValueError, match="holds -64 for a bin that is reachable"):
        m._inner.with_boundary(-np.abs(bits))


def test_the_refinement_in_parts_of_any_size_equals_the_whole(ur5, ur5_map):
    # The distributed refinement's steps: crossings per range of cells, in
    # any partition and order, applied to the merged map.
    r = armkit._armkit._reach
    m = ur5_map
    bits = np.where(m.reachable, 64, -64).astype(np.int8).reshape(-1)
    cells = m._inner.with_boundary(bits)
    n = m.dims[0] * m.dims[1] * m.dims[2]
    edges = [0, 1, 7, n // 3, n // 3 + 1, n]
    parts = [r.refine_chunk(ur5, cells, (a, b)) for a, b in zip(edges, edges[1:])]
    assert sum(len(p["bin"]) for p in parts) > 0
    assert all(p["bin"].dtype == np.uint64 and p["at"].dtype == np.float32 for p in parts)
    refined = r.apply_refinement(cells, parts[::-1])
    np.testing.assert_array_equal(refined.boundary, m.boundary.reshape(-1))
    assert refined.calls == cells.calls + sum(p["calls"] for p in parts)
    torn = dict(parts[-1], axis=parts[-1]["axis"][:-1])
    with pytest.raises(ValueError, match="differ in length"):
        r.apply_refinement(cells, [torn])
    with pytest.raises(ValueError, match="a result has no `at`"):
        r.apply_refinement(cells, [{k: v for k, v in parts[0].items() if k != "at"}])


def test_arm4_map_is_position_only():
    arm4 = armkit.Robot.builtin("arm4")
    m = armkit.reach.build(arm4, resolution=0.1, progress=False)
    assert m.spec["target"] == "position" and m.layout.orientation_count == 1
    assert m.reachable_cells > 20 and np.all(m.capability[m.capability > 0] == 1.0)
    c = m.cell_center(tuple(np.argwhere(m.capability > 0)[0]))
    turned = np.array([[0, -1, 0], [1, 0, 0], [0, 0, 1.0]])
    assert m.query(pose(np.eye(3), c)) == m.query(pose(turned, c))
    with pytest.raises(ValueError, match="rolls.*4 joints.*position-only"):
        armkit.reach.build(arm4, resolution=0.1, rolls=2, progress=False)


def test_nearest_reachable_cell_and_capability_at(ur5_map):
    m = ur5_map
    reachable = np.argwhere(m.capability > 0)
    centres = np.array([m.cell_center(tuple(c)) for c in reachable])
    for p in ([2.0, 0.3, -0.1], [0.0, 0.0, 0.0], m.cell_center(tuple(reachable[5]))):
        cell = m.nearest_reachable_cell(p)
        assert m.capability[cell] > 0
        best = np.min(np.linalg.norm(centres - p, axis=1))
        assert np.linalg.norm(m.cell_center(cell) - p) == pytest.approx(best, abs=1e-12)
    c = tuple(reachable[3])
    assert m.capability_at(m.cell_center(c)) == m.capability[c]
    assert m.capability_at([50.0, 0.0, 0.0]) == 0.0


def test_local_build_does_not_depend_on_threads(ur5, ur5_map):
    assert_same_map(armkit.reach.build(ur5, threads=1, **SMALL), ur5_map)


def test_progress_callback_counts_chunks(ur5):
    seen = []
    armkit.reach.build(ur5, resolution=0.2, orientations=8, progress=lambda d, t: seen.append((d, t)))
    assert seen and seen[-1][0] == seen[-1][1] and [d for d, _ in seen] == sorted(d for d, _ in seen)


def test_npz_round_trip(tmp_path, ur5_map):
    path = ur5_map.save(tmp_path / "map.npz")
    again = armkit.reach.load(path)
    assert_same_map(again, ur5_map)
    assert again.robot_description == "ur5" and again.robot().name == "ur5"
    with np.load(path) as data:  # plain NumPy reads it
        np.testing.assert_array_equal(data["capability"], ur5_map.capability)


def test_zarr_round_trip(tmp_path, ur5_map):
    pytest.importorskip("zarr", reason="the zarr extra is not installed")
    path = ur5_map.save(tmp_path / "map.zarr")
    assert path.is_dir()
    assert_same_map(armkit.reach.ReachMap.load(path), ur5_map)


def test_coverage_of_a_sampled_map_against_the_ik_map(ur5, ur5_map):
    sampled = armkit.reach.build(ur5, **SAMPLED)
    more = armkit.reach.build(ur5, **{**SAMPLED, "samples": 80_000})
    hit = np.count_nonzero(sampled.reachable & ur5_map.reachable)
    assert sampled.coverage_of(ur5_map) == pytest.approx(hit / ur5_map.reachable_bins, abs=1e-15)
    assert 0 < sampled.coverage_of(ur5_map) < more.coverage_of(ur5_map) <= 1
    assert ur5_map.coverage_of(ur5_map) == 1.0
    with pytest.raises(ValueError, match="different layouts"):
        ur5_map.coverage_of(armkit.reach.build(ur5, resolution=0.3, orientations=8, progress=False))


def test_load_reads_the_cli_npz(tmp_path, ur5, ur5_map):
    # `armkit reach --out` writes these arrays (no spec, robot or calls).
    arrays = ur5_map._arrays()
    cli = {k: arrays[k] for k in ("reachable", "solutions", "capability", "manipulability", "origin", "resolution",
                                  "orientations", "directions", "rolls")}
    np.savez(tmp_path / "cli.npz", **cli)
    with pytest.raises(ValueError, match="pass robot="):
        armkit.reach.load(tmp_path / "cli.npz")
    m = armkit.reach.load(tmp_path / "cli.npz", robot=ur5)
    for name in ("reachable", "solutions", "capability", "manipulability"):
        np.testing.assert_array_equal(getattr(m, name), getattr(ur5_map, name))
    np.testing.assert_array_equal(m.orientations, ur5_map.orientations)
    # Files before the refinement: the cells' boundary.
    np.testing.assert_array_equal(m.boundary, np.where(ur5_map.reachable, 64, -64))
    # Today's CLI also writes the refined boundary and the spec.
    np.savez(tmp_path / "cli2.npz", **cli, boundary=arrays["boundary"], spec=arrays["spec"])
    m = armkit.reach.load(tmp_path / "cli2.npz", robot=ur5)
    np.testing.assert_array_equal(m.boundary, ur5_map.boundary)
    assert m.spec == ur5_map.spec


def test_out_writes_the_map(tmp_path, ur5, ur5_map):
    m = armkit.reach.build(ur5, out=tmp_path / "built.npz", **SMALL)
    assert_same_map(armkit.reach.load(tmp_path / "built.npz"), m)


@pytest.mark.parametrize(
    "options, message",
    [
        (dict(resolution=0.0), "resolution"),
        (dict(resolution=float("nan")), "resolution"),
        (dict(orientations=0), "approach_directions"),
        (dict(rolls=0), "rolls"),
        (dict(builder="rrt"), 'expected "ik" or "fk-samples"'),
        (dict(builder="fk-samples", samples=0), "samples"),
        (dict(resolution=1e-4), "exceeds the limit"),
        (dict(threads=0), "threads"),
        (dict(progress="yes"), "progress"),
    ],
)
def test_bad_build_arguments_raise_value_error(ur5, options, message):
    with pytest.raises(ValueError, match=message):
        armkit.reach.build(ur5, **{**SMALL, **options})


def test_bad_files_raise(tmp_path, ur5_map):
    with pytest.raises(FileNotFoundError):
        armkit.reach.load(tmp_path / "none.npz")
    (tmp_path / "junk.npz").write_text("not a zip")
    with pytest.raises(ValueError, match="not a NumPy .npz file"):
        armkit.reach.load(tmp_path / "junk.npz")
    np.savez(tmp_path / "other.npz", x=np.zeros(3))
    with pytest.raises(ValueError, match="not a reach map"):
        armkit.reach.load(tmp_path / "other.npz")
    ur5_map.save(tmp_path / "ur5.npz")
    with pytest.raises(ValueError, match="a different robot or spec"):
        armkit.reach.load(tmp_path / "ur5.npz", robot=armkit.Robot.from_description(planar_text(0.1, 0.1)))


# ---------------------------------------------------------------- on Dask


@pytest.fixture(scope="module")
def client():
    distributed = pytest.importorskip("distributed", reason="dask.distributed is not installed (the dask extra)")
    with distributed.LocalCluster(
        n_workers=2, processes=True, threads_per_worker=1, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        yield client


def test_dask_build_equals_local_build(client, ur5, ur5_map):
    m = armkit.reach.build(ur5, client=client, chunk_seconds=0.01, **SMALL)
    assert_same_map(m, ur5_map)


def test_dask_refinement_runs_as_tasks_on_the_workers(client, ur5, ur5_map):
    from distributed import get_task_stream

    with get_task_stream(client) as stream:
        m = armkit.reach.build(ur5, client=client, chunk_seconds=0.01, **SMALL)
    keys = [str(task["key"]) for task in stream.data]
    assert sum("armkit-reach-refine-" in k for k in keys) >= 2
    assert_same_map(m, ur5_map)


def test_dask_build_into_zarr_equals_local_build(client, ur5, ur5_map, tmp_path):
    pytest.importorskip("zarr", reason="the zarr extra is not installed")
    m = armkit.reach.build(ur5, client=client, chunk_seconds=0.01, out=tmp_path / "m.zarr", **SMALL)
    assert_same_map(m, ur5_map)
    assert_same_map(armkit.reach.load(tmp_path / "m.zarr"), ur5_map)
    # Written by the workers, one chunk of x slices per task.
    import zarr

    chunks = zarr.open_group(str(tmp_path / "m.zarr"), mode="r")["reachable"].chunks
    assert chunks[1:] == ur5_map.reachable.shape[1:] and chunks[0] < ur5_map.dims[0]


def test_dask_sampling_build_equals_local_build(client, ur5):
    local = armkit.reach.build(ur5, **SAMPLED)
    assert local.calls == SAMPLED["samples"] and 0 < local.reachable_bins
    assert_same_map(armkit.reach.build(ur5, client=client, chunk_seconds=0.01, **SAMPLED), local)


def test_dask_build_survives_a_worker_killed_mid_build(client, ur5):
    import os
    import signal

    options = dict(resolution=0.1, orientations=30, progress=False)
    local = armkit.reach.build(ur5, **options)
    pids = client.run(os.getpid)
    victim = next(iter(pids.values()))
    events = []

    def kill_one(done, total):
        if done == 1:
            events.append(total)
            os.kill(victim, signal.SIGKILL)

    m = armkit.reach.build(ur5, client=client, chunk_seconds=0.05, **{**options, "progress": kill_one})
    assert events and events[0] >= 8  # killed with chunks still to come
    assert victim not in client.run(os.getpid).values()
    assert_same_map(m, local)


def test_base_placements_find_a_known_base_from_transforms_and_quaternions(ur5):
    m = armkit.reach.build(ur5, resolution=0.1, orientations=50, threads=2, progress=False)
    base = np.eye(4)
    base[:3, :3] = [[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]  # yaw pi/2
    base[:3, 3] = [0.7, -0.4, 0.0]
    Q = [[0.3, -1.2, 1.4, -1.7, -1.5, 0.2], [0.6, -1.0, 1.2, -1.6, -1.5, 0.0], [0.0, -1.4, 1.6, -1.8, -1.4, 0.5]]
    task = base @ ur5.fk(Q)
    grid = dict(x=(-0.5, 1.5), y=(-1.5, 0.5), step=0.1, z=0.0, yaws=4)
    found = m.base_placements(task, **grid)
    assert found.shape[1] == 5 and 0 < len(found) < 4 * 21 * 21
    assert np.all(np.diff(found[:, 4]) <= 0)
    known = np.all(np.abs(found[:, :4] - [0.7, -0.4, 0.0, np.pi / 2]) < 1e-9, axis=1)
    assert known.sum() == 1
    # The same task as positions and quaternions (qw, qx, qy, qz).
    rows = []
    for T in task:
        R = T[:3, :3]
        w = 0.5 * np.sqrt(max(1.0 + np.trace(R), 0.0))
        rows.append([*T[:3, 3], w, (R[2, 1] - R[1, 2]) / (4 * w), (R[0, 2] - R[2, 0]) / (4 * w), (R[1, 0] - R[0, 1]) / (4 * w)])
    np.testing.assert_allclose(m.base_placements(np.array(rows), **grid), found, atol=1e-9)
    far = task.copy()
    far[1, 0, 3] += 4.0
    with pytest.raises(ValueError, match="no base placement reaches all 3 task poses"):
        m.base_placements(far, **grid)
    with pytest.raises(ValueError, match="step"):
        m.base_placements(task, **{**grid, "step": 0.0})
    with pytest.raises(ValueError, match="expected \\(4, 4\\)"):
        m.base_placements(np.zeros((2, 5)), **grid)
