//! Example 01: forward kinematics, the Jacobian and dexterity measures of a
//! built-in robot.
//!
//! Run: `cargo run --release --example 01_forward_kinematics`

use armkit::kinematics::{
    condition_number, forward_kinematics, jacobian, manipulability, smallest_singular_value, Data,
    JacobianFrame,
};

fn main() -> Result<(), armkit::Error> {
    let model = armkit::robots::by_name("ur5")?;
    let mut data = Data::new(&model);
    let q = [0.1, -1.2, 1.0, -0.5, 1.5, 0.3];

    let pose = *forward_kinematics(&model, &mut data, &q)?;
    let (roll, pitch, yaw) = pose.rpy();
    println!("{} at q = {q:?}", model.name());
    println!("  position (m): {:.4?}", pose.translation.as_slice());
    println!("  roll pitch yaw (rad): {roll:.4} {pitch:.4} {yaw:.4}");
    for (j, frame) in data.joint_frames().iter().enumerate() {
        println!(
            "  joint {} origin (m): {:.4?}",
            j + 1,
            frame.translation.as_slice()
        );
    }

    let j = jacobian(&model, &mut data, &q, JacobianFrame::World)?;
    println!("  Jacobian (rows vx vy vz wx wy wz):{j:.4}");
    println!(
        "  manipulability {:.5}, condition number {:.2}, smallest singular value {:.5}",
        manipulability(j),
        condition_number(j),
        smallest_singular_value(j)
    );
    Ok(())
}
