"""Reachability and capability maps: which tool poses an arm reaches, over a
position grid (cubic cells over the arm's reach) times a set of tool
orientations (near-uniform approach directions times roll samples).

Built locally on every core (the library's threads, GIL released) or, given
a Dask ``client``, on a cluster: the cells are cut into chunks of a few
seconds' work; each task receives the robot's description text, the spec as
JSON and its chunk, and returns plain NumPy arrays; the results are merged by
a tree of merge tasks (no step gathers every cell on one worker before the
merge); a lost worker loses only its chunks, which Dask reruns. The result is
the same as the local build's: chunks are deterministic.

Frames and units: positions in the world frame (the frame of the robot's
base transform), metres; orientations are tool frames in the world frame.
Arrays are indexed ``[ix, iy, iz]`` (per cell) or ``[ix, iy, iz, k]`` (per
cell and orientation ``k``).

>>> import armkit, armkit.reach
>>> robot = armkit.Robot.builtin("ur5")
>>> m = armkit.reach.build(robot, resolution=0.2, orientations=8, progress=False)
>>> m.capability.shape == m.dims
True
"""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path
from typing import Any, Callable, Dict, List, Optional, Tuple, Union

import numpy as np

from ._armkit import Robot, _reach

__all__ = ["MapLayout", "ReachMap", "build", "load"]

#: The grid of a map (cells over the reach bound's box times orientations).
MapLayout = _reach.MapLayout

_Chunk = Tuple[int, int, int, int]
_Part = Dict[str, Any]
_Progress = Union[bool, Callable[[int, int], Any]]

#: Merge tasks combine this many partial results each (the tree's fan-in).
MERGE_FAN_IN = 8
#: Chunks per Dask worker at least, so that every worker has work and a lost
#: worker loses a small share of the map.
CHUNKS_PER_WORKER = 4


def build(
    robot: Robot,
    resolution: float = 0.05,
    orientations: int = 200,
    rolls: Optional[int] = None,
    builder: str = "ik",
    client: Any = None,
    threads: Optional[int] = None,
    chunk_seconds: float = 2.0,
    progress: _Progress = True,
    samples: int = 1_000_000,
    seed: int = 0,
    out: Optional[Union[str, "Path"]] = None,
) -> "ReachMap":
    """Builds the reachability map of ``robot``.

    ``resolution``: edge of a cubic cell, m. ``orientations``: tool
    orientations per cell, split into near-uniform approach directions times
    ``rolls`` roll samples (``rolls=None``: the library's choice: one roll
    per direction where the last joint rolls the tool freely (the UR5) or,
    on an arm with more than six joints, over at least 300 degrees (the
    Panda; RM4D's reduction), else about equal angular spacing, 200 giving
    25 x 8). An arm with fewer than six joints gets a position-only
    map (one nominal orientation; ``orientations`` unused, ``rolls`` an
    error), as ``armkit reach`` does. ``builder``: ``"ik"`` (every (cell centre, orientation)
    pose solved: analytic IK where the arm allows, numeric IK with restarts
    otherwise) or ``"fk-samples"`` (``samples`` configurations drawn within
    the joint limits from ``seed``, each pose binned: faster, misses bins no
    sample hits). ``client``: a ``dask.distributed.Client``; None builds
    locally on ``threads`` threads (None: every core). ``chunk_seconds``: the
    work of one Dask task. ``progress``: True for a line on stderr, False for
    none, or a callable ``progress(done, total)`` (chunks). ``out``: also
    save the map there (``.npz``, or a Zarr store for a path ending in
    ``.zarr``).
    """
    spec = _reach.spec_json(robot, resolution, orientations, rolls, builder, samples, seed)
    report = _progress_function(progress)
    start = time.perf_counter()
    to_zarr = out is not None and Path(out).suffix == ".zarr"
    if client is not None and to_zarr and builder == "ik":
        reach_map = _build_into_zarr(client, robot, spec, chunk_seconds, report, Path(out))  # type: ignore[arg-type]
        reach_map.build_seconds = time.perf_counter() - start
    else:
        if client is None:
            inner = _reach.build(robot, spec, threads, report)
        else:
            inner = _build_on_dask(client, robot, spec, chunk_seconds, report)
        reach_map = ReachMap(inner, robot.description(), time.perf_counter() - start)
        if out is not None:
            reach_map.save(out)
    if progress is True:
        print(f"\r{reach_map.summary()}", file=sys.stderr)
    return reach_map


def _progress_function(progress: _Progress) -> Optional[Callable[[int, int], Any]]:
    if callable(progress):
        return progress
    if progress is True:

        def line(done: int, total: int) -> None:
            print(f"\rreach: {done}/{total} chunks", end="", file=sys.stderr, flush=True)

        return line
    if progress is False or progress is None:
        return None
    raise ValueError(f"invalid argument `progress`: expected True, False or a callable, got {progress!r}")


# ---------------------------------------------------------------- Dask build


_WORKER_LAYOUTS: Dict[Tuple[str, str], Tuple[Robot, Any]] = {}


def _worker_layout(description: str, spec_json: str) -> Tuple[Robot, Any]:
    """The robot and layout a task needs, made once per worker process (the
    last few kept)."""
    key = (description, spec_json)
    if key not in _WORKER_LAYOUTS:
        if len(_WORKER_LAYOUTS) >= 4:
            _WORKER_LAYOUTS.pop(next(iter(_WORKER_LAYOUTS)))
        robot = Robot.from_description(description)
        _WORKER_LAYOUTS[key] = (robot, MapLayout(robot, spec_json))
    return _WORKER_LAYOUTS[key]


def _chunk_task(description: str, spec_json: str, chunk: _Chunk) -> _Part:
    """A Dask task: one chunk of the map, as a dict of NumPy arrays."""
    robot, layout = _worker_layout(description, spec_json)
    return _reach.build_chunk(robot, layout, tuple(chunk))


def _merge(*parts: _Part) -> _Part:
    """Merges partial results (a merge task of the tree): IK parts hold
    consecutive cell ranges, joined in cell order; sampling parts hold the
    bins they hit, joined as a union keeping each bin's best
    manipulability. Partial merges have the form of a chunk's result, so
    merges nest."""
    ordered = sorted(parts, key=lambda p: (p["cells"][0], p["samples"][0]))
    cells = [p for p in ordered if p["cells"][1] > p["cells"][0]]
    for a, b in zip(cells, cells[1:]):
        if a["cells"][1] != b["cells"][0]:
            raise ValueError(f"chunks: cell ranges {a['cells']} and {b['cells']} are not consecutive")

    def joined(key: str, dtype: Any) -> np.ndarray:
        return np.concatenate([np.asarray(p[key], dtype=dtype) for p in ordered])

    hits = joined("hits", np.uint64)
    hit_manipulability = joined("hit_manipulability", np.float64)
    if hits.size:
        order = np.argsort(hits, kind="stable")
        hits, hit_manipulability = hits[order], hit_manipulability[order]
        hits, first = np.unique(hits, return_index=True)
        hit_manipulability = np.maximum.reduceat(hit_manipulability, first)
    samples = [p["samples"] for p in ordered if p["samples"][1] > p["samples"][0]]
    return {
        "cells": (cells[0]["cells"][0], cells[-1]["cells"][1]) if cells else (0, 0),
        "samples": (min(s[0] for s in samples), max(s[1] for s in samples)) if samples else (0, 0),
        "reachable": joined("reachable", np.uint8),
        "solutions": joined("solutions", np.uint8),
        "manipulability": joined("manipulability", np.float64),
        "hits": hits,
        "hit_manipulability": hit_manipulability,
        "calls": int(sum(int(p["calls"]) for p in ordered)),
    }


def _target_work(robot: Robot, layout: Any, chunk_seconds: float, workers: int) -> int:
    """IK solves (or samples) per chunk: about ``chunk_seconds`` of one
    core's work, timed on a probe chunk from the middle of the grid (the
    corners are mostly out of reach and faster), and small enough that each
    worker gets ``CHUNKS_PER_WORKER`` chunks."""
    if not (chunk_seconds > 0 and np.isfinite(chunk_seconds)):
        raise ValueError(f"invalid argument `chunk_seconds`: must be finite and > 0, got {chunk_seconds}")
    probe_work = 4 * layout.orientation_count
    probes = layout.chunks(probe_work)
    probe = probes[len(probes) // 2]
    start = time.perf_counter()
    calls = int(_reach.build_chunk(robot, layout, probe)["calls"])
    rate = max(calls, 1) / max(time.perf_counter() - start, 1e-6)
    sampling = probe[3] > probe[2]
    total = probe_work * len(probes) if sampling else layout.cell_count * layout.orientation_count
    spread = max(1, total // (CHUNKS_PER_WORKER * max(workers, 1)))
    return int(max(1, min(rate * chunk_seconds, spread)))


def _build_on_dask(
    client: Any,
    robot: Robot,
    spec_json: str,
    chunk_seconds: float,
    report: Optional[Callable[[int, int], Any]],
) -> Any:
    """Builds the map on the Dask cluster of ``client``; returns the merged
    map (the extension's Map)."""
    try:
        from distributed import as_completed
    except ImportError as error:  # pragma: no cover - the extra is missing
        raise ImportError('a Dask build needs dask.distributed: pip install "armkit[dask]"') from error
    from dask.base import tokenize

    layout = MapLayout(robot, spec_json)
    workers = len(client.scheduler_info().get("workers", {})) or 1
    chunks = layout.chunks(_target_work(robot, layout, chunk_seconds, workers))
    description = robot.description()
    token = tokenize(description, spec_json)
    futures = [
        client.submit(_chunk_task, description, spec_json, chunk, key=f"armkit-reach-chunk-{i}-{token}")
        for i, chunk in enumerate(chunks)
    ]
    # The tree of merges: each level merges MERGE_FAN_IN neighbours (their
    # cell ranges are consecutive), on the workers that hold them.
    level, depth = futures, 0
    while len(level) > 1:
        depth += 1
        level = [
            client.submit(_merge, *level[i : i + MERGE_FAN_IN], key=f"armkit-reach-merge-{depth}-{i}-{token}")
            for i in range(0, len(level), MERGE_FAN_IN)
        ]
    # The boundary's refinement needs the merged bits: tasks on the workers,
    # each given the merged map (Dask moves it to each worker once) and a
    # range of cells; their crossings are applied here.
    refinements = []
    if _refines(spec_json):
        spans = _cell_spans(layout.cell_count, CHUNKS_PER_WORKER * workers)
        refinements = [
            client.submit(
                _refine_task, description, spec_json, token, level[0], span, key=f"armkit-reach-refine-{i}-{token}"
            )
            for i, span in enumerate(spans)
        ]
    if report is not None:
        tasks = futures + refinements
        for done, _ in enumerate(as_completed(tasks), start=1):
            report(done, len(tasks))
    merged = _reach.from_chunks(layout, [level[0].result()])
    if not refinements:
        return merged
    # Arrays from the wire may sit misaligned in their frames: copied.
    parts = [
        {k: np.require(v, requirements=["C", "A"]) if isinstance(v, np.ndarray) else v for k, v in part.items()}
        for part in client.gather(refinements)
    ]
    return _reach.apply_refinement(merged, parts)


def _refines(spec_json: str) -> bool:
    """True when the spec's boundary is located by bisection."""
    boundary = json.loads(spec_json).get("boundary", "cells")
    return isinstance(boundary, dict) and "bisection" in boundary


def _cell_spans(cells: int, pieces: int) -> List[Tuple[int, int]]:
    """``cells`` split into at most ``pieces`` consecutive ranges of nearly
    equal length, in order."""
    pieces = max(1, min(cells, pieces))
    edges = [cells * i // pieces for i in range(pieces + 1)]
    return [(a, b) for a, b in zip(edges, edges[1:]) if b > a]


_WORKER_MAPS: Dict[str, Any] = {}


def _refine_task(description: str, spec_json: str, token: str, merged: _Part, span: Tuple[int, int]) -> Dict[str, Any]:
    """A Dask task: the boundary crossings on the edges leaving cells
    ``span`` of the merged map (made once per worker and build)."""
    robot, layout = _worker_layout(description, spec_json)
    if token not in _WORKER_MAPS:
        _WORKER_MAPS.clear()
        _WORKER_MAPS[token] = _reach.from_chunks(layout, [merged])
    return _reach.refine_chunk(robot, _WORKER_MAPS[token], span)


def _zarr_chunk_task(description: str, spec_json: str, slices: Tuple[int, int], path: str) -> int:
    """A Dask task: the cells of x slices ``slices`` computed and written
    into their own chunk of the Zarr store at ``path``; returns the calls."""
    robot, layout = _worker_layout(description, spec_json)
    nx, ny, nz = layout.dims
    k = layout.orientation_count
    slab = ny * nz
    part = _reach.build_chunk(robot, layout, (slices[0] * slab, slices[1] * slab, 0, 0))
    n = slices[1] - slices[0]
    reachable = part["reachable"].reshape(n, ny, nz, k)
    group = _zarr().open_group(path, mode="r+")
    region = slice(slices[0], slices[1])
    group["reachable"][region] = reachable
    group["solutions"][region] = part["solutions"].reshape(n, ny, nz, k)
    group["manipulability"][region] = part["manipulability"].reshape(n, ny, nz)
    # The library's capability index: reachable orientations / orientations.
    counts = reachable.sum(axis=3, dtype=np.int64)
    group["capability"][region] = counts.astype(np.float64) / k
    return int(part["calls"])


def _build_into_zarr(
    client: Any,
    robot: Robot,
    spec_json: str,
    chunk_seconds: float,
    report: Optional[Callable[[int, int], Any]],
    path: Path,
) -> "ReachMap":
    """The IK build on Dask writing straight into a Zarr store: each task
    computes whole x slices and writes them into its own chunk of each
    array (no two tasks write one chunk; the store must be on a file system
    every worker sees); nothing is merged in memory. Returns the map read
    back from the store."""
    from distributed import as_completed

    layout = MapLayout(robot, spec_json)
    nx, ny, nz = layout.dims
    k = layout.orientation_count
    workers = len(client.scheduler_info().get("workers", {})) or 1
    target = _target_work(robot, layout, chunk_seconds, workers)
    per = max(1, min(nx, round(target / (ny * nz * k))))
    description = robot.description()
    arrays = {
        "reachable": ((nx, ny, nz, k), np.uint8),
        "solutions": ((nx, ny, nz, k), np.uint8),
        "capability": ((nx, ny, nz), np.float64),
        "manipulability": ((nx, ny, nz), np.float64),
    }
    attrs = {
        "origin": np.asarray(layout.origin).tolist(),
        "resolution": float(layout.resolution),
        "spec": layout.spec_json,
        "robot": description,
    }
    _create_zarr(path, arrays, per, attrs)
    futures = [
        client.submit(_zarr_chunk_task, description, spec_json, (x, min(x + per, nx)), str(path))
        for x in range(0, nx, per)
    ]
    calls = 0
    for done, future in enumerate(as_completed(futures), start=1):
        calls += future.result()
        if report is not None:
            report(done, len(futures))
    group = _zarr().open_group(str(path), mode="r+")
    group.attrs["calls"] = calls
    # The boundary's refinement, after the slices are all in, written as
    # one more array of the store.
    refined = ReachMap(_reach.refine(robot, ReachMap.load(path, robot)._inner), description)
    create = getattr(group, "create_array", None) or group.create_dataset
    create("boundary", shape=(nx, ny, nz, k), chunks=(per, ny, nz, k), dtype=np.int8, fill_value=0)
    group["boundary"][...] = refined.boundary
    group.attrs["calls"] = refined.calls
    return refined


# ------------------------------------------------------------------ the map


class ReachMap:
    """A reachability map: per cell and orientation reachable or not and the
    number of IK solutions; per cell the capability index (the reachable
    fraction of its orientations, after Zacharias et al. 2007) and the best
    manipulability. Positions in the world frame, m."""

    def __init__(self, inner: Any, robot_description: str, build_seconds: Optional[float] = None) -> None:
        self._inner = inner
        self._layout = inner.layout
        #: The description text of the robot the map is of (``Robot.from_description``).
        self.robot_description = robot_description
        #: Wall time of the build, s (None for a loaded map).
        self.build_seconds = build_seconds
        dims = self.dims
        k = self._layout.orientation_count
        #: Per cell and orientation: True where the pose is reachable, shape (nx, ny, nz, K).
        self.reachable: np.ndarray = inner.reachable.reshape(*dims, k).astype(bool)
        #: Per cell and orientation: distinct IK solutions within the limits (uint8; 0 for sampling).
        self.solutions: np.ndarray = inner.solutions.reshape(*dims, k)
        #: Per cell and orientation: the signed distance from the cell centre to
        #: the boundary in 1/64 of a cell (int8), positive where reachable;
        #: +-64 away from the boundary or where the map was not refined.
        self.boundary: np.ndarray = inner.boundary.reshape(*dims, k)
        #: Per cell: the capability index in [0, 1], shape (nx, ny, nz).
        self.capability: np.ndarray = inner.capability.reshape(dims)
        #: Per cell: the best manipulability (Yoshikawa) of a reaching configuration, 0 where none.
        self.manipulability: np.ndarray = inner.manipulability.reshape(dims)

    @property
    def layout(self) -> Any:
        """The grid (:class:`MapLayout`)."""
        return self._layout

    @property
    def spec(self) -> Dict[str, Any]:
        """What the map is: resolution, approach_directions, rolls, builder."""
        return dict(json.loads(self._layout.spec_json))

    @property
    def builder(self) -> str:
        """``"ik"`` or ``"fk-samples"``."""
        return "ik" if self.spec["builder"] == "inverse_kinematics" else "fk-samples"

    @property
    def resolution(self) -> float:
        """Edge of a cubic cell, m."""
        return float(self._layout.resolution)

    @property
    def origin(self) -> np.ndarray:
        """World-frame position of the grid's lower corner, m, shape (3,)."""
        return np.asarray(self._layout.origin)

    @property
    def dims(self) -> Tuple[int, int, int]:
        """Cells along x, y, z."""
        return tuple(self._layout.dims)  # type: ignore[return-value]

    @property
    def orientations(self) -> np.ndarray:
        """The tool orientations (rotation matrices, world frame), shape (K, 3, 3)."""
        return np.asarray(self._layout.orientations())

    @property
    def calls(self) -> int:
        """IK solves (or FK samples) the build took."""
        return int(self._inner.calls)

    @property
    def reachable_cells(self) -> int:
        """Cells with at least one reachable orientation."""
        return int(np.count_nonzero(self.capability > 0))

    @property
    def reachable_bins(self) -> int:
        """Reachable (cell, orientation) bins."""
        return int(np.count_nonzero(self.reachable))

    def coverage_of(self, reference: "ReachMap") -> float:
        """The fraction of ``reference``'s reachable bins this map also has
        reachable: a sampled map's coverage against the IK map of the same
        spec (the CLI's ``--coverage``); 1 when ``reference`` has none."""
        return float(self._inner.coverage_of(reference._inner))

    @property
    def reachable_volume(self) -> float:
        """Volume of the cells with at least one reachable orientation, m^3."""
        return float(np.count_nonzero(self.capability > 0)) * self.resolution**3

    def cell_center(self, index: Union[int, Tuple[int, int, int]]) -> np.ndarray:
        """World-frame centre of a cell (flat index or (ix, iy, iz)), m."""
        ijk = np.unravel_index(index, self.dims) if np.ndim(index) == 0 else index
        return self.origin + (np.asarray(ijk, dtype=float) + 0.5) * self.resolution

    def query(self, T: Any) -> Any:
        """Whether pose ``T`` (4, 4) is reachable by the map: over the three
        orientations around its rotation (the one of a position-only map),
        the trilinear interpolation of the signed boundary distances
        (``boundary``) at the 8 cell centres around its position is at least
        0: near the boundary, where the refinement's bisection put it;
        unrefined, the interpolated reachable bits at least 1/2 (a boundary
        between the centres, not the cells' staircase). For ``T`` of shape
        (N, 4, 4) a bool array (N,). False outside the box."""
        return self._inner.query(T)

    def bin_reachable(self, T: Any) -> Any:
        """The raw bit of the bin of ``T`` (4, 4): its position's cell, the
        orientation nearest its rotation; (N, 4, 4) gives a bool array (N,)."""
        return self._inner.bin_reachable(T)

    def capability_at(self, p: Any) -> float:
        """The capability index of the cell containing ``p`` (3,), m; 0 outside the box."""
        return float(self._inner.capability_at(p))

    def nearest_reachable_cell(self, p: Any) -> Optional[Tuple[int, int, int]]:
        """``(ix, iy, iz)`` of the reachable cell whose centre is nearest
        ``p`` (3,), m; None when no cell is reachable."""
        index = self._inner.nearest_reachable_cell(p)
        if index is None:
            return None
        return tuple(int(i) for i in np.unravel_index(index, self.dims))  # type: ignore[return-value]

    def base_placements(
        self,
        task: Any,
        x: Tuple[float, float],
        y: Tuple[float, float],
        step: float,
        z: float = 0.0,
        yaws: int = 1,
    ) -> np.ndarray:
        """Inverse reachability: the base placements from which the map
        reaches every task pose, best first.

        ``task``: world-frame tool poses, (4, 4) or (N, 4, 4) transforms, or
        (7,) or (N, 7) rows ``(x, y, z, qw, qx, qy, qz)`` (m, unit
        quaternion scalar first). Candidates: the robot's base frame at
        ``(x, y, z)`` on the grid over the ``x`` and ``y`` ranges (m) with
        ``step`` (m), turned by ``yaws`` headings in [0, 2 pi) about the
        world z axis. Returns rows ``(x, y, z, yaw, score)`` (m, rad, the
        mean capability index of the task's cells seen from the base).
        Raises ValueError naming the problem, and when no placement reaches
        every pose (how many were tried, the most poses one reached)."""
        return self._inner.base_placements(_task_transforms(task), tuple(x), tuple(y), step, z, yaws)

    def robot(self) -> Robot:
        """The robot the map is of (rebuilt from its description)."""
        return Robot.from_description(self.robot_description)

    def summary(self) -> str:
        """One line: cells, orientations, reachable volume, build time, calls per second."""
        nx, ny, nz = self.dims
        text = (
            f"reach map: {nx} x {ny} x {nz} cells at {self.resolution:g} m x "
            f"{self._layout.orientation_count} orientations ({self.builder}), "
            f"{self.reachable_cells} reachable cells ({self.reachable_volume:.3f} m^3), "
            f"{self.reachable_bins} reachable bins"
        )
        if self.build_seconds:
            rate = self.calls / self.build_seconds
            text += f", built in {self.build_seconds:.2f} s ({rate:,.0f} calls/s)"
        return text

    def __repr__(self) -> str:
        return f"<ReachMap {self.summary()}>"

    def _arrays(self) -> Dict[str, Any]:
        return {
            "reachable": self.reachable.astype(np.uint8),
            "solutions": self.solutions,
            "capability": self.capability,
            "manipulability": self.manipulability,
            "origin": self.origin,
            "resolution": np.float64(self.resolution),
            "orientations": self.orientations,
            "directions": np.asarray(self._layout.directions()),
            "rolls": np.int64(self.spec["rolls"]),
            "boundary": self.boundary,
            "calls": np.uint64(self.calls),
            "spec": np.str_(self._layout.spec_json),
            "robot": np.str_(self.robot_description),
        }

    def save(self, path: Union[str, "Path"]) -> Path:
        """Writes the map as NumPy ``.npz`` (``reachable`` (nx, ny, nz, K)
        uint8, ``solutions``, ``capability``, ``manipulability``, ``origin``,
        ``resolution``, ``orientations`` (K, 3, 3), ``directions`` (D, 3),
        ``rolls``, ``boundary`` (nx, ny, nz, K) int8, ``spec`` JSON: the
        arrays of ``armkit reach --out``; and ``calls``, ``robot``
        description), or
        as a Zarr store (the same arrays, chunked by x slices) when the path
        ends in ``.zarr``. Returns the path."""
        path = Path(path)
        if path.suffix == ".zarr":
            _save_zarr(path, self._arrays(), self.dims)
        else:
            with open(path, "wb") as f:
                np.savez(f, **self._arrays())
        return path

    @classmethod
    def load(cls, path: Union[str, "Path"], robot: Optional[Robot] = None) -> "ReachMap":
        """Reads a map :meth:`save` (``.npz`` or ``.zarr``) or ``armkit reach
        --out`` wrote. ``robot`` is needed only for a file without the
        robot's description (the CLI's)."""
        path = Path(path)
        if not path.exists():
            raise FileNotFoundError(f"{path}: no such file or directory")
        arrays = _load_zarr(path) if path.is_dir() or path.suffix == ".zarr" else _load_npz(path)
        if "spec" not in arrays and {"resolution", "directions", "rolls"} <= set(arrays):
            # A map of `armkit reach --out`: its grid from the arrays.
            arrays["spec"] = json.dumps(
                {
                    "resolution": float(arrays["resolution"]),
                    "approach_directions": int(np.shape(arrays["directions"])[0]),
                    "rolls": int(arrays["rolls"]),
                    "builder": "inverse_kinematics",
                }
            )
        missing = [k for k in ("reachable", "solutions", "manipulability", "spec") if k not in arrays]
        if missing:
            raise ValueError(f"{path}: not a reach map (no {', '.join(missing)})")
        if robot is None:
            if "robot" not in arrays:
                raise ValueError(f"{path}: the file names no robot: pass robot=")
            robot = Robot.from_description(str(arrays["robot"]))
        layout = MapLayout(robot, str(arrays["spec"]))
        reachable = np.asarray(arrays["reachable"])
        shape = (*layout.dims, layout.orientation_count)
        if reachable.shape != shape:
            raise ValueError(
                f"{path}: `reachable` has shape {reachable.shape}, the map's grid {shape} "
                "(a different robot or spec?)"
            )
        whole = {
            "cells": (0, layout.cell_count),
            "samples": (0, 0),
            "reachable": np.ascontiguousarray(reachable.reshape(-1), dtype=np.uint8),
            "solutions": np.ascontiguousarray(np.asarray(arrays["solutions"]).reshape(-1), dtype=np.uint8),
            "manipulability": np.ascontiguousarray(
                np.asarray(arrays["manipulability"]).reshape(-1), dtype=np.float64
            ),
            "hits": np.zeros(0, np.uint64),
            "hit_manipulability": np.zeros(0, np.float64),
            "calls": int(arrays.get("calls", 0)),
        }
        inner = _reach.from_chunks(layout, [whole])
        if "boundary" in arrays:
            boundary = np.ascontiguousarray(np.asarray(arrays["boundary"]).reshape(-1), dtype=np.int8)
            inner = inner.with_boundary(boundary)
        return cls(inner, robot.description())


def _task_transforms(task: Any) -> np.ndarray:
    """Task poses as (N, 4, 4): transforms as given, rows ``(x, y, z, qw,
    qx, qy, qz)`` converted (the quaternion normalized; a zero one raises)."""
    a = np.asarray(task, dtype=float)
    if a.shape[-2:] == (4, 4):
        return a.reshape(-1, 4, 4)
    if a.ndim not in (1, 2) or a.shape[-1] != 7:
        raise ValueError(f"task: expected (4, 4), (N, 4, 4), (7,) or (N, 7) (x, y, z, qw, qx, qy, qz), got shape {a.shape}")
    a = a.reshape(-1, 7)
    q = a[:, 3:]
    norm = np.linalg.norm(q, axis=1)
    if not np.all(np.isfinite(norm)) or np.any(norm < 1e-12):
        raise ValueError("task: every quaternion (qw, qx, qy, qz) must be finite and non-zero")
    w, qx, qy, qz = (q / norm[:, None]).T
    T = np.zeros((len(a), 4, 4))
    T[:, 0] = np.stack([1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - w * qz), 2 * (qx * qz + w * qy), a[:, 0]], axis=1)
    T[:, 1] = np.stack([2 * (qx * qy + w * qz), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - w * qx), a[:, 1]], axis=1)
    T[:, 2] = np.stack([2 * (qx * qz - w * qy), 2 * (qy * qz + w * qx), 1 - 2 * (qx * qx + qy * qy), a[:, 2]], axis=1)
    T[:, 3, 3] = 1.0
    return T


def load(path: Union[str, "Path"], robot: Optional[Robot] = None) -> ReachMap:
    """Reads a map (``ReachMap.load``)."""
    return ReachMap.load(path, robot)


def _load_npz(path: Path) -> Dict[str, Any]:
    try:
        with np.load(path, allow_pickle=False) as data:
            return {k: data[k][()] if data[k].ndim == 0 else data[k] for k in data.files}
    except (OSError, ValueError) as error:
        raise ValueError(f"{path}: not a NumPy .npz file ({error})") from error


def _zarr() -> Any:
    try:
        import zarr
    except ImportError as error:
        raise ImportError('a Zarr store needs zarr: pip install "armkit[zarr]"') from error
    return zarr


def _create_zarr(
    path: Path, arrays: Dict[str, Tuple[Tuple[int, ...], Any]], slices: int, attrs: Dict[str, Any]
) -> Any:
    """A new Zarr store of the given (shape, dtype) arrays, chunked by
    ``slices`` x slices (a slice of the map reads without the rest)."""
    zarr = _zarr()
    group = zarr.open_group(str(path), mode="w")
    create = getattr(group, "create_array", None) or group.create_dataset
    for name, (shape, dtype) in arrays.items():
        create(name, shape=shape, chunks=(slices, *shape[1:]), dtype=dtype, fill_value=0)
    group.attrs.update(attrs)
    return group


def _save_zarr(path: Path, arrays: Dict[str, Any], dims: Tuple[int, int, int]) -> None:
    grids = {k: v for k, v in arrays.items() if isinstance(v, np.ndarray) and v.ndim >= 3}
    attrs = {k: (v.tolist() if isinstance(v, np.ndarray) else v.item()) for k, v in arrays.items() if k not in grids}
    group = _create_zarr(path, {k: (v.shape, v.dtype) for k, v in grids.items()}, 1, attrs)
    for name, value in grids.items():
        group[name][...] = value


def _load_zarr(path: Path) -> Dict[str, Any]:
    zarr = _zarr()
    try:
        group = zarr.open_group(str(path), mode="r")
    except Exception as error:  # zarr's errors differ between versions
        raise ValueError(f"{path}: not a Zarr store ({error})") from error
    arrays: Dict[str, Any] = dict(group.attrs)
    for name in ("reachable", "solutions", "capability", "manipulability", "boundary"):
        if name in group:
            arrays[name] = group[name][...]
    return arrays
