//! Example 08: a free-floating space manipulator (seed 004's 6R arm on a
//! 400 kg satellite).
//!
//! * The generalized Jacobian `J*` (the base reacts to the arm's motion)
//!   against the fixed-base Jacobian of the same arm, in both base modes:
//!   attitude held by the spacecraft (seed 004) and fully free floating.
//! * A 2 s joint motion simulated in both modes: the base moves (and, free
//!   floating, turns), the system's centre of mass stays put, and the tool
//!   ends up away from where a fixed-base arm would have put it.
//!
//! Run: `cargo run --release --example 08_space_robot`

use armkit::kinematics::{forward_kinematics, jacobian, Data, JacobianFrame};
use armkit::math::{rotation_angle, DVector, Pose, Vector6};
use armkit::robots::space6r_free_floating;
use armkit::space::{
    center_of_mass, end_effector_pose, generalized_jacobian, step, BaseMode, FreeFloatingState,
    SpaceData,
};

/// Prints the tool's linear (m/s) and angular (rad/s) velocity.
fn print_twist(label: &str, twist: &Vector6<f64>) {
    let v = twist.as_slice();
    println!(
        "{label}: tool velocity {:.4?} m/s, angular velocity {:.4?} rad/s",
        &v[..3],
        &v[3..]
    );
}

fn main() -> Result<(), armkit::Error> {
    let system = space6r_free_floating()?;
    let arm = system.arm();
    println!(
        "{} on a {:.0} kg satellite: {:.0} kg in all",
        arm.name(),
        system.base().mass,
        system.total_mass()
    );
    let q0 = vec![0.1, 0.5, -0.4, 0.2, 0.6, 0.0];
    let rates = [0.2, -0.3, 0.25, 0.4, -0.2, 0.3]; // rad/s, held for 2 s
    let mut data = SpaceData::new(&system);

    // Fixed base: the arm's own Jacobian, turned from the mount frame into
    // the inertial frame (base at the origin, arm mounted on top of it).
    let base = Pose::identity();
    let mount = base * system.base().mount;
    let mut arm_data = Data::new(arm);
    let mut j_fixed = jacobian(arm, &mut arm_data, &q0, JacobianFrame::World)?.clone();
    for block in [0, 3] {
        let turned = mount.rotation * j_fixed.fixed_rows::<3>(block);
        j_fixed.fixed_rows_mut::<3>(block).copy_from(&turned);
    }
    let rate_vector = DVector::from_column_slice(&rates);
    print_twist("fixed base", &(&j_fixed * &rate_vector));

    for mode in [BaseMode::AttitudeHeld, BaseMode::FreeFloating] {
        let j_star = generalized_jacobian(&system, &mut data, &base, &q0, mode)?.clone();
        print_twist(&format!("{mode:?}"), &(&j_star * &rate_vector));
        println!(
            "  largest entry of J* - J: {:.3} (m/s or rad/s per rad/s)",
            (&j_star - &j_fixed).amax()
        );

        // Simulate 2 s at 100 Hz.
        let mut state = FreeFloatingState::new(base, q0.clone());
        let com_before = center_of_mass(&system, &mut data, &state.base, &state.q)?;
        for _ in 0..200 {
            step(&system, &mut data, &mut state, &rates, 0.01, mode)?;
        }
        let com_after = center_of_mass(&system, &mut data, &state.base, &state.q)?;
        let tip = end_effector_pose(&system, &mut data, &state.base, &state.q)?;
        let tip_on_fixed_base = mount * *forward_kinematics(arm, &mut arm_data, &state.q)?;
        println!(
            "  after 2 s: base moved {:.1} mm and turned {:.4} rad; centre of mass drift {:.1e} m",
            1e3 * state.base.translation.norm(),
            rotation_angle(&state.base.rotation),
            (com_after - com_before).norm()
        );
        println!(
            "  the tool is {:.1} mm from where a fixed-base arm would have put it",
            1e3 * (tip.translation - tip_on_fixed_base.translation).norm()
        );
    }
    Ok(())
}
