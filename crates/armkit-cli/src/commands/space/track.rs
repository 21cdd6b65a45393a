//! `armkit space track`: resolved-rate tracking of a line with J*.

use std::fmt::Write as _;

use armkit::space::{
    generalized_jacobian, track_pose_path, BaseMode, FreeFloatingState, SpaceData,
};
use armkit::tracking::{LeastSquares, TimedPath, TrackingOptions, TrackingStatus};
use armkit::trajectory::{CartesianTrajectory, TimeLaw};

use super::csv::{joint_header, number_cells, pose_cells, pose_header, write_plots};
use super::{initial_q, step_count, TrackArgs};
use crate::common::{parse_pose, print_json, CliError, CliResult, Outcome};
use crate::plot::Figure;

pub(super) fn run_track(args: &TrackArgs) -> CliResult<Outcome> {
    let (model, base) = args.system.load()?;
    let mode = BaseMode::from(args.system.base_mode);
    let q0 = initial_q(args.q.as_deref(), &model)?;
    let goal = parse_pose(&args.goal, "--goal")?;
    step_count(args.duration, args.dt)?;
    if !(args.accel_time.is_finite()
        && args.accel_time >= 0.0
        && 2.0 * args.accel_time <= args.duration)
    {
        return Err(CliError(format!(
            "--accel-time: must be in [0, duration / 2] = [0, {}] s, got {}",
            args.duration / 2.0,
            args.accel_time
        )));
    }
    let mut data = SpaceData::new(&model);
    let initial = FreeFloatingState::new(base, q0);
    generalized_jacobian(&model, &mut data, &initial.base, &initial.q, mode)?;
    let start = *data.end_effector_pose();
    let (duration, accel) = (args.duration, args.accel_time);
    // Seed 004's trapezoidal speed along the line (constant speed without
    // an acceleration phase).
    let law = if accel > 0.0 {
        TimeLaw::Trapezoidal {
            acceleration_time: accel,
        }
    } else {
        TimeLaw::Linear
    };
    let path = CartesianTrajectory::line(start, goal, law, duration)?;
    let options = TrackingOptions {
        dt: args.dt,
        ..TrackingOptions::default()
    };
    let damping = LeastSquares {
        damping: args.damping,
    };
    let report = track_pose_path(&model, &mut data, mode, &initial, &path, damping, &options)?;
    let n = model.dof();
    if let Some(output) = &args.output {
        let mut csv = format!(
            "t,{},{},{},{},{},position_error,orientation_error\n",
            joint_header("q", n),
            joint_header("qd", n),
            pose_header("base"),
            pose_header("ee"),
            pose_header("goal"),
        );
        for s in &report.samples {
            let _ = writeln!(
                csv,
                "{},{},{},{},{},{},{},{}",
                s.time,
                number_cells(&s.q),
                number_cells(&s.joint_rates),
                pose_cells(&s.base),
                pose_cells(&s.end_effector),
                pose_cells(&path.pose(s.time)),
                s.position_error,
                s.orientation_error
            );
        }
        crate::report::write_text(output, &csv)?;
    }
    if let Some(dir) = &args.plots {
        let t: Vec<f64> = report.samples.iter().map(|s| s.time).collect();
        let title = format!("{} ({mode:?}, dt = {} s)", model.arm().name(), args.dt);
        let mut rates = Figure::new(format!("Joint rates, {title}"), "t (s)", "rad/s", t.clone());
        for j in 0..n {
            rates = rates.with_series(
                format!("q{}", j + 1),
                report.samples.iter().map(|s| s.joint_rates[j]).collect(),
            );
        }
        let errors = Figure::new(format!("Tracking error, {title}"), "t (s)", "m, rad", t)
            .with_series(
                "position (m)",
                report.samples.iter().map(|s| s.position_error).collect(),
            )
            .with_series(
                "orientation (rad)",
                report.samples.iter().map(|s| s.orientation_error).collect(),
            );
        write_plots(dir, &[("tracking_error", errors), ("joint_rates", rates)])?;
    }
    let max_rate = report
        .samples
        .iter()
        .flat_map(|s| s.joint_rates.iter())
        .fold(0.0f64, |m, r| m.max(r.abs()));
    let status = report.status.to_string();
    if args.json {
        print_json(&serde_json::json!({
            "robot": model.arm().name(),
            "base_mode": format!("{mode:?}"),
            "status": status,
            "samples": report.samples.len(),
            "max_position_error": report.max_position_error,
            "max_orientation_error": report.max_orientation_error,
            "max_joint_rate": max_rate,
            "final_q": report.samples.last().map(|s| s.q.clone()),
        }))?;
    } else {
        println!(
            "{} on a {} kg base ({mode:?}): tracking {duration} s, {status}",
            model.arm().name(),
            model.base().mass
        );
        println!(
            "max position error {:.3e} m, max orientation error {:.3e} rad, max |joint rate| {max_rate:.4} rad/s",
            report.max_position_error, report.max_orientation_error
        );
        if let Some(path) = &args.output {
            println!("wrote {}", path.display());
        }
    }
    Ok(match report.status {
        TrackingStatus::Completed => Outcome::Success,
        _ => Outcome::NotConverged,
    })
}
