//! Example 05: sharing one end-effector twist among the 9 joints of a gantry.
//!
//! The 9-DOF gantry (`gantry9`: rail, beam, ram, then a 6R arm) has three
//! spare joints. For one twist, the same weighted least-norm solver gives:
//! * minimum norm (all weights 1, the pseudo-inverse);
//! * seed 000's priorities (rail 100, beam joints 10, arm 1: a heavy axis
//!   moves less);
//! * seed 001's energy-optimal weights `a_i = tau_i^2` from the torques that
//!   hold a 50 N payload and the links' own weight;
//! * the minimum norm with the rail locked.
//!
//! Each is printed with seed 001's energy measure `F = sum (q_dot_i tau_i)^2`
//! (eq 9, W^2), which the energy-optimal weights minimise.
//!
//! Run: `cargo run --release --example 05_redundancy`

use armkit::kinematics::{jacobian, Data, JacobianFrame};
use armkit::math::{DVector, Vector6};
use armkit::redundancy::{
    energy_measure, joint_torques, JointWeights, Load, SolverOptions, TorqueFloor,
    WeightedLeastNorm, SEED000_PRIORITY_WEIGHTS,
};

fn main() -> Result<(), armkit::Error> {
    let model = armkit::robots::by_name("gantry9")?;
    let mut data = Data::new(&model);
    let q = [3.0, 2.5, 1.0, 0.3, 0.4, -0.5, 0.2, 0.8, 0.1];
    model.check_limits(&q)?;

    // Torques (N, N m) holding a 50 N payload and the links against gravity.
    let load = Load::payload(50.0).with_seed001_gravity();
    let mut torques = [0.0; 9];
    joint_torques(&model, &mut data, &q, &load, &mut torques)?;
    let j = jacobian(&model, &mut data, &q, JacobianFrame::World)?.clone();

    // 0.1 m/s along x, 0.05 m/s down, and 0.1 rad/s about z.
    let twist = Vector6::new(0.1, 0.0, -0.05, 0.0, 0.0, 0.1);
    let cases = [
        ("minimum norm", JointWeights::uniform(9)),
        ("priorities", JointWeights::new(&SEED000_PRIORITY_WEIGHTS)?),
        (
            "energy-optimal",
            JointWeights::from_torques(&torques, TorqueFloor::default())?,
        ),
        ("rail locked", JointWeights::uniform(9).with_locked(&[0])?),
    ];
    let mut solver = WeightedLeastNorm::new(9, SolverOptions::default())?;
    let mut solutions = Vec::new();
    for (name, weights) in &cases {
        let q_dot = solver
            .solve(&j, weights, &twist)?
            .solved()
            .ok_or_else(|| armkit::Error::invalid_argument("jacobian", "is singular"))?
            .to_vec();
        let residual = (&j * DVector::from_column_slice(&q_dot) - twist).norm();
        solutions.push((name, q_dot, residual));
    }

    println!(
        "{} at q = {q:?}; twist [vx vy vz wx wy wz] = {:?} (m/s, rad/s)",
        model.name(),
        twist.as_slice()
    );
    print!("{:<5} {:>14}", "joint", "torque");
    for (name, _, _) in &solutions {
        print!(" {name:>15}");
    }
    println!();
    for (i, joint) in model.joints().iter().enumerate() {
        let (unit, torque_unit) = if joint.kind.is_rotational() {
            ("rad/s", "N m")
        } else {
            ("m/s", "N")
        };
        print!("{:<5} {:>10.1} {torque_unit:<3}", joint.name, torques[i]);
        for (_, q_dot, _) in &solutions {
            print!(" {:>9.4} {unit:<5}", q_dot[i]);
        }
        println!();
    }
    print!("{:<20}", "F (eq 9, W^2)");
    for (_, q_dot, _) in &solutions {
        print!(" {:>15.3}", energy_measure(q_dot, &torques)?);
    }
    println!();
    print!("{:<20}", "|J q_dot - V| (m/s)");
    for (_, _, residual) in &solutions {
        print!(" {residual:>15.1e}");
    }
    println!();
    Ok(())
}
