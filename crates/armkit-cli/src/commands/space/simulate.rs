//! `armkit space simulate`: a smooth random joint motion, momentum conserved.

use std::fmt::Write as _;

use armkit::math::{Pose, Rotation3, Vector6};
use armkit::space::{
    center_of_mass, generalized_jacobian, momentum, step, BaseMode, FreeFloatingState,
    SinusoidalJointMotion, SpaceData,
};

use super::csv::{joint_header, number_cells, pose_cells, pose_header, write_plots};
use super::{initial_q, step_count, SimulateArgs};
use crate::common::{print_json, CliResult, Outcome};
use crate::plot::Figure;

/// The base twist that `J*` implies for joint rates `rates` (call after
/// `generalized_jacobian`).
fn base_twist(data: &SpaceData, rates: &[f64]) -> Vector6<f64> {
    let mut twist = Vector6::zeros();
    for (j, rate) in rates.iter().enumerate() {
        twist += data.base_jacobian().column(j) * *rate;
    }
    twist
}

/// Twist of the base between two states `2 dt` apart (central difference).
fn differenced_base_twist(before: &Pose, after: &Pose, dt: f64) -> Vector6<f64> {
    let v = (after.translation - before.translation) / (2.0 * dt);
    let w = Rotation3::from_matrix_unchecked(after.rotation * before.rotation.transpose())
        .scaled_axis()
        / (2.0 * dt);
    Vector6::new(v.x, v.y, v.z, w.x, w.y, w.z)
}

pub(super) fn run_simulate(args: &SimulateArgs) -> CliResult<Outcome> {
    let (model, base) = args.system.load()?;
    let mode = BaseMode::from(args.system.base_mode);
    let q0 = initial_q(args.q.as_deref(), &model)?;
    let steps = step_count(args.duration, args.dt)?;
    let dt = args.duration / steps as f64;
    let n = model.dof();
    let motion = SinusoidalJointMotion::random(n, args.seed, args.amplitude, args.max_frequency)?;
    let mut data = SpaceData::new(&model);
    let mut states = Vec::with_capacity(steps + 1);
    let mut state = FreeFloatingState::new(base, q0);
    let com0 = center_of_mass(&model, &mut data, &state.base, &state.q)?;
    states.push(state.clone());
    let mut rates = vec![0.0; n];
    for k in 0..steps {
        // Rates at the middle of the step (zero-order hold).
        motion.rates((k as f64 + 0.5) * dt, &mut rates);
        step(&model, &mut data, &mut state, &rates, dt, mode)?;
        states.push(state.clone());
    }
    let mut csv = format!(
        "t,{},{},{},com_x,com_y,com_z,com_drift,{},linear_momentum,angular_momentum,linear_momentum_fd,angular_momentum_fd\n",
        joint_header("q", n),
        joint_header("qd", n),
        pose_header("base"),
        pose_header("ee"),
    );
    let (mut com_drift, mut worst_p, mut worst_l, mut worst_p_fd, mut worst_l_fd) =
        (0.0f64, 0.0f64, 0.0f64, 0.0f64, 0.0f64);
    // Plot series: time, COM drift, |P| and |L| by differences, base pose.
    let mut series: [Vec<f64>; 10] = Default::default();
    for (k, s) in states.iter().enumerate() {
        let t = k as f64 * dt;
        motion.rates(t, &mut rates);
        // Momentum with the base twist J* implies for the instantaneous rates.
        generalized_jacobian(&model, &mut data, &s.base, &s.q, mode)?;
        let twist = base_twist(&data, &rates);
        let com = *data.center_of_mass();
        let tip = *data.end_effector_pose();
        let p = momentum(&model, &mut data, &s.base, &s.q, &twist, &rates)?;
        // Momentum of the simulated motion itself, by central differences.
        let fd = if k > 0 && k < steps {
            let (before, after) = (&states[k - 1], &states[k + 1]);
            let q_dot: Vec<f64> = (0..n)
                .map(|j| (after.q[j] - before.q[j]) / (2.0 * dt))
                .collect();
            let twist = differenced_base_twist(&before.base, &after.base, dt);
            Some(momentum(&model, &mut data, &s.base, &s.q, &twist, &q_dot)?)
        } else {
            None
        };
        let drift = (com - com0).norm();
        com_drift = com_drift.max(drift);
        let (roll, pitch, yaw) = s.base.rpy();
        let p_base = s.base.translation - base.translation;
        let (p_fd, l_fd) = fd.map_or((f64::NAN, f64::NAN), |m| {
            (m.linear.norm(), m.angular.norm())
        });
        for (column, value) in series.iter_mut().zip([
            t, drift, p_fd, l_fd, p_base.x, p_base.y, p_base.z, roll, pitch, yaw,
        ]) {
            column.push(value);
        }
        worst_p = worst_p.max(p.linear.norm());
        worst_l = worst_l.max(p.angular.norm());
        let fd_cells = match fd {
            Some(m) => {
                worst_p_fd = worst_p_fd.max(m.linear.norm());
                worst_l_fd = worst_l_fd.max(m.angular.norm());
                format!("{},{}", m.linear.norm(), m.angular.norm())
            }
            None => ",".into(),
        };
        let _ = writeln!(
            csv,
            "{t},{},{},{},{},{},{},{drift},{},{},{},{fd_cells}",
            number_cells(&s.q),
            number_cells(&rates),
            pose_cells(&s.base),
            com.x,
            com.y,
            com.z,
            pose_cells(&tip),
            p.linear.norm(),
            p.angular.norm(),
        );
    }
    let last = &states[steps];
    let travel = (last.base.translation - base.translation).norm();
    let turn =
        Rotation3::from_matrix_unchecked(last.base.rotation * base.rotation.transpose()).angle();
    if let Some(path) = &args.output {
        crate::report::write_text(path, &csv)?;
    }
    if let Some(dir) = &args.plots {
        let [t, drift, p_fd, l_fd, x, y, z, roll, pitch, yaw] = series;
        let title = format!("{} ({mode:?}, dt = {dt} s)", model.arm().name());
        write_plots(
            dir,
            &[
                (
                    "com_drift",
                    Figure::new(
                        format!("Centre-of-mass drift, {title}"),
                        "t (s)",
                        "|r_g(t) - r_g(0)| (m)",
                        t.clone(),
                    )
                    .with_series("COM drift", drift),
                ),
                (
                    "momentum",
                    Figure::new(
                        format!("Momentum of the simulated motion (central differences), {title}"),
                        "t (s)",
                        "|P| (kg m/s), |L| (kg m^2/s)",
                        t.clone(),
                    )
                    .with_series("|P|", p_fd)
                    .with_series("|L| about the COM", l_fd),
                ),
                (
                    "base_position",
                    Figure::new(
                        format!("Base displacement, {title}"),
                        "t (s)",
                        "m",
                        t.clone(),
                    )
                    .with_series("x", x)
                    .with_series("y", y)
                    .with_series("z", z),
                ),
                (
                    "base_attitude",
                    Figure::new(format!("Base attitude, {title}"), "t (s)", "rad", t)
                        .with_series("roll", roll)
                        .with_series("pitch", pitch)
                        .with_series("yaw", yaw),
                ),
            ],
        )?;
    }
    if args.json {
        print_json(&serde_json::json!({
            "robot": model.arm().name(),
            "base_mode": format!("{mode:?}"),
            "steps": steps,
            "dt": dt,
            "max_com_drift": com_drift,
            "max_linear_momentum": worst_p,
            "max_angular_momentum": worst_l,
            "max_linear_momentum_fd": worst_p_fd,
            "max_angular_momentum_fd": worst_l_fd,
            "base_travel": travel,
            "base_rotation": turn,
        }))?;
    } else {
        println!(
            "{} on a {} kg base ({mode:?}): {steps} steps of {dt} s",
            model.arm().name(),
            model.base().mass
        );
        println!("max centre-of-mass drift: {com_drift:.3e} m");
        println!(
            "max |P|, |L| with the base twist J* implies: {worst_p:.3e} kg m/s, {worst_l:.3e} kg m^2/s"
        );
        println!(
            "max |P|, |L| of the simulated motion (central differences, O(dt^2)): {worst_p_fd:.3e} kg m/s, {worst_l_fd:.3e} kg m^2/s"
        );
        println!("base moved {travel:.6} m and turned {turn:.6} rad");
        if let Some(path) = &args.output {
            println!("wrote {}", path.display());
        }
    }
    Ok(Outcome::Success)
}
