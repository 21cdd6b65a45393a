//! Example 06: joint trajectories and seed 002's continuous path.
//!
//! * Seed 004's trapezoidal timing (20 s with 4 s of acceleration and of
//!   deceleration) on the 6R space arm: cruise speeds and a few samples.
//! * The fastest rest-to-rest quintic of the Panda under its data-sheet
//!   velocity and acceleration limits, sampled at 100 Hz into one reused
//!   buffer (`sample_into` allocates nothing), with forward kinematics at
//!   every sample.
//! * Seed 002's continuous path on the 4-DOF `arm4`: a 0.3 m straight line,
//!   IK at the knots (closed form), one polynomial per segment, and the
//!   adaptive segmentation (Fig 6) choosing the number of segments for a
//!   0.1 mm tolerance.
//!
//! Run: `cargo run --release --example 06_trajectory`

use armkit::kinematics::{forward_kinematics, Data};
use armkit::math::Vector3;
use armkit::trajectory::JointState;
use armkit::trajectory::{self, ProfileShape};
use armkit::trajectory::{check_limits, peak_rates, TrajectoryLimits};
use armkit::trajectory::{
    measure_path_error, plan_continuous_path, ContinuousPathOptions, PathTolerance,
};
use armkit::trajectory::{path_ik_for, IkTask};
use armkit::trajectory::{CartesianTrajectory, LinePath, TimeLaw};

fn main() -> Result<(), armkit::Error> {
    // Seed 004's trapezoid on space6r.
    let q0 = [0.0, -0.5, 0.3, 0.0, 0.8, 0.0];
    let qf = [1.2, -0.1, 0.9, 0.6, 0.2, -0.4];
    let trapezoid = trajectory::trapezoidal(&q0, &qf, 20.0, 4.0)?;
    let peaks = peak_rates(&trapezoid);
    println!(
        "trapezoid, 20 s with 4 s ramps: cruise speeds {:.4?} rad/s, accelerations {:.4?} rad/s^2",
        peaks.velocity, peaks.acceleration
    );
    let mut state = JointState::zeros(6);
    for t in [0.0, 2.0, 4.0, 10.0, 18.0, 20.0] {
        trapezoid.sample_into(t, &mut state)?;
        println!(
            "  t = {t:4.1} s: q1 = {:.4} rad, q1' = {:.4} rad/s, q1'' = {:.4} rad/s^2",
            state.position[0], state.velocity[0], state.acceleration[0]
        );
    }

    // The fastest quintic of the Panda under its own limits.
    let panda = armkit::robots::by_name("panda")?;
    let limits = TrajectoryLimits::from_model(&panda);
    let from = [0.0, -0.3, 0.0, -2.2, 0.0, 2.0, 0.8];
    let to = [1.2, 0.4, -0.5, -1.5, 0.6, 1.4, -0.3];
    let quintic = trajectory::minimum_time(ProfileShape::Quintic, &from, &to, &limits)?;
    let peaks = peak_rates(&quintic);
    let (joint, ratio) = (0..panda.dof())
        .map(|j| {
            (
                j,
                (peaks.velocity[j] / limits.velocity[j])
                    .max(peaks.acceleration[j] / limits.acceleration[j]),
            )
        })
        .fold((0, 0.0), |best, c| if c.1 > best.1 { c } else { best });
    println!(
        "panda minimum-time quintic: {:.3} s; joint {} sets it ({:.1} % of its limit); {} limit violations",
        quintic.duration(),
        joint + 1,
        100.0 * ratio,
        check_limits(&quintic, &limits)?.len()
    );

    // Sample at 100 Hz into one buffer; FK at each sample gives the tool's path.
    let mut data = Data::new(&panda);
    let mut state = JointState::zeros(panda.dof());
    let steps = (quintic.duration() * 100.0).ceil() as usize;
    let mut previous: Option<(f64, Vector3<f64>)> = None;
    let (mut length, mut top_speed) = (0.0, 0.0_f64);
    for k in 0..=steps {
        let t = quintic.duration() * k as f64 / steps as f64;
        quintic.sample_into(t, &mut state)?;
        let p = forward_kinematics(&panda, &mut data, &state.position)?.translation;
        if let Some((t_prev, p_prev)) = previous {
            let d = (p - p_prev).norm();
            length += d;
            top_speed = top_speed.max(d / (t - t_prev));
        }
        previous = Some((t, p));
    }
    println!(
        "  {} samples: the tool travels {length:.3} m, at up to {top_speed:.2} m/s",
        steps + 1
    );

    // Seed 002: a 0.3 m line on arm4 (the tool at x = -0.15 .. +0.15 m, y = -0.30 m),
    // trapezoidal timing over 2 s, position tolerance 0.1 mm (arm4 reaches a 4-D
    // subset of poses, so the orientation is left free).
    let arm4 = armkit::robots::by_name("arm4")?;
    let mut data = Data::new(&arm4);
    let q_start = [0.33824988933280115, -1.9358832167391893, 0.3, 0.4];
    let q_end = [1.2655451073344133, -1.935883216739189, 0.3, 0.4];
    let start = *forward_kinematics(&arm4, &mut data, &q_start)?;
    let end = *forward_kinematics(&arm4, &mut data, &q_end)?;
    let timing = TimeLaw::Trapezoidal {
        acceleration_time: 0.5,
    }
    .timing(2.0)?;
    let path = CartesianTrajectory::new(LinePath::new(start, end)?, timing)?;
    let (mut ik, method) = path_ik_for(&arm4, IkTask::Position)?;
    let options = ContinuousPathOptions {
        tolerance: PathTolerance::Position(1e-4),
        ..ContinuousPathOptions::default()
    };
    let report = plan_continuous_path(&arm4, &path, &mut *ik, &q_start, &options)?;
    let dense = measure_path_error(&arm4, &report.trajectory, &path, 100)?;
    println!(
        "arm4 continuous path, {:.3} m line in 2 s, IK: {method}",
        (end.translation - start.translation).norm()
    );
    println!(
        "  {:?}: {} segments after {} passes ({} IK solves); error {:.4} mm at the check points, {:.4} mm at 100 points per segment",
        report.status,
        report.trajectory.segment_count(),
        report.passes,
        report.ik_solves,
        1e3 * report.checked_error.position,
        1e3 * dense.position
    );
    Ok(())
}
