//! Singularity detection and avoidance from Python (`armkit.singularity`):
//! classification of a configuration, and seed 004's tracking of a pose
//! line through a singularity (plain, avoidance, DLS, SRI) on a fixed base.

use armkit::ik::{ChiaveriniFilter, DampedReciprocal, NakamuraDamping};
use armkit::kinematics::{jacobian, Data, JacobianFrame};
use armkit::singularity::{
    classify as library_classify, jacobian_determinant, line_through as library_line_through,
    AvoidanceOptions, ClassifyOptions, DetectionOptions, LineTask, Manipulator, Method,
    PathTracker, RegionPlan, SEPARATION,
};
use armkit::study::FITTED_DETERMINANT_THRESHOLD;
use armkit::tracking::{Feedback, TrackingOptions};
use numpy::ndarray::Dim;
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::arrays::{new_array, pose_argument, vector, vector_argument, write_pose};
use crate::errors::OrRaise;
use crate::robot::Robot;

/// The kinds of singularity at `q` (seed 004; wrist, elbow, shoulder for a
/// 6R arm with a spherical wrist). Returns a dict: `kinds` (list of
/// `"wrist"`, `"elbow"`, `"shoulder"`, `"unclassified"`; empty when
/// regular), `singular` (bool), `rank`, `singular_values` (largest first,
/// of the world-frame Jacobian), `determinant` (of a square Jacobian, else
/// None). `tolerance`: relative singular-value threshold.
#[pyfunction]
#[pyo3(signature = (robot, q, tolerance=1e-6))]
pub fn classify<'py>(
    py: Python<'py>,
    robot: &Robot,
    q: &Bound<'py, PyAny>,
    tolerance: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let model = &robot.model;
    let q = vector_argument(q, "q", model.dof())?;
    let mut data = Data::new(model);
    let found =
        library_classify(model, &mut data, &q, &ClassifyOptions { tolerance }).or_raise()?;
    let out = PyDict::new(py);
    let kinds: Vec<&str> = found.kinds.iter().map(|k| k.as_str()).collect();
    out.set_item("kinds", kinds)?;
    out.set_item("singular", found.is_singular())?;
    out.set_item("rank", found.rank)?;
    out.set_item("singular_values", vector(py, &found.singular_values))?;
    let determinant = if model.dof() == 6 {
        let j = jacobian(model, &mut data, &q, JacobianFrame::World).or_raise()?;
        Some(jacobian_determinant(j))
    } else {
        None
    };
    out.set_item("determinant", determinant)?;
    Ok(out)
}

/// The tracking method named in Python; `max_rate` (rad/s) is the clamped
/// DLS's joint speed limit.
fn tracking_method(name: &str, k: usize, max_rate: f64) -> armkit::Result<Method> {
    let method = match name {
        "plain" => Ok(Method::Plain),
        "avoidance" => Ok(Method::Avoidance { k }),
        "dls" => Ok(Method::DampedLeastSquares(NakamuraDamping::default())),
        "dls_clamped" => Ok(Method::ClampedDampedLeastSquares {
            damping: NakamuraDamping::default(),
            max_rate,
        }),
        "sri" => Ok(Method::SingularityRobust(ChiaveriniFilter::default())),
        SEPARATION => Ok(Method::SeparatedDampedReciprocal(DampedReciprocal::default())),
        other => Err(armkit::Error::invalid_argument(
            "method",
            format!(
                "expected \"plain\", \"avoidance\", \"dls\", \"dls_clamped\", \"sri\" or \"{SEPARATION}\", got \"{other}\""
            ),
        )),
    }?;
    // Before any run (the threshold's calibration is one).
    method.validate()?;
    Ok(method)
}

/// A straight pose line whose midpoint is the pose at `through` (rad or m)
/// and whose direction is the end-effector motion of the joint displacement
/// `joint_direction` there (seed 004's path construction: a `through` with
/// `q5 = 0` crosses a wrist singularity at mid-path).
/// `miss`: the line moved off that pose by `miss` along the motion the
/// Jacobian cannot make there (the left singular vector of its smallest
/// singular value, m and rad together; 0 passes through it): the near-miss
/// lines of the study's sweep. Returns `(q_start,
/// T_goal)`: the start configuration (on the branch of `through`) and the
/// end pose ((4, 4), world frame, m).
#[pyfunction]
#[pyo3(signature = (robot, through, joint_direction, miss=0.0))]
#[allow(clippy::type_complexity)]
pub fn line_through<'py>(
    py: Python<'py>,
    robot: &Robot,
    through: &Bound<'py, PyAny>,
    joint_direction: &Bound<'py, PyAny>,
    miss: f64,
) -> PyResult<(Bound<'py, PyArray1<f64>>, Bound<'py, PyArray2<f64>>)> {
    let dof = robot.model.dof();
    let through = vector_argument(through, "through", dof)?;
    let direction = vector_argument(joint_direction, "joint_direction", dof)?;
    let manipulator = Manipulator::FixedBase(&robot.model);
    let line = library_line_through(&manipulator, &through, &direction, miss).or_raise()?;
    let goal = new_array(py, Dim([4, 4]), |out| {
        write_pose(&line.goal, out);
        Ok(())
    })?;
    Ok((vector(py, &line.start), goal))
}

/// Tracks the straight pose line from FK(`q_start`) to `T_goal` ((4, 4),
/// world frame, m) in `duration` s (trapezoidal speed, `acceleration_time`
/// s of ramp; seed 004: 20 s and 4 s), every `dt` s, at the velocity level
/// with `method`: `"plain"` (J^-1), `"avoidance"` (seed 004: NR knots every
/// `k`-th pose of the singular region, joined by a C2 cubic), `"dls"`,
/// `"dls_clamped"` (DLS with its rates scaled so that none exceeds
/// `max_rate` rad/s: the damped baseline at the arm's speed limit), `"sri"`
/// or `"separation"` (singularity separation with a damped reciprocal, seed
/// 004's reference [9]; 6-joint arms). `region_plan`: how the avoidance chooses a region's knots when
/// the arm cannot reach them exactly, `"joint"` (all knots together, the
/// default), `"greedy"` (knot by knot) or `"exact"` (seed 004's step 3 as
/// printed: the Newton-Raphson knots, no rate bound). `feedback`:
/// `"next-pose"` (seed 004, eqs 26-27) or `"open-loop"` (`V = V_d`, no error
/// feedback). The region is entered when |det J| < `determinant_threshold`
/// (m^3 for a 6R arm) or a plain joint step exceeds `joint_step_threshold`
/// (rad). Without `determinant_threshold`, seed 004's rule sets it: the
/// largest |det J| where the plain run of this line jumps (the fitted
/// 0.004 m^3 when it never jumps); the dict's `determinant_threshold` and
/// `threshold_rule` (`"given"`, `"calibrated"`, `"fitted"`) say which. Returns a dict of arrays (`time`, `q`, `joint_rates`,
/// `position_error`, `orientation_error`, `determinant`, `in_region`) and
/// the summary (`status`, `peak_joint_rate`, `max_position_error`,
/// `max_orientation_error`, `final_position_error`,
/// `time_in_singular_region`, `ik_solves`). At most
/// [`armkit::tracking::MAX_PERIODS`] control periods (`duration / dt`) and
/// `k` in `1..=MAX_PERIODS`: ValueError naming `dt` or `k` before any work.
#[pyfunction]
#[pyo3(signature = (robot, q_start, T_goal, method="avoidance", k=5, duration=20.0, acceleration_time=4.0, dt=0.01, determinant_threshold=None, joint_step_threshold=0.005, max_rate=0.5, region_plan="joint", feedback="next-pose"))]
#[allow(non_snake_case, clippy::too_many_arguments)]
pub fn track_line<'py>(
    py: Python<'py>,
    robot: &Robot,
    q_start: &Bound<'py, PyAny>,
    T_goal: &Bound<'py, PyAny>,
    method: &str,
    k: usize,
    duration: f64,
    acceleration_time: f64,
    dt: f64,
    determinant_threshold: Option<f64>,
    joint_step_threshold: f64,
    max_rate: f64,
    region_plan: &str,
    feedback: &str,
) -> PyResult<Bound<'py, PyDict>> {
    let model = &robot.model;
    let dof = model.dof();
    let start = vector_argument(q_start, "q_start", dof)?;
    let goal = pose_argument(T_goal, "T_goal")?;
    let method = tracking_method(method, k, max_rate).or_raise()?;
    let region_plan: RegionPlan = region_plan.parse().or_raise()?;
    let feedback: Feedback = feedback.parse().or_raise()?;
    let task = LineTask {
        start,
        goal,
        duration,
        acceleration_time,
    };
    let options = |determinant_threshold| AvoidanceOptions {
        tracking: TrackingOptions { dt, feedback },
        detection: DetectionOptions {
            determinant_threshold,
            joint_step_threshold,
        },
        region_plan,
        ..AvoidanceOptions::default()
    };
    let tracker = |threshold| {
        PathTracker::new(
            Manipulator::FixedBase(model),
            task.clone(),
            options(threshold),
        )
    };
    let (run, threshold, rule) = py
        .detach(|| {
            // No threshold given: seed 004's rule on this line's plain run,
            // the fitted value when the plain run never jumps (as the study).
            let (threshold, rule) = match determinant_threshold {
                Some(value) => (value, "given"),
                None => match tracker(FITTED_DETERMINANT_THRESHOLD)?.calibrated_threshold()? {
                    Some(value) => (value, "calibrated"),
                    None => (FITTED_DETERMINANT_THRESHOLD, "fitted"),
                },
            };
            Ok::<_, armkit::Error>((tracker(threshold)?.run(&method)?, threshold, rule))
        })
        .or_raise()?;
    let out = PyDict::new(py);
    out.set_item("determinant_threshold", threshold)?;
    out.set_item("threshold_rule", rule)?;
    out.set_item("time", vector(py, &run.time))?;
    // The library keeps one series per joint: samples become rows here.
    out.set_item(
        "q",
        samples_by_joint(py, &run.joint_positions, run.time.len())?,
    )?;
    out.set_item(
        "joint_rates",
        samples_by_joint(py, &run.joint_rates, run.time.len())?,
    )?;
    out.set_item("position_error", vector(py, &run.position_error))?;
    out.set_item("orientation_error", vector(py, &run.orientation_error))?;
    out.set_item("determinant", vector(py, &run.determinant))?;
    out.set_item("in_region", PyArray1::from_slice(py, &run.in_region))?;
    out.set_item("status", run.status.as_str())?;
    let summary = &run.summary;
    out.set_item("peak_joint_rate", summary.peak_joint_rate)?;
    out.set_item("max_position_error", summary.max_position_error)?;
    out.set_item("max_orientation_error", summary.max_orientation_error)?;
    out.set_item("final_position_error", summary.final_position_error)?;
    out.set_item("time_in_singular_region", summary.time_in_singular_region)?;
    out.set_item("ik_solves", summary.ik_solves)?;
    Ok(out)
}

/// `series[j][i]` (joint j, sample i) as a (samples, joints) array.
fn samples_by_joint<'py>(
    py: Python<'py>,
    series: &[Vec<f64>],
    samples: usize,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let joints = series.len();
    new_array(py, Dim([samples, joints]), |out| {
        for (j, joint) in series.iter().enumerate() {
            for (i, value) in joint.iter().take(samples).enumerate() {
                out[i * joints + j] = *value;
            }
        }
        Ok(())
    })
}
