//! Example 04: inverse kinematics, numeric and closed form.
//!
//! * Numeric IK (Levenberg-Marquardt, the default) on the UR5 and the Panda,
//!   for poses computed from known configurations, with the solver's report:
//!   status, position and orientation errors, iterations, restarts, time.
//! * A target 2 m out of the UR5's reach: the solver says `NotConverged` and
//!   returns its best iterate (never a false success).
//! * The PUMA 560's closed-form (Pieper) solutions: all 8 arm configurations
//!   of one pose, each checked by forward kinematics.
//!
//! Run: `cargo run --release --example 04_inverse_kinematics`

use armkit::ik::closed_form::{ClosedFormSolver, RangeFilter};
use armkit::ik::{IkOptions, IkReport, IkSolver};
use armkit::kinematics::{forward_kinematics, Data};
use armkit::math::{Pose, Vector3};
use armkit::Model;

fn print_report(label: &str, report: &IkReport) {
    println!(
        "  {label}: {}, position error {:.2e} m, orientation error {:.2e} rad, \
         {} iterations, {} restarts, {:.0} us",
        report.status.as_str(),
        report.position_error,
        report.orientation_error,
        report.iterations,
        report.restarts,
        report.elapsed.as_secs_f64() * 1e6
    );
}

/// Solves for the pose of `q_goal`, starting from the model's neutral configuration.
fn solve_known_pose(model: &Model, q_goal: &[f64]) -> Result<(), armkit::Error> {
    let goal = *forward_kinematics(model, &mut Data::new(model), q_goal)?;
    let mut solver = IkSolver::new(model, IkOptions::default())?;
    let report = solver.solve(&goal, &model.neutral_configuration())?;
    println!(
        "{}: target {:.4?} m",
        model.name(),
        goal.translation.as_slice()
    );
    print_report("numeric", &report);
    println!(
        "    q = {:.4?} rad (the target came from {q_goal:?})",
        report.q
    );
    Ok(())
}

fn main() -> Result<(), armkit::Error> {
    let ur5 = armkit::robots::by_name("ur5")?;
    solve_known_pose(&ur5, &[0.3, -1.2, 1.4, -0.5, 1.2, 0.4])?;
    let panda = armkit::robots::by_name("panda")?;
    solve_known_pose(&panda, &[0.2, -0.5, 0.3, -2.1, 0.2, 1.9, 0.6])?;

    // Out of reach: the UR5 spans about 0.95 m.
    let far = Pose::from_translation(Vector3::new(2.0, 0.0, 0.5));
    let mut solver = IkSolver::new(&ur5, IkOptions::default())?;
    let report = solver.solve(&far, &ur5.neutral_configuration())?;
    println!("ur5: target (2, 0, 0.5) m, out of reach");
    print_report("numeric", &report);

    // PUMA 560: every solution of one pose, limits ignored to count Pieper's 8.
    let puma = armkit::robots::by_name("puma560")?;
    let q = [0.3, 0.6, -1.9, 0.4, 0.8, -0.5];
    let target = *forward_kinematics(&puma, &mut Data::new(&puma), &q)?;
    let closed_form = ClosedFormSolver::new(&puma)?;
    let all = closed_form.solve_with(&target, &q, RangeFilter::IgnoreLimits)?;
    let within = closed_form.solve(&target, &q)?;
    println!(
        "puma560: {} closed-form solutions ({} within the joint limits), nearest the start first",
        all.len(),
        within.len()
    );
    for (k, s) in all.iter().enumerate() {
        println!(
            "  {}: q = {:7.3?} rad, errors {:.0e} m, {:.0e} rad",
            k + 1,
            s.q,
            s.position_error,
            s.orientation_error
        );
    }
    Ok(())
}
