//! The published arms: PUMA 560, UR5, Panda, Stanford arm, with their
//! makers' (or the Robotics Toolbox's) tables, mass properties and limits.

use std::f64::consts::{FRAC_PI_2, PI};

use super::deg;
use crate::error::{Error, Result};
use crate::math::{Matrix3, Pose, Vector3};
use crate::model::{DhConvention, DhLink, LinkInertia, Model};

/// Unimation PUMA 560, standard DH, as in the Robotics Toolbox
/// (`models.DH.Puma560`, after Corke and Armstrong-Helouvry): lengths in m,
/// joint limits from RTB. No velocity limits are published in that model.
pub fn puma560() -> Result<Model> {
    let links = [
        DhLink::revolute(0.67183, 0.0, FRAC_PI_2).with_limits(deg(-160.0), deg(160.0)),
        DhLink::revolute(0.0, 0.4318, 0.0).with_limits(deg(-45.0), deg(225.0)),
        DhLink::revolute(0.15005, 0.0203, -FRAC_PI_2).with_limits(deg(-225.0), deg(45.0)),
        DhLink::revolute(0.4318, 0.0, FRAC_PI_2).with_limits(deg(-110.0), deg(170.0)),
        DhLink::revolute(0.0, 0.0, -FRAC_PI_2).with_limits(deg(-100.0), deg(100.0)),
        DhLink::revolute(0.0, 0.0, 0.0).with_limits(deg(-266.0), deg(266.0)),
    ];
    Model::from_dh("puma560", DhConvention::Standard, &links)
}

/// Universal Robots UR5, standard DH from UR's published table (as RTB's
/// `models.DH.UR5`), with UR's published mass properties and limits.
///
/// Frames: the DH base frame, which is the URDF's `base_link` turned by
/// 180 deg about z (UR's URDFs put the arm along +x at `q = 0`, this table
/// along -x): a point `p` of the DH base frame is `Rz(pi) p` in `base_link`. `d1` is RTB's
/// 0.089459 m; UR's page and the URDF give 0.089159 m, a shift of the whole
/// arm along joint 1's axis that changes neither the Jacobian's directions
/// nor the dynamics.
///
/// Sources:
/// * masses and centres of mass in the DH frames: Universal Robots, "DH
///   parameters for calculations of kinematics and dynamics" (UR5 table:
///   3.7, 8.393, 2.275, 1.219, 1.219, 0.1879 kg);
/// * inertia about each centre of mass: UR publishes none; uniform cylinders
///   with the dimensions of UR's `ur_description` (radius 0.06 m; lengths
///   0.15, 0.56, 0.5, 0.12, 0.12 m; wrist 3 radius 0.0375 m, length 0.0345 m),
///   their axes along the links as in that URDF. That URDF (and
///   example-robot-data's copy in `tests/data/urdf/ur5.urdf`) gives the wrists
///   a 0.6 m radius, ten times the arm's, and puts the centres of mass on the
///   joint origins: its dynamics differ from these (see [`ur5_mass_properties`]);
/// * limits: positions +-2 pi (the elbow +-pi) as in UR's URDF; velocity
///   pi rad/s (180 deg/s, the UR5 data sheet); effort 150, 150, 150, 28, 28,
///   28 N m (UR's `ur_description`, the base/shoulder/elbow and wrist joint
///   sizes); acceleration 5 rad/s^2 on every joint, the value of UR's
///   `ur_moveit_config` `joint_limits.yaml` (UR publishes no acceleration
///   limit: the arm's are set by its torques).
pub fn ur5() -> Result<Model> {
    let two_pi = 2.0 * PI;
    let table = [
        // (d, a, alpha, position limit, effort)
        (0.089459, 0.0, FRAC_PI_2, two_pi, 150.0),
        (0.0, -0.425, 0.0, two_pi, 150.0),
        (0.0, -0.39225, 0.0, PI, 150.0),
        (0.10915, 0.0, FRAC_PI_2, two_pi, 28.0),
        (0.09465, 0.0, -FRAC_PI_2, two_pi, 28.0),
        (0.0823, 0.0, 0.0, two_pi, 28.0),
    ];
    let masses = ur5_mass_properties();
    let mut links = [DhLink::revolute(0.0, 0.0, 0.0); 6];
    for (j, ((d, a, alpha, limit, effort), inertia)) in table.into_iter().zip(masses).enumerate() {
        let mut link = DhLink::revolute(d, a, alpha)
            .with_limits(-limit, limit)
            .with_velocity_limit(PI)
            .with_inertia(inertia);
        link.limits.acceleration = Some(5.0);
        link.limits.effort = Some(effort);
        links[j] = link;
    }
    Model::from_dh("ur5", DhConvention::Standard, &links)
}

/// The UR5 of [`ur5`] (same DH table, mass properties and limits) with
/// poses in the frame of UR's URDF (`base_link`, as in
/// `tests/data/urdf/ur5.urdf` from `base_link` to `tool0`): the DH base
/// placed in `base_link` turned by 180 deg about z and lowered by 0.3 mm,
/// the URDF's d1 (0.089159 m) against the table's 0.089459 m. The same
/// configuration gives the URDF's end-effector pose (to rounding), and
/// `ur5`'s pose turned by 180 deg about z.
pub fn ur5_urdf() -> Result<Model> {
    let dh = ur5()?;
    let (convention, links) = dh.dh_table().ok_or_else(|| {
        Error::invalid_argument("ur5", "the built-in UR5 is described by a DH table")
    })?;
    let base = Pose::trans_z(0.089159 - 0.089459) * Pose::rot_z(PI);
    Model::from_dh_with_transforms("ur5-urdf", convention, links, base, Pose::identity())
}

/// Mass properties of the UR5's links in their standard-DH frames (frame j at
/// the distal end of link j), from Universal Robots' published table (masses,
/// centres of mass) and uniform cylinders (inertia; see [`ur5`]).
///
/// | link | mass (kg) | centre of mass (m) | cylinder r x l (m) | cylinder axis |
/// | --- | --- | --- | --- | --- |
/// | 1 | 3.7 | (0, -0.02561, 0.00193) | 0.06 x 0.15 | y1 |
/// | 2 | 8.393 | (0.2125, 0, 0.11336) | 0.06 x 0.56 | x2 |
/// | 3 | 2.275 | (0.15, 0, 0.0265) | 0.06 x 0.5 | x3 |
/// | 4 | 1.219 | (0, -0.0018, 0.01634) | 0.06 x 0.12 | z4 |
/// | 5 | 1.219 | (0, 0.0018, 0.01634) | 0.06 x 0.12 | y5 |
/// | 6 | 0.1879 | (0, 0, -0.001159) | 0.0375 x 0.0345 | y6 |
pub fn ur5_mass_properties() -> [LinkInertia; 6] {
    // A uniform cylinder: m (3 r^2 + l^2) / 12 across its axis, m r^2 / 2 along it.
    let cylinder = |mass: f64, com: [f64; 3], radius: f64, length: f64, axis: usize| {
        let across = mass * (3.0 * radius * radius + length * length) / 12.0;
        let along = mass * radius * radius / 2.0;
        let mut inertia = LinkInertia::point_mass(mass, Vector3::from(com));
        for k in 0..3 {
            inertia.inertia[(k, k)] = if k == axis { along } else { across };
        }
        inertia
    };
    [
        cylinder(3.7, [0.0, -0.02561, 0.00193], 0.06, 0.15, 1),
        cylinder(8.393, [0.2125, 0.0, 0.11336], 0.06, 0.56, 0),
        cylinder(2.275, [0.15, 0.0, 0.0265], 0.06, 0.5, 0),
        cylinder(1.219, [0.0, -0.0018, 0.01634], 0.06, 0.12, 2),
        cylinder(1.219, [0.0, 0.0018, 0.01634], 0.06, 0.12, 1),
        cylinder(0.1879, [0.0, 0.0, -0.001159], 0.0375, 0.0345, 1),
    ]
}

/// Franka Emika Panda, modified DH from Franka's documentation (as RTB's
/// `models.DH.Panda`), with RTB's tool: the flange 0.107 m beyond joint 7
/// (in the table) plus 0.103 m and -45 deg about z, at the Franka Hand's
/// fingertip centre.
///
/// Frames: the modified-DH frame j (1-6) is `panda_link<j>` of Franka's URDF
/// (`franka_description`), frame 7 is `panda_link8` (the flange: the table's
/// d7 = 0.107 m), the base frame is `panda_link0`; so the same configuration
/// gives the same joint frames as the URDF.
///
/// Sources:
/// * limits: Franka's data sheet ("Robot and interface specifications",
///   Franka Control Interface documentation): positions, velocities 2.175 /
///   2.61 rad/s, accelerations 15, 7.5, 10, 12.5, 15, 20, 20 rad/s^2, torques
///   87 N m (joints 1-4) and 12 N m (5-7);
/// * mass properties of links 1-7: the identified, physically feasible set of
///   Gaz, Cognetti, Oliva, Robuffo Giordano and De Luca, "Dynamic
///   identification of the Franka Emika Panda robot with retrieval of
///   feasible parameters using penalty-based optimization", IEEE RA-L 4(4),
///   2019, as `franka_description` ships them (see [`panda_mass_properties`]);
/// * the Franka Hand on the flange (0.73 kg, and its two 0.015 kg fingers
///   closed) from `franka_description`, folded into link 7 because the tool
///   frame is the hand's.
pub fn panda() -> Result<Model> {
    let table = [
        // (d, a, alpha, lower, upper, velocity, acceleration, effort)
        (0.333, 0.0, 0.0, -2.8973, 2.8973, 2.175, 15.0, 87.0),
        (0.0, 0.0, -FRAC_PI_2, -1.7628, 1.7628, 2.175, 7.5, 87.0),
        (0.316, 0.0, FRAC_PI_2, -2.8973, 2.8973, 2.175, 10.0, 87.0),
        (0.0, 0.0825, FRAC_PI_2, -3.0718, -0.0698, 2.175, 12.5, 87.0),
        (
            0.384, -0.0825, -FRAC_PI_2, -2.8973, 2.8973, 2.61, 15.0, 12.0,
        ),
        (0.0, 0.0, FRAC_PI_2, -0.0175, 3.7525, 2.61, 20.0, 12.0),
        (0.107, 0.088, FRAC_PI_2, -2.8973, 2.8973, 2.61, 20.0, 12.0),
    ];
    let masses = panda_mass_properties()?;
    let mut links = [DhLink::revolute(0.0, 0.0, 0.0); 7];
    for (j, (row, inertia)) in table.into_iter().zip(masses).enumerate() {
        let (d, a, alpha, lower, upper, velocity, acceleration, effort) = row;
        let mut link = DhLink::revolute(d, a, alpha)
            .with_limits(lower, upper)
            .with_velocity_limit(velocity)
            .with_inertia(inertia);
        link.limits.acceleration = Some(acceleration);
        link.limits.effort = Some(effort);
        links[j] = link;
    }
    let tool = Pose::trans_z(0.103) * Pose::rot_z(-PI / 4.0);
    Model::from_dh_with_transforms(
        "panda",
        DhConvention::Modified,
        &links,
        Pose::identity(),
        tool,
    )
}

/// Mass properties of the Panda's links 1-7 in their modified-DH frames
/// (`panda_link1` .. `panda_link6`, and the flange `panda_link8` for link 7,
/// 0.107 m along z from `panda_link7`), link 7 carrying the Franka Hand.
///
/// Links 1-7: Gaz et al. 2019 (see [`panda`]), masses 4.970684, 0.646926,
/// 3.228604, 3.587895, 1.225946, 1.666555, 0.735522 kg, with their centres of
/// mass and inertia tensors (about the centre of mass, in the link frame's
/// axes) as `franka_description` lists them. The hand: 0.73 kg, centre of
/// mass (-0.01, 0, 0.03) m and inertia diag(0.001, 0.0025, 0.0017) kg m^2 in
/// the hand frame (`Tz(0.107) Rz(-45 deg)` from link 7); each finger 0.015 kg
/// at 0.0584 m along the hand's z (closed), inertia diag(2.375e-6, 2.375e-6,
/// 7.5e-7) kg m^2. Errors only if a value were not a valid body.
pub fn panda_mass_properties() -> Result<[LinkInertia; 7]> {
    let body = |mass: f64, com: [f64; 3], i: [f64; 6]| {
        let [xx, xy, xz, yy, yz, zz] = i;
        LinkInertia {
            mass,
            com: Vector3::from(com),
            inertia: Matrix3::new(xx, xy, xz, xy, yy, yz, xz, yz, zz),
        }
    };
    let link7 = body(
        0.735522,
        [1.0517e-02, -4.252e-03, 6.1597e-02],
        [
            0.012516, -0.000428, -0.001196, 0.010027, -0.000741, 0.004815,
        ],
    );
    let hand_frame = Pose::trans_z(0.107) * Pose::rot_z(-PI / 4.0);
    let hand = body(
        0.73,
        [-0.01, 0.0, 0.03],
        [0.001, 0.0, 0.0, 0.0025, 0.0, 0.0017],
    );
    let finger = body(
        0.015,
        [0.0, 0.0, 0.0584],
        [2.375e-6, 0.0, 0.0, 2.375e-6, 0.0, 7.5e-7],
    );
    // The table's d7 = 0.107 m puts DH frame 7 at the flange (`panda_link8`),
    // 0.107 m along z from `panda_link7`, where Franka gives link 7's body.
    let link7_with_hand = LinkInertia::combine(&[
        link7,
        hand.transformed(&hand_frame),
        finger.transformed(&hand_frame),
        finger.transformed(&hand_frame),
    ])
    .ok_or_else(|| Error::invalid_argument("panda", "no bodies to combine"))?
    .transformed(&Pose::trans_z(-0.107));
    Ok([
        body(
            4.970684,
            [0.003875, 0.002081, -0.04762],
            [0.70337, -0.000139, 0.006772, 0.70661, 0.019169, 0.009117],
        ),
        body(
            0.646926,
            [-0.003141, -0.02872, 0.003495],
            [0.007962, -0.003925, 0.010254, 0.02811, 0.000704, 0.025995],
        ),
        body(
            3.228604,
            [2.7518e-02, 3.9252e-02, -6.6502e-02],
            [0.037242, -0.004761, -0.011396, 0.036155, -0.012805, 0.01083],
        ),
        body(
            3.587895,
            [-5.317e-02, 1.04419e-01, 2.7454e-02],
            [0.025853, 0.007796, -0.001332, 0.019552, 0.008641, 0.028323],
        ),
        body(
            1.225946,
            [-1.1953e-02, 4.1065e-02, -3.8437e-02],
            [0.035549, -0.002117, -0.004037, 0.029474, 0.000229, 0.008627],
        ),
        body(
            1.666555,
            [6.0149e-02, -1.4117e-02, -1.0517e-02],
            [0.001964, 0.000109, -0.001158, 0.004354, 0.000341, 0.005433],
        ),
        link7_with_hand,
    ])
}

/// The Stanford arm (RRPRRR), standard DH as in RTB's `models.DH.Stanford`:
/// joint 3 is prismatic (0.3048 m to 1.27 m) with a constant theta of -pi/2.
pub fn stanford() -> Result<Model> {
    let links = [
        DhLink::revolute(0.412, 0.0, -FRAC_PI_2).with_limits(deg(-170.0), deg(170.0)),
        DhLink::revolute(0.154, 0.0, FRAC_PI_2).with_limits(deg(-170.0), deg(170.0)),
        DhLink::prismatic(-FRAC_PI_2, 0.0203, 0.0).with_limits(12.0 * 0.0254, 50.0 * 0.0254),
        DhLink::revolute(0.0, 0.0, -FRAC_PI_2).with_limits(deg(-170.0), deg(170.0)),
        DhLink::revolute(0.0, 0.0, FRAC_PI_2).with_limits(deg(-90.0), deg(90.0)),
        DhLink::revolute(0.0, 0.0, 0.0).with_limits(deg(-170.0), deg(170.0)),
    ];
    Model::from_dh("stanford", DhConvention::Standard, &links)
}
