//! Example 03: a robot from a URDF file, checked against the built-in DH model.
//!
//! Loads the Franka Panda's chain `panda_link0 -> panda_link8` (the flange)
//! from `tests/data/urdf/panda.urdf`, computes forward kinematics and the
//! Jacobian, and compares both with the built-in modified-DH `panda` with its
//! tool taken off (the built-in model adds RTB's tool, 0.103 m and -45 deg
//! beyond the flange).
//!
//! Run: `cargo run --release --example 03_urdf`

use armkit::kinematics::{forward_kinematics, jacobian, manipulability, Data, JacobianFrame};
use armkit::math::rotation_angle;
use armkit::urdf::{self, ChainSelection};
use armkit::Model;

const PANDA_URDF: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../tests/data/urdf/panda.urdf"
);

fn main() -> Result<(), armkit::Error> {
    let from_urdf = urdf::load(
        PANDA_URDF,
        &ChainSelection::between("panda_link0", "panda_link8"),
    )?;
    println!(
        "{}: {} joints from the URDF",
        from_urdf.name(),
        from_urdf.dof()
    );
    for joint in from_urdf.joints() {
        println!(
            "  {:13} [{:7.4}, {:7.4}] rad, {:.3} rad/s",
            joint.name,
            joint.limits.lower,
            joint.limits.upper,
            joint.limits.velocity.unwrap_or(f64::INFINITY)
        );
    }

    // The built-in DH panda without its tool: its end-effector is the flange.
    let builtin = armkit::robots::by_name("panda")?;
    let (convention, links) = builtin
        .dh_table()
        .ok_or_else(|| armkit::Error::invalid_argument("panda", "has no DH table"))?;
    let flange = Model::from_dh("panda-flange", convention, links)?;

    let q = [0.3, -0.4, 0.2, -2.0, 0.1, 1.8, 0.7];
    from_urdf.check_limits(&q)?;
    let mut urdf_data = Data::new(&from_urdf);
    let mut dh_data = Data::new(&flange);
    let a = *forward_kinematics(&from_urdf, &mut urdf_data, &q)?;
    let b = *forward_kinematics(&flange, &mut dh_data, &q)?;
    println!("q = {q:?} rad");
    println!(
        "  flange from the URDF (m): {:.5?}",
        a.translation.as_slice()
    );
    println!(
        "  flange from DH (m):       {:.5?}",
        b.translation.as_slice()
    );
    println!(
        "  difference: {:.1e} m, {:.1e} rad",
        (a.translation - b.translation).norm(),
        rotation_angle(&(a.rotation * b.rotation.transpose()))
    );

    let ja = jacobian(&from_urdf, &mut urdf_data, &q, JacobianFrame::World)?.clone();
    let jb = jacobian(&flange, &mut dh_data, &q, JacobianFrame::World)?;
    println!(
        "  Jacobians (6 x 7): largest entry difference {:.1e}, manipulability {:.5} (URDF) vs {:.5} (DH)",
        (&ja - jb).amax(),
        manipulability(&ja),
        manipulability(jb)
    );

    // The built-in tool sits 0.103 m further along the flange's z axis.
    let tool = *forward_kinematics(&builtin, &mut Data::new(&builtin), &q)?;
    println!(
        "  built-in panda's tool point is {:.4} m beyond the flange",
        (tool.translation - a.translation).norm()
    );
    Ok(())
}
