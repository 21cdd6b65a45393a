//! `armkit._armkit._reach`: the library's reachability maps (`armkit::reach`)
//! for `armkit.reach` (python/armkit/reach.py), which adds the Dask build,
//! `.npz` and Zarr files.
//!
//! What crosses processes is plain: the spec as JSON (serde of
//! `armkit::reach::MapSpec`), a chunk as four integers, a chunk's result as a
//! dict of NumPy arrays. The Rust work runs with the GIL released.
//!
//! Frames and units (the library's): positions in the world frame, m; cell
//! `i = (ix * ny + iy) * nz + iz`; bin `cell * orientations + k`.

use armkit::reach::{
    self, Builder, Chunk, ChunkResult, Crossing, FloorGrid, MapLayout, MapSpec, ReachMap,
    Refinement,
};
use armkit::Error;
use numpy::ndarray::Ix2;
use numpy::{PyArray1, PyArray2, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::arrays::{
    copy_values, float_array, new_array, read_pose, shape_error, vector, vector_argument,
};
use crate::errors::OrRaise;
use crate::parallel::thread_count;
use crate::robot::Robot;

/// A chunk as Python sees it: `(cells_start, cells_end, samples_start, samples_end)`.
type ChunkTuple = (usize, usize, u64, u64);

/// The spec of a map of `robot` as canonical JSON. `rolls=None`: the
/// library's choice for the robot (`MapSpec::for_model`: one roll per
/// direction where a roll of the tool changes no answer or, on an arm
/// with more than six joints, almost none (`reach::one_roll_suffices`),
/// else directions and rolls of about equal angular spacing); else `round(orientations /
/// rolls)` directions (at least 1) times `rolls`. `builder`: `"ik"` or
/// `"fk-samples"`.
#[pyfunction]
#[pyo3(signature = (robot, resolution, orientations, rolls=None, builder="ik", samples=1_000_000, seed=0))]
pub fn spec_json(
    robot: &Robot,
    resolution: f64,
    orientations: usize,
    rolls: Option<usize>,
    builder: &str,
    samples: u64,
    seed: u64,
) -> PyResult<String> {
    let builder = match builder {
        "ik" => Builder::InverseKinematics,
        "fk-samples" => Builder::ForwardSampling { samples, seed },
        other => {
            return Err(Error::invalid_argument(
                "builder",
                format!("expected \"ik\" or \"fk-samples\", got \"{other}\""),
            ))
            .or_raise()
        }
    };
    let spec = match rolls {
        None => MapSpec::for_model(&robot.model, resolution, orientations, builder),
        Some(0) => {
            return Err(Error::invalid_argument(
                "rolls",
                "must be at least 1 (or None to choose)",
            ))
            .or_raise()
        }
        Some(_) if robot.model.dof() < 6 => {
            return Err(Error::invalid_argument(
                "rolls",
                format!(
                    "the robot has {} joints, fewer than the six a tool pose needs, so its map is position-only (a cell is reachable when some configuration puts the tool point in it); leave rolls=None",
                    robot.model.dof()
                ),
            ))
            .or_raise()
        }
        Some(rolls) => MapSpec {
            approach_directions: if orientations == 0 {
                0
            } else {
                ((orientations as f64 / rolls as f64).round() as usize).max(1)
            },
            rolls,
            ..MapSpec::with_orientations(resolution, orientations, builder)
        },
    };
    spec.validate().or_raise()?;
    serde_json::to_string(&spec)
        .map_err(|e| Error::invalid_argument("spec", e.to_string()).into_py())
}

/// Converts a library error to Python's `ValueError` (for `map_err`).
trait IntoPy {
    fn into_py(self) -> PyErr;
}

impl IntoPy for Error {
    fn into_py(self) -> PyErr {
        crate::errors::value_error(self)
    }
}

fn parse_spec(json: &str) -> PyResult<MapSpec> {
    let spec: MapSpec = serde_json::from_str(json)
        .map_err(|e| Error::invalid_argument("spec", format!("invalid JSON: {e}")).into_py())?;
    spec.validate().or_raise()?;
    Ok(spec)
}

/// The grid of a map for a robot: cells over the reach bound's box times
/// orientations.
#[pyclass(frozen, module = "armkit.reach", name = "MapLayout")]
pub struct Layout {
    pub(crate) layout: MapLayout,
}

#[pymethods]
impl Layout {
    /// The layout of the spec `spec_json` for `robot`.
    #[new]
    fn new(py: Python<'_>, robot: &Robot, spec_json: &str) -> PyResult<Self> {
        let spec = parse_spec(spec_json)?;
        let layout = py
            .detach(|| MapLayout::new(&robot.model, &spec))
            .or_raise()?;
        Ok(Layout { layout })
    }

    /// The spec as JSON.
    #[getter]
    fn spec_json(&self) -> PyResult<String> {
        serde_json::to_string(self.layout.spec())
            .map_err(|e| Error::invalid_argument("spec", e.to_string()).into_py())
    }

    /// Edge of a cubic cell, m.
    #[getter]
    fn resolution(&self) -> f64 {
        self.layout.resolution()
    }

    /// World-frame position of the grid's lower corner, m, shape (3,).
    #[getter]
    fn origin<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vector(py, &self.layout.origin())
    }

    /// Cells along x, y, z.
    #[getter]
    fn dims(&self) -> (usize, usize, usize) {
        let [x, y, z] = self.layout.dims();
        (x, y, z)
    }

    /// Number of position cells.
    #[getter]
    fn cell_count(&self) -> usize {
        self.layout.cell_count()
    }

    /// Orientations per cell.
    #[getter]
    fn orientation_count(&self) -> usize {
        self.layout.orientation_count()
    }

    /// The unit approach directions (tool z axes, world frame), shape (directions, 3).
    fn directions<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let directions = self.layout.directions();
        let out = new_array(py, numpy::ndarray::Dim([directions.len(), 3]), |out| {
            for (row, d) in out.chunks_exact_mut(3).zip(directions) {
                row.copy_from_slice(d);
            }
            Ok(())
        })?;
        Ok(out.into_any())
    }

    /// World-frame centres of every cell, m, shape (cells, 3).
    fn cell_centers<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let n = self.layout.cell_count();
        let out = new_array(py, numpy::ndarray::Dim([n, 3]), |out| {
            for (i, row) in out.chunks_exact_mut(3).enumerate() {
                row.copy_from_slice(&self.layout.cell_center(i));
            }
            Ok(())
        })?;
        Ok(out.into_any())
    }

    /// The tool orientations (rotation matrices in the world frame), shape
    /// (orientations, 3, 3).
    fn orientations<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let n = self.layout.orientation_count();
        let out = new_array(py, numpy::ndarray::Dim([n, 3, 3]), |out| {
            for (k, m) in out.chunks_exact_mut(9).enumerate() {
                let r = self.layout.orientation(k);
                for row in 0..3 {
                    for col in 0..3 {
                        m[3 * row + col] = r[(row, col)];
                    }
                }
            }
            Ok(())
        })?;
        Ok(out.into_any())
    }

    /// The partition into chunks of about `target_work` IK solves (or
    /// samples) each, as `(cells_start, cells_end, samples_start, samples_end)`.
    fn chunks(&self, target_work: usize) -> Vec<ChunkTuple> {
        reach::chunks(&self.layout, self.layout.spec(), target_work)
            .into_iter()
            .map(|c| (c.cells.start, c.cells.end, c.samples.start, c.samples.end))
            .collect()
    }
}

/// Computes one chunk (GIL released): a dict of NumPy arrays `reachable`,
/// `solutions` (uint8), `manipulability`, `hit_manipulability` (float64),
/// `hits` (uint64) and the ints `cells`, `samples` (start, end) and `calls`.
#[pyfunction]
pub fn build_chunk<'py>(
    py: Python<'py>,
    robot: &Robot,
    layout: &Layout,
    chunk: ChunkTuple,
) -> PyResult<Bound<'py, PyDict>> {
    let chunk = Chunk {
        cells: chunk.0..chunk.1,
        samples: chunk.2..chunk.3,
    };
    let result = py
        .detach(|| reach::build_chunk(&robot.model, &layout.layout, &chunk))
        .or_raise()?;
    chunk_dict(py, result)
}

fn chunk_dict(py: Python<'_>, result: ChunkResult) -> PyResult<Bound<'_, PyDict>> {
    let dict = PyDict::new(py);
    dict.set_item("cells", (result.cells.start, result.cells.end))?;
    dict.set_item("samples", (result.samples.start, result.samples.end))?;
    dict.set_item("reachable", PyArray1::from_vec(py, result.reachable))?;
    dict.set_item("solutions", PyArray1::from_vec(py, result.solutions))?;
    dict.set_item(
        "manipulability",
        PyArray1::from_vec(py, result.manipulability),
    )?;
    dict.set_item("hits", PyArray1::from_vec(py, result.hits))?;
    dict.set_item(
        "hit_manipulability",
        PyArray1::from_vec(py, result.hit_manipulability),
    )?;
    dict.set_item("calls", result.calls)?;
    Ok(dict)
}

/// Item `key` of a dict in argument `argument` (chunk or refinement
/// results) as a Vec (the array's dtype must be `T`).
fn item_vec<T: numpy::Element + Copy>(
    dict: &Bound<'_, PyDict>,
    argument: &str,
    key: &str,
) -> PyResult<Vec<T>> {
    let value = dict.get_item(key)?.ok_or_else(|| {
        Error::invalid_argument(argument, format!("a result has no `{key}`")).into_py()
    })?;
    let array = value.cast::<PyArray1<T>>().map_err(|_| {
        Error::invalid_argument(
            argument,
            format!(
                "a result's `{key}` is not a 1-D array of {}",
                std::any::type_name::<T>()
            ),
        )
        .into_py()
    })?;
    Ok(array.to_vec()?)
}

/// Item `key` of a result dict, or `T`'s default where the dict has none.
fn item_or_default<'py, T>(dict: &Bound<'py, PyDict>, key: &str) -> PyResult<T>
where
    T: for<'a> FromPyObject<'a, 'py, Error = PyErr> + Default,
{
    Ok(dict
        .get_item(key)?
        .map(|value| value.extract())
        .transpose()?
        .unwrap_or_default())
}

fn chunk_from_dict(dict: &Bound<'_, PyDict>) -> PyResult<ChunkResult> {
    let range = |key: &str| -> PyResult<(u64, u64)> {
        dict.get_item(key)?
            .ok_or_else(|| {
                Error::invalid_argument("chunks", format!("a chunk result has no `{key}`"))
                    .into_py()
            })?
            .extract()
    };
    let cells = range("cells")?;
    let samples = range("samples")?;
    let calls = item_or_default(dict, "calls")?;
    Ok(ChunkResult {
        cells: cells.0 as usize..cells.1 as usize,
        samples: samples.0..samples.1,
        reachable: item_vec(dict, "chunks", "reachable")?,
        solutions: item_vec(dict, "chunks", "solutions")?,
        manipulability: item_vec(dict, "chunks", "manipulability")?,
        hits: item_vec(dict, "chunks", "hits")?,
        hit_manipulability: item_vec(dict, "chunks", "hit_manipulability")?,
        calls,
    })
}

/// A merged reachability map (the library's `ReachMap`).
#[pyclass(frozen, module = "armkit.reach", name = "Map")]
pub struct Map {
    map: ReachMap,
}

/// Merges chunk results (dicts as `build_chunk` returns, any order) into a map.
#[pyfunction]
pub fn from_chunks(
    py: Python<'_>,
    layout: &Layout,
    chunks: Vec<Bound<'_, PyDict>>,
) -> PyResult<Map> {
    let parts = chunks
        .iter()
        .map(chunk_from_dict)
        .collect::<PyResult<Vec<_>>>()?;
    let layout = layout.layout.clone();
    let map = py
        .detach(|| ReachMap::from_chunks(layout, parts))
        .or_raise()?;
    Ok(Map { map })
}

/// Locates the boundary on the disagreeing edges leaving cells `cells`
/// (start, end) of `map` of `robot` (GIL released; `reach::refine_chunk`):
/// a dict of `bin` (uint64, the bin an edge starts from), `axis` (uint8),
/// `at` (float32, where on the edge, a fraction from the bin's centre),
/// `cells` (start, end) and `calls`. A step of a distributed refinement.
#[pyfunction]
pub fn refine_chunk<'py>(
    py: Python<'py>,
    robot: &Robot,
    map: &Map,
    cells: (usize, usize),
) -> PyResult<Bound<'py, PyDict>> {
    let found = py
        .detach(|| reach::refine_chunk(&robot.model, &map.map, cells.0..cells.1))
        .or_raise()?;
    let dict = PyDict::new(py);
    dict.set_item("cells", (found.cells.start, found.cells.end))?;
    let crossings = &found.crossings;
    let bins: Vec<u64> = crossings.iter().map(|c| c.bin).collect();
    let axes: Vec<u8> = crossings.iter().map(|c| c.axis).collect();
    let at: Vec<f32> = crossings.iter().map(|c| c.at).collect();
    dict.set_item("bin", PyArray1::from_vec(py, bins))?;
    dict.set_item("axis", PyArray1::from_vec(py, axes))?;
    dict.set_item("at", PyArray1::from_vec(py, at))?;
    dict.set_item("calls", found.calls)?;
    Ok(dict)
}

/// One dict as `refine_chunk` returns it, read back.
fn refinement_from_dict(dict: &Bound<'_, PyDict>) -> PyResult<Refinement> {
    let bins = item_vec::<u64>(dict, "parts", "bin")?;
    let axes = item_vec::<u8>(dict, "parts", "axis")?;
    let at = item_vec::<f32>(dict, "parts", "at")?;
    if bins.len() != axes.len() || bins.len() != at.len() {
        return Err(Error::invalid_argument(
            "parts",
            format!(
                "a refinement part's `bin`, `axis` and `at` differ in length ({}, {}, {})",
                bins.len(),
                axes.len(),
                at.len()
            ),
        )
        .into_py());
    }
    let cells: (usize, usize) = item_or_default(dict, "cells")?;
    let crossings = (bins.into_iter().zip(axes).zip(at))
        .map(|((bin, axis), at)| Crossing { bin, axis, at })
        .collect();
    Ok(Refinement {
        cells: cells.0..cells.1,
        crossings,
        calls: item_or_default(dict, "calls")?,
    })
}

/// `map` with the crossings of `parts` (dicts as `refine_chunk` returns,
/// any order and partition of the cells) applied
/// (`reach::apply_refinement`): the distributed refinement's merge.
#[pyfunction]
pub fn apply_refinement(py: Python<'_>, map: &Map, parts: Vec<Bound<'_, PyDict>>) -> PyResult<Map> {
    let parts = parts
        .iter()
        .map(refinement_from_dict)
        .collect::<PyResult<Vec<_>>>()?;
    let map = map.map.clone();
    let map = py
        .detach(|| reach::apply_refinement(map, parts))
        .or_raise()?;
    Ok(Map { map })
}

/// Runs `work` with the GIL released, handing it a progress reporter that
/// calls Python's `progress(done, total)` (with the GIL) until the callback
/// first raises; that error, if any, is returned instead of the result.
fn with_progress<T: Send>(
    py: Python<'_>,
    progress: &Option<Py<PyAny>>,
    work: impl FnOnce(&mut dyn FnMut(usize, usize)) -> armkit::Result<T> + Send,
) -> PyResult<T> {
    let mut callback_error: Option<PyErr> = None;
    let result = py.detach(|| {
        let mut report = |done: usize, total: usize| {
            if let (Some(callback), None) = (progress, &callback_error) {
                Python::attach(|py| {
                    if let Err(e) = callback.call1(py, (done, total)) {
                        callback_error = Some(e);
                    }
                });
            }
        };
        work(&mut report)
    });
    match callback_error {
        Some(error) => Err(error),
        None => result.or_raise(),
    }
}

/// The map `map` of `robot` with its boundary refined (the spec's
/// bisection steps; a map of the cells' boundary as it is) on `threads`
/// threads (None: every core), GIL released: the step after a distributed
/// build's merge. `progress(done, total)` as chunks finish.
#[pyfunction]
#[pyo3(signature = (robot, map, threads=None, progress=None))]
pub fn refine(
    py: Python<'_>,
    robot: &Robot,
    map: &Map,
    threads: Option<i64>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Map> {
    let threads = thread_count(threads)?;
    let map = with_progress(py, &progress, |report| {
        reach::refine(&robot.model, map.map.clone(), threads, report)
    })?;
    Ok(Map { map })
}

/// Builds the whole map locally on `threads` threads (None: every core),
/// GIL released; `progress(done, total)` is called as chunks finish.
#[pyfunction]
#[pyo3(signature = (robot, spec_json, threads=None, progress=None))]
pub fn build(
    py: Python<'_>,
    robot: &Robot,
    spec_json: &str,
    threads: Option<i64>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Map> {
    let spec = parse_spec(spec_json)?;
    let threads = thread_count(threads)?;
    let map = with_progress(py, &progress, |report| {
        reach::build(&robot.model, &spec, threads, report)
    })?;
    Ok(Map { map })
}

#[pymethods]
impl Map {
    /// The map's layout.
    #[getter]
    fn layout(&self) -> Layout {
        Layout {
            layout: self.map.layout().clone(),
        }
    }

    /// Per bin: 1 reachable, 0 not (uint8, shape (cells * orientations,)).
    #[getter]
    fn reachable<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<u8>> {
        PyArray1::from_slice(py, self.map.reachable())
    }

    /// Per bin: distinct IK solutions within the limits (uint8).
    #[getter]
    fn solutions<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<u8>> {
        PyArray1::from_slice(py, self.map.solutions())
    }

    /// Per bin: the signed distance to the boundary in 1/64 of a cell,
    /// positive where reachable (int8; +-64 away from it or unrefined).
    #[getter]
    fn boundary<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<i8>> {
        PyArray1::from_slice(py, self.map.boundary())
    }

    /// The map with `boundary` (int8 per bin, as `boundary` returns it: a
    /// refined map read back). Raises ValueError naming the first bin that
    /// does not fit.
    fn with_boundary(&self, boundary: &Bound<'_, PyArray1<i8>>) -> PyResult<Map> {
        let values = boundary.to_vec()?;
        Ok(Map {
            map: self.map.clone().with_boundary(values).or_raise()?,
        })
    }

    /// Per cell: the capability index in [0, 1].
    #[getter]
    fn capability<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vector(py, self.map.capability())
    }

    /// Per cell: the best manipulability (0 where nothing is reachable).
    #[getter]
    fn manipulability<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vector(py, self.map.manipulability())
    }

    /// IK solves (or samples) the build took.
    #[getter]
    fn calls(&self) -> u64 {
        self.map.calls()
    }

    /// Whether the pose `T` (4, 4) is reachable by the map (the library's
    /// `ReachMap::query`: the interpolation of the signed boundary distances
    /// of the 8 surrounding cell centres and the orientations around its
    /// rotation is at least 0); for `T` of shape (N, 4, 4) a bool array of
    /// shape (N,).
    #[allow(non_snake_case)]
    fn query<'py>(&self, py: Python<'py>, T: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
        self.each_pose(py, T, ReachMap::query)
    }

    /// Whether the bin of `T` (its position's cell, the orientation nearest
    /// its rotation) is reachable: the raw bit; (N, 4, 4) gives (N,).
    #[allow(non_snake_case)]
    fn bin_reachable<'py>(
        &self,
        py: Python<'py>,
        T: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.each_pose(py, T, ReachMap::bin_reachable)
    }

    /// The fraction of `reference`'s reachable bins this map also has
    /// reachable (a sampled map's coverage against an IK map of the same
    /// layout); 1 when `reference` has none. Errors: different layouts.
    fn coverage_of(&self, reference: &Map) -> PyResult<f64> {
        self.map.coverage_of(&reference.map).or_raise()
    }

    /// Capability index of the cell containing `p` (world frame, m); 0 outside the box.
    fn capability_at(&self, p: &Bound<'_, PyAny>) -> PyResult<f64> {
        let p = vector_argument(p, "p", 3)?;
        Ok(self.map.capability_at([p[0], p[1], p[2]]))
    }

    /// The index of the reachable cell nearest `p` (world frame, m), None
    /// when no cell is reachable.
    fn nearest_reachable_cell(&self, p: &Bound<'_, PyAny>) -> PyResult<Option<usize>> {
        let p = vector_argument(p, "p", 3)?;
        Ok(self.map.nearest_reachable_cell([p[0], p[1], p[2]]))
    }

    /// Inverse reachability (`armkit::reach::base_placements`): the base
    /// placements on the plane `z` (m), over the grid `x`, `y` ranges (m)
    /// with `step` (m) times `yaws` headings in [0, 2 pi), from which every
    /// task pose `T` ((4, 4) or (N, 4, 4), world frame) is reachable; rows
    /// `(x, y, z, yaw, score)` (m, rad, mean capability index), best first.
    /// Raises ValueError naming the problem, and when no placement reaches
    /// every pose.
    #[allow(non_snake_case)]
    #[pyo3(signature = (T, x, y, step, z=0.0, yaws=1))]
    #[allow(clippy::too_many_arguments)]
    fn base_placements<'py>(
        &self,
        py: Python<'py>,
        T: &Bound<'py, PyAny>,
        x: (f64, f64),
        y: (f64, f64),
        step: f64,
        z: f64,
        yaws: usize,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let array = float_array(T, "T")?;
        let shape = array.shape().to_vec();
        if !(shape == [4, 4] || (shape.len() == 3 && shape[1..] == [4, 4])) {
            return Err(shape_error("T", "(4, 4) or (N, 4, 4)", &shape));
        }
        let mut values = Vec::with_capacity(array.len());
        copy_values(&array, &mut values);
        let task = values
            .chunks_exact(16)
            .enumerate()
            .map(|(i, m)| read_pose(m, &format!("T[{i}]")))
            .collect::<armkit::Result<Vec<_>>>()
            .or_raise()?;
        let floor = FloorGrid {
            x: [x.0, x.1],
            y: [y.0, y.1],
            step,
            z,
            yaws,
        };
        let found = py
            .detach(|| reach::base_placements(&self.map, &task, &floor))
            .or_raise()?;
        new_array(py, Ix2(found.len(), 5), |out| {
            for (row, p) in out.chunks_exact_mut(5).zip(&found) {
                row.copy_from_slice(&[p.x, p.y, p.z, p.yaw, p.score]);
            }
            Ok(())
        })
    }
}

impl Map {
    /// `answer(map, pose)` for a (4, 4) pose (a bool) or each of (N, 4, 4) (a bool array).
    #[allow(non_snake_case)]
    fn each_pose<'py>(
        &self,
        py: Python<'py>,
        T: &Bound<'py, PyAny>,
        answer: fn(&ReachMap, &armkit::math::Pose) -> bool,
    ) -> PyResult<Bound<'py, PyAny>> {
        let array = float_array(T, "T")?;
        let shape = array.shape().to_vec();
        let mut values = Vec::with_capacity(array.len());
        copy_values(&array, &mut values);
        if shape == [4, 4] {
            let pose = read_pose(&values, "T").or_raise()?;
            return Ok(answer(&self.map, &pose)
                .into_pyobject(py)?
                .to_owned()
                .into_any());
        }
        if shape.len() != 3 || shape[1..] != [4, 4] {
            return Err(shape_error("T", "(4, 4) or (N, 4, 4)", &shape));
        }
        let answers = values
            .chunks_exact(16)
            .enumerate()
            .map(|(i, m)| read_pose(m, &format!("T[{i}]")).map(|pose| answer(&self.map, &pose)))
            .collect::<armkit::Result<Vec<bool>>>()
            .or_raise()?;
        Ok(PyArray1::from_vec(py, answers).into_any())
    }
}

/// Adds the `_reach` submodule to the extension module.
pub fn add_module(parent: &Bound<'_, PyModule>) -> PyResult<()> {
    let m = PyModule::new(parent.py(), "_reach")?;
    m.add_function(wrap_pyfunction!(spec_json, &m)?)?;
    m.add_function(wrap_pyfunction!(build_chunk, &m)?)?;
    m.add_function(wrap_pyfunction!(from_chunks, &m)?)?;
    m.add_function(wrap_pyfunction!(build, &m)?)?;
    m.add_function(wrap_pyfunction!(refine, &m)?)?;
    m.add_function(wrap_pyfunction!(refine_chunk, &m)?)?;
    m.add_function(wrap_pyfunction!(apply_refinement, &m)?)?;
    m.add_class::<Layout>()?;
    m.add_class::<Map>()?;
    parent.add_submodule(&m)
}
