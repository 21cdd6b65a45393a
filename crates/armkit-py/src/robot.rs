//! `armkit.Robot`: a robot model, its forward kinematics and Jacobian, one
//! configuration at a time or batched over arrays of configurations.

use std::path::PathBuf;
use std::sync::Mutex;

use armkit::dynamics::DynamicsData;
use armkit::kinematics::{
    forward_kinematics, forward_kinematics_batch, jacobian, jacobian_batch, link_frames, Data,
    JacobianFrame,
};
use armkit::math::{Pose, Vector3};
use armkit::Model;
use numpy::ndarray::Dim;
use numpy::{PyArray1, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::prelude::*;

use crate::analytic::{IkSolutions, SolutionsArguments};
use crate::arrays::{
    copy_values, float_array, new_array, pose_argument, read_flat_sequence, read_pose, shape_error,
    vector, write_jacobian, write_pose, RowMajor,
};
use crate::description::Source;
use crate::errors::{load_error, row_error, OrRaise};
use crate::ik::{IkArguments, IkEngine, IkResult};
use crate::parallel::{for_each_row, thread_count, RowsMut};
use armkit::error::read_source;
use armkit::ik::IkStatus;
use numpy::{PyArray2, PyArray3};
use pyo3::exceptions::PyValueError;

/// Targets per thread below which a batched IK stays on fewer threads.
const IK_ROWS_PER_THREAD: usize = 8;

/// A serial robot model (immutable) and a workspace for one-at-a-time calls.
///
/// Units: rad for revolute joints, m for prismatic ones; poses in the world
/// frame (the frame the model's base transform is given in), metres.
#[pyclass(frozen, module = "armkit", name = "Robot")]
pub struct Robot {
    pub(crate) model: Model,
    scratch: Mutex<Scratch>,
    /// The IK engine of the last `ik` call, reused while the options stay
    /// the same (building one clones the model).
    ik_engine: Mutex<Option<(IkArguments, IkEngine)>>,
    /// The dynamics workspace of one-state calls, made on first use.
    dynamics: Mutex<Option<DynamicsData>>,
    /// The URDF the model came from, for the 3-D view's meshes.
    pub(crate) urdf: Option<armkit_view::UrdfSource>,
    /// The text the model was built from (`description()`).
    source: Source,
}

/// Workspace of the one-at-a-time calls: the kinematics data and the joint
/// positions read from Python (no allocation per call after the first).
pub(crate) struct Scratch {
    pub data: Data,
    pub q: Vec<f64>,
}

impl Scratch {
    fn new(model: &Model) -> Self {
        Scratch {
            data: Data::new(model),
            q: Vec::with_capacity(model.dof()),
        }
    }
}

/// The Jacobian frame named in Python: `"world"` or `"end-effector"`.
pub(crate) fn jacobian_frame(name: &str) -> armkit::Result<JacobianFrame> {
    match name {
        "world" => Ok(JacobianFrame::World),
        "end-effector" | "end_effector" => Ok(JacobianFrame::EndEffector),
        other => Err(armkit::Error::invalid_argument(
            "frame",
            format!("expected \"world\" or \"end-effector\", got \"{other}\""),
        )),
    }
}

impl Robot {
    pub(crate) fn new(model: Model, source: Source) -> Self {
        let scratch = Mutex::new(Scratch::new(&model));
        Robot {
            model,
            scratch,
            ik_engine: Mutex::new(None),
            dynamics: Mutex::new(None),
            urdf: None,
            source,
        }
    }

    /// Runs `f` with the workspace; a fresh one when another thread holds it.
    pub(crate) fn with_scratch<R>(&self, f: impl FnOnce(&mut Scratch) -> R) -> R {
        match self.scratch.try_lock() {
            Ok(mut scratch) => f(&mut scratch),
            Err(_) => f(&mut Scratch::new(&self.model)),
        }
    }

    /// Runs `f` with a dynamics workspace (gravity set), the cached one
    /// unless another thread holds it. Errors: the model has no mass
    /// properties, or a coupling.
    pub(crate) fn with_dynamics<R>(
        &self,
        gravity: Vector3<f64>,
        f: impl FnOnce(&mut DynamicsData) -> armkit::Result<R>,
    ) -> armkit::Result<R> {
        match self.dynamics.try_lock() {
            Ok(mut cached) => {
                let data = match &mut *cached {
                    Some(data) => data,
                    slot => slot.insert(DynamicsData::new(&self.model)?),
                };
                data.set_gravity(gravity)?;
                f(data)
            }
            Err(_) => {
                let mut data = DynamicsData::new(&self.model)?;
                data.set_gravity(gravity)?;
                f(&mut data)
            }
        }
    }
}

#[pymethods]
impl Robot {
    /// A built-in robot by name (`armkit.builtin_robots()` lists them).
    #[staticmethod]
    fn builtin(name: &str) -> PyResult<Self> {
        let model = armkit::robots::by_name(name).or_raise()?;
        Ok(Robot::new(model, Source::Builtin(name.to_string())))
    }

    /// The serial chain from link `base` to link `tip` of a URDF file
    /// (defaults: the root link, the only leaf below the base).
    #[staticmethod]
    #[pyo3(signature = (path, base=None, tip=None))]
    fn from_urdf(path: PathBuf, base: Option<String>, tip: Option<String>) -> PyResult<Self> {
        let selection = armkit::urdf::ChainSelection { base, tip };
        let (text, source_name) = read_source(&path).map_err(|e| load_error(&path, e))?;
        let model = armkit::urdf::parse_str(&text, &source_name, &selection)
            .map_err(|e| load_error(&path, e))?;
        let source = Source::Urdf {
            text,
            selection: selection.clone(),
        };
        Ok(Robot {
            urdf: Some(armkit_view::UrdfSource {
                path,
                selection,
                package_paths: Vec::new(),
            }),
            ..Robot::new(model, source)
        })
    }

    /// The robot in 3-D at configuration `q` (default: the middle of each
    /// joint's range): an `armkit.view.View`, shown inline by Jupyter, with
    /// `save(path)` to write the HTML page (offline, three.js inlined).
    #[pyo3(signature = (q=None))]
    fn show<'py>(
        slf: &Bound<'py, Self>,
        q: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let view = slf.py().import("armkit.view")?;
        view.getattr("show")?.call1((slf, q))
    }

    /// A DH description file (TOML or JSON, as the CLI's `--robot-file`).
    #[staticmethod]
    fn from_file(path: PathBuf) -> PyResult<Self> {
        let (text, source_name) = read_source(&path).map_err(|e| load_error(&path, e))?;
        let format = armkit::description::Format::detect(&path, &text);
        armkit::description::parse_str(&text, format, &source_name)
            .map(|model| Robot::new(model, Source::Dh(text)))
            .map_err(|e| load_error(&path, e))
    }

    /// The robot as text: a built-in robot's name, the URDF text (led by a
    /// comment naming the chain when it is not the default one) or the DH
    /// description; `Robot.from_description` reads it back. This is how a
    /// robot crosses processes (pickle, Dask workers).
    fn description(&self) -> String {
        self.source.text()
    }

    /// The robot a description names (`description()`): a built-in robot's
    /// name, URDF text (starting with `<`) or a DH description in JSON
    /// (starting with `{`) or TOML.
    #[staticmethod]
    fn from_description(text: &str) -> PyResult<Self> {
        let (model, source) = Source::parse(text, "<description>").or_raise()?;
        Ok(Robot::new(model, source))
    }

    /// Pickling: the robot is rebuilt from its description.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<(Bound<'py, PyAny>, (String,))> {
        let rebuild = slf.get_type().getattr("from_description")?;
        Ok((rebuild, (slf.get().source.text(),)))
    }

    /// Degrees of freedom (moving joints).
    #[getter]
    fn dof(&self) -> usize {
        self.model.dof()
    }

    /// The model's name.
    #[getter]
    fn name(&self) -> &str {
        self.model.name()
    }

    /// Joint names, base to tip.
    #[getter]
    fn joint_names(&self) -> Vec<String> {
        self.model.joints().iter().map(|j| j.name.clone()).collect()
    }

    /// Lower position limits (rad or m; -inf where a joint has none), shape (dof,).
    #[getter]
    fn lower<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vector(py, &self.model.position_limits().0)
    }

    /// Upper position limits (rad or m; +inf where a joint has none), shape (dof,).
    #[getter]
    fn upper<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vector(py, &self.model.position_limits().1)
    }

    /// Velocity limits (rad/s or m/s), shape (dof,), or None when a joint has none.
    #[getter]
    fn velocity_limits<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        self.model.velocity_limits().map(|v| vector(py, &v))
    }

    /// The mid-range configuration (0 for joints without finite limits), shape (dof,).
    fn neutral_configuration<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vector(py, &self.model.neutral_configuration())
    }

    /// Raises ValueError naming the first joint of `q` outside its limits.
    fn check_limits(&self, q: &Bound<'_, PyAny>) -> PyResult<()> {
        let q = crate::arrays::vector_argument(q, "joint_positions", self.model.dof())?;
        self.model.check_limits(&q).or_raise()
    }

    /// Forward kinematics: the end-effector pose in the world frame as a
    /// homogeneous (4, 4) array (m) for `q` of shape (dof,), or (N, 4, 4) for
    /// `q` of shape (N, dof) (batched: GIL released, `threads` threads,
    /// default every core).
    #[pyo3(signature = (q, threads=None))]
    fn fk<'py>(&self, q: &Bound<'py, PyAny>, threads: Option<i64>) -> PyResult<Bound<'py, PyAny>> {
        let py = q.py();
        let single = |s: &mut Scratch| -> PyResult<Bound<'py, PyAny>> {
            let pose = forward_kinematics(&self.model, &mut s.data, &s.q).or_raise()?;
            Ok(new_array(py, Dim([4, 4]), |out| {
                write_pose(pose, out);
                Ok(())
            })?
            .into_any())
        };
        if let Some(pose) =
            self.with_scratch(|s| read_flat_sequence(q, &mut s.q).then(|| single(s)))
        {
            return pose;
        }
        let array = float_array(q, "q")?;
        match array.ndim() {
            1 => self.with_scratch(|s| {
                copy_values(&array, &mut s.q);
                single(s)
            }),
            2 => self.batched_blocks(
                &array,
                &[4, 4],
                threads,
                forward_kinematics_batch,
                |model, data, q, out| {
                    write_pose(forward_kinematics(model, data, q)?, out);
                    Ok(())
                },
            ),
            _ => Err(shape_error(
                "q",
                &format!("({},) or (N, {})", self.model.dof(), self.model.dof()),
                array.shape(),
            )),
        }
    }

    /// Names of the frames [`fk_all`](Self::fk_all) returns, base to tip: the
    /// chain's joints (a URDF's joint names, `q1`, `q2`, ... for a DH table).
    #[getter]
    fn frame_names(&self) -> Vec<String> {
        self.model
            .chain_joints()
            .iter()
            .map(|j| j.name.clone())
            .collect()
    }

    /// Forward kinematics of every link frame along the chain, world frame,
    /// as homogeneous (4, 4) arrays (m): (n, 4, 4) for `q` of shape (dof,),
    /// (N, n, 4, 4) for (N, dof) (batched as `fk`), n = `len(frame_names)`.
    /// Frame i is the frame of the link joint i moves: a URDF's child link
    /// frame (Pinocchio's `oMi`), a DH table's frame i (RTB's `fkine_all`
    /// without the base). The end effector is `fk(q)`.
    #[pyo3(signature = (q, threads=None))]
    fn fk_all<'py>(
        &self,
        q: &Bound<'py, PyAny>,
        threads: Option<i64>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let py = q.py();
        let n = self.model.chain_joints().len();
        let all =
            |model: &Model, data: &mut Data, q: &[f64], out: &mut [f64]| -> armkit::Result<()> {
                let mut frames = vec![Pose::identity(); n];
                link_frames(model, data, q, &mut frames)?;
                for (frame, out) in frames.iter().zip(out.chunks_exact_mut(16)) {
                    write_pose(frame, out);
                }
                Ok(())
            };
        let array = float_array(q, "q")?;
        match array.ndim() {
            1 => self.with_scratch(|s| {
                copy_values(&array, &mut s.q);
                let q = std::mem::take(&mut s.q);
                let result = new_array(py, Dim([n, 4, 4]), |out| {
                    all(&self.model, &mut s.data, &q, out).or_raise()
                });
                s.q = q;
                Ok(result?.into_any())
            }),
            2 => self.batched(&array, &[n, 4, 4], threads, all),
            _ => Err(shape_error(
                "q",
                &format!("({},) or (N, {})", self.model.dof(), self.model.dof()),
                array.shape(),
            )),
        }
    }

    /// Geometric Jacobian of the end-effector frame, rows
    /// `[vx, vy, vz, wx, wy, wz]` (m/s and rad/s per unit joint velocity) in
    /// the axes of `frame` (`"world"` or `"end-effector"`): (6, dof) for `q`
    /// of shape (dof,), (N, 6, dof) for (N, dof) (batched as `fk`).
    #[pyo3(signature = (q, frame="world", threads=None))]
    fn jacobian<'py>(
        &self,
        q: &Bound<'py, PyAny>,
        frame: &str,
        threads: Option<i64>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let py = q.py();
        let frame = jacobian_frame(frame).or_raise()?;
        let dof = self.model.dof();
        let single = |s: &mut Scratch| -> PyResult<Bound<'py, PyAny>> {
            let j = jacobian(&self.model, &mut s.data, &s.q, frame).or_raise()?;
            Ok(new_array(py, Dim([6, dof]), |out| {
                write_jacobian(j, out);
                Ok(())
            })?
            .into_any())
        };
        if let Some(j) = self.with_scratch(|s| read_flat_sequence(q, &mut s.q).then(|| single(s))) {
            return j;
        }
        let array = float_array(q, "q")?;
        match array.ndim() {
            1 => self.with_scratch(|s| {
                copy_values(&array, &mut s.q);
                single(s)
            }),
            2 => self.batched_blocks(
                &array,
                &[6, dof],
                threads,
                |model, batch, q, out| jacobian_batch(model, batch, q, frame, out),
                |model, data, q, out| {
                    write_jacobian(jacobian(model, data, q, frame)?, out);
                    Ok(())
                },
            ),
            _ => Err(shape_error(
                "q",
                &format!("({dof},) or (N, {dof})"),
                array.shape(),
            )),
        }
    }

    /// Inverse kinematics of one end-effector pose `T` ((4, 4) homogeneous,
    /// world frame, m) from `q0` (default: mid-range). `solver`: `"auto"`
    /// (the library's: analytic where the arm's class allows, else
    /// Levenberg-Marquardt), `"analytic"` (every analytic solution, the
    /// nearest exact one returned; alias `"closed-form"`), `"lm"`, `"nr"`,
    /// `"dls"` or `"sri"`: the names of `armkit ik --solver`. Tolerances in m
    /// and rad; `time_budget` in s (None: no budget); `task_weights` of
    /// `[x, y, z, rx, ry, rz]` (a zero masks the component). Not converging
    /// is `result.status == "not_converged"`, never an exception.
    #[pyo3(signature = (T, q0=None, solver="auto", position_tolerance=1e-6, orientation_tolerance=1e-6, max_iterations=50, max_restarts=1000, time_budget=Some(0.005), seed=0, task_weights=None))]
    #[pyo3(
        text_signature = "(self, T, q0=None, solver='auto', position_tolerance=1e-06, orientation_tolerance=1e-06, max_iterations=50, max_restarts=1000, time_budget=0.005, seed=0, task_weights=None)"
    )]
    #[allow(non_snake_case, clippy::too_many_arguments)]
    fn ik(
        &self,
        py: Python<'_>,
        T: &Bound<'_, PyAny>,
        q0: Option<&Bound<'_, PyAny>>,
        solver: &str,
        position_tolerance: f64,
        orientation_tolerance: f64,
        max_iterations: usize,
        max_restarts: usize,
        time_budget: Option<f64>,
        seed: u64,
        task_weights: Option<Vec<f64>>,
    ) -> PyResult<IkResult> {
        let arguments = IkArguments::new(
            solver,
            position_tolerance,
            orientation_tolerance,
            max_iterations,
            max_restarts,
            time_budget,
            seed,
            task_weights,
        )
        .or_raise()?;
        let target = pose_argument(T, "T")?;
        let start = match q0 {
            None => self.model.neutral_configuration(),
            Some(q0) => {
                let mut values = Vec::with_capacity(self.model.dof());
                copy_values(&float_array(q0, "q0")?, &mut values);
                values
            }
        };
        let outcome = match self.ik_engine.try_lock() {
            Ok(mut cached) => {
                let engine = match &mut *cached {
                    Some((used, engine)) if *used == arguments => engine,
                    slot => {
                        let engine = IkEngine::new(&self.model, &arguments).or_raise()?;
                        &mut slot.insert((arguments, engine)).1
                    }
                };
                py.detach(|| engine.solve(&target, &start))
            }
            // Another thread is solving with this robot: a fresh engine.
            Err(_) => {
                let mut engine = IkEngine::new(&self.model, &arguments).or_raise()?;
                py.detach(|| engine.solve(&target, &start))
            }
        }
        .or_raise()?;
        IkResult::new(py, outcome, self.model.dof())
    }

    /// Inverse kinematics of many poses: `Ts` of shape (N, 4, 4) (world
    /// frame, m), `q0` of shape (dof,) (one start for all), (N, dof) (one
    /// per target) or None (mid-range). Options as `ik`. Returns `(Q,
    /// converged)`: joint positions of shape (N, dof) (the best effort where
    /// not converged, always within the limits) and a bool array of shape
    /// (N,). GIL released, `threads` threads (default every core).
    #[pyo3(signature = (Ts, q0=None, solver="auto", position_tolerance=1e-6, orientation_tolerance=1e-6, max_iterations=50, max_restarts=1000, time_budget=Some(0.005), seed=0, task_weights=None, threads=None))]
    #[pyo3(
        text_signature = "(self, Ts, q0=None, solver='auto', position_tolerance=1e-06, orientation_tolerance=1e-06, max_iterations=50, max_restarts=1000, time_budget=0.005, seed=0, task_weights=None, threads=None)"
    )]
    #[allow(non_snake_case, clippy::too_many_arguments, clippy::type_complexity)]
    fn ik_batch<'py>(
        &self,
        py: Python<'py>,
        Ts: &Bound<'py, PyAny>,
        q0: Option<&Bound<'py, PyAny>>,
        solver: &str,
        position_tolerance: f64,
        orientation_tolerance: f64,
        max_iterations: usize,
        max_restarts: usize,
        time_budget: Option<f64>,
        seed: u64,
        task_weights: Option<Vec<f64>>,
        threads: Option<i64>,
    ) -> PyResult<(Bound<'py, PyArray2<f64>>, Bound<'py, PyArray1<bool>>)> {
        let arguments = IkArguments::new(
            solver,
            position_tolerance,
            orientation_tolerance,
            max_iterations,
            max_restarts,
            time_budget,
            seed,
            task_weights,
        )
        .or_raise()?;
        let threads = thread_count(threads)?;
        let dof = self.model.dof();
        let targets = float_array(Ts, "Ts")?;
        let shape = targets.shape();
        if shape.len() != 3 || shape[1..] != [4, 4] {
            return Err(shape_error("Ts", "(N, 4, 4)", shape));
        }
        let rows = shape[0];
        let targets = RowMajor::new(&targets)?;
        let (starts, start_stride) = match q0 {
            None => (self.model.neutral_configuration(), 0),
            Some(q0) => {
                let array = float_array(q0, "q0")?;
                let stride = match array.shape() {
                    [n] if *n == dof => 0,
                    [n, m] if *n == rows && *m == dof => dof,
                    other => {
                        return Err(shape_error(
                            "q0",
                            &format!("({dof},) or ({rows}, {dof})"),
                            other,
                        ))
                    }
                };
                let mut values = Vec::with_capacity(array.len());
                copy_values(&array, &mut values);
                (values, stride)
            }
        };
        let engine = IkEngine::new(&self.model, &arguments).or_raise()?;
        let q_out = PyArray2::<f64>::zeros(py, [rows, dof], false);
        let converged_out = PyArray1::<bool>::zeros(py, rows, false);
        {
            // SAFETY: both arrays are new (no other view exists) and C-contiguous.
            let (q_values, converged_values) =
                unsafe { (q_out.as_slice_mut(), converged_out.as_slice_mut()) };
            let to_error = |e: numpy::AsSliceError| {
                PyValueError::new_err(format!("allocating the result: {e}"))
            };
            let q_values = q_values.map_err(to_error)?;
            let converged_values = converged_values.map_err(to_error)?;
            let targets = targets.as_slice();
            py.detach(|| {
                for_each_row(
                    rows,
                    threads,
                    IK_ROWS_PER_THREAD,
                    (
                        RowsMut::new(q_values, dof),
                        RowsMut::new(converged_values, 1),
                    ),
                    || engine.clone(),
                    |engine, row, local, (q_rows, converged_rows)| {
                        let target = read_pose(&targets[16 * row..16 * (row + 1)], "T")?;
                        let start = &starts[row * start_stride..row * start_stride + dof];
                        let outcome = engine.solve(&target, start)?;
                        q_rows.row(local).copy_from_slice(&outcome.q);
                        converged_rows.row(local)[0] = outcome.status == IkStatus::Converged;
                        Ok(())
                    },
                )
            })
            .map_err(|e| row_error("Ts", e.row, &e.error))?;
        }
        Ok((q_out, converged_out))
    }

    /// Every analytic IK solution of `T` (4 x 4, world frame, m) within the
    /// joint limits, exact ones first, each group nearest `q0` first
    /// (default: mid-range): the route of `armkit ik --solver analytic`.
    /// `representatives`: `"nearest"` (the default: each distinct solution
    /// once, its 2 pi multiple nearest `q0`) or `"every"` (every 2 pi
    /// multiple within the joint limits), as `--representatives`. `search`: `"elimination"` (the default
    /// and the only route: closed forms, every other 6R arm by algebraic
    /// elimination); `"1d"` and `"2d"` (retired searches) are errors. 7-joint
    /// arms: the elbow angle of a spherical-shoulder-elbow-wrist arm, else a
    /// held joint; `fixed_joint` (0-based, like a numpy index) holds that
    /// joint; `parameter` is the elbow angle (rad) or the held joint's value
    /// (default: `q0`'s); `sweep` N solves at N values of it (the elbow
    /// angle's circle or the held joint's range) together. Returns an
    /// `IkSolutions` (`q` (k, dof), `exact` (k,), `fits`, `position_error`,
    /// `orientation_error`, `arm_class`, `method`). An arm without analytic
    /// solver raises `ValueError` naming its class.
    #[pyo3(signature = (T, q0=None, search="elimination", fixed_joint=None, parameter=None, sweep=None, representatives="nearest"))]
    #[allow(non_snake_case, clippy::too_many_arguments)]
    fn ik_solutions(
        &self,
        py: Python<'_>,
        T: &Bound<'_, PyAny>,
        q0: Option<&Bound<'_, PyAny>>,
        search: &str,
        fixed_joint: Option<i64>,
        parameter: Option<f64>,
        sweep: Option<i64>,
        representatives: &str,
    ) -> PyResult<IkSolutions> {
        let arguments =
            SolutionsArguments::new(search, fixed_joint, parameter, sweep, representatives)
                .or_raise()?;
        let target = pose_argument(T, "T")?;
        let start = match q0 {
            None => self.model.neutral_configuration(),
            Some(q0) => crate::arrays::vector_argument(q0, "q0", self.model.dof())?,
        };
        crate::analytic::ik_solutions(py, &self.model, &arguments, &target, &start)
    }

    /// The arm's analytic class: `(name, description)`, as `armkit ik
    /// --explain` (a 7-joint arm's with its held joint, 0-based, when the
    /// whole arm has no class). Arms without analytic solver have a class too
    /// (`ik_solutions` raises naming it).
    fn arm_class(&self) -> PyResult<(&'static str, String)> {
        crate::analytic::arm_class(&self.model).or_raise()
    }

    /// The IK benchmark's targets (`armkit bench-ik`'s protocol): `count`
    /// configurations drawn uniformly within the limits (ChaCha8, `seed`)
    /// and their end-effector poses. Returns `(Q, Ts)` of shapes (count, dof)
    /// and (count, 4, 4); every target is reachable.
    #[pyo3(signature = (count, seed=42))]
    #[allow(clippy::type_complexity)]
    fn benchmark_targets<'py>(
        &self,
        py: Python<'py>,
        count: usize,
        seed: u64,
    ) -> PyResult<(Bound<'py, PyArray2<f64>>, Bound<'py, PyArray3<f64>>)> {
        let targets = armkit::ik::benchmark_targets(&self.model, count, seed).or_raise()?;
        let dof = self.model.dof();
        let q = new_array(py, Dim([count, dof]), |out| {
            for (row, (q, _)) in out.chunks_exact_mut(dof.max(1)).zip(&targets) {
                row.copy_from_slice(q);
            }
            Ok(())
        })?;
        let poses = new_array(py, Dim([count, 4, 4]), |out| {
            for (row, (_, pose)) in out.chunks_exact_mut(16).zip(&targets) {
                write_pose(pose, row);
            }
            Ok(())
        })?;
        Ok((q, poses))
    }

    fn __repr__(&self) -> String {
        format!("Robot('{}', dof={})", self.model.name(), self.model.dof())
    }
}
