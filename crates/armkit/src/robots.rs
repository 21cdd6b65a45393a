//! Built-in robots: published arms and the three seed robots.
//!
//! | name | DOF | model | source |
//! | --- | --- | --- | --- |
//! | `puma560` | 6 | standard DH | Corke, Robotics Toolbox `models.DH.Puma560` |
//! | `ur5` | 6 | standard DH | Universal Robots' published DH, RTB `models.DH.UR5`; UR's masses and centres of mass, limits with effort ([`ur5`]) |
//! | `panda` | 7 | modified DH + tool | Franka Emika's published DH, RTB `models.DH.Panda`; Gaz et al. 2019's inertial parameters with the hand, data-sheet limits ([`panda`]) |
//! | `stanford` | 6 (RRPRRR) | standard DH | Scheinman's Stanford arm, RTB `models.DH.Stanford` |
//! | `arm4` | 4 | standard DH | seed 002's 4-DOF arm, our dimensions |
//! | `space6r` | 6 | standard DH | seed 004's 6R space arm, PUMA-like, paper's lengths |
//! | `gantry9` | 9 (PPP + 6R) | modified DH | seed 000's gantry, our dimensions |
//! | `gantry9-flex` | 9 (PPP + 6R) | modified DH + beam deflection | `gantry9` on seed 000's flexible beam |
//!
//! The published arms reproduce the Robotics Toolbox tables exactly (checked
//! against `tests/data/reference_*_dh.json`). The seed robots' tables are not
//! printed (or are garbled) in the papers; each builder's documentation gives
//! every length and limit we chose, and why.
//!
//! Seed 004's space robot, `space6r` on its satellite
//! ([`space6r_base_body`]), is [`space6r_free_floating`], a
//! [`crate::space::FreeFloatingModel`].
//!
//! ```
//! for name in armkit::robots::names() {
//!     let model = armkit::robots::by_name(name).unwrap();
//!     assert!(model.dof() >= 4);
//! }
//! assert!(armkit::robots::by_name("r2d2").is_err());
//! ```

use std::f64::consts::{FRAC_PI_2, PI};

use crate::error::{Error, Result};
use crate::math::{Matrix3, Pose, Vector3};
use crate::model::{DhConvention, DhLink, LinkInertia, Model};
use crate::space::{BaseBody, FreeFloatingModel};

/// A built-in robot: name, degrees of freedom, one-line description, constructor.
#[derive(Clone, Copy, Debug)]
pub struct BuiltinRobot {
    /// Name used by [`by_name`] and the CLI's `--robot`.
    pub name: &'static str,
    /// Degrees of freedom.
    pub dof: usize,
    /// One line: what it is and where its parameters come from.
    pub description: &'static str,
    /// The base frame poses are given in, and how it relates to the frames of
    /// the robot's other published models (a URDF's `base_link`).
    pub frames: &'static str,
    /// Builds the model.
    pub build: fn() -> Result<Model>,
}

/// Every built-in robot, in the order `armkit robots` lists them.
pub const BUILTIN: &[BuiltinRobot] = &[
    BuiltinRobot {
        name: "puma560",
        dof: 6,
        description: "Unimation PUMA 560, standard DH (Corke; Robotics Toolbox models.DH.Puma560)",
        frames: "DH base frame (RTB models.DH.Puma560)",
        build: puma560,
    },
    BuiltinRobot {
        name: "ur5",
        dof: 6,
        description: "Universal Robots UR5, standard DH (UR's published table; RTB models.DH.UR5)",
        frames: "DH base frame: the UR URDF's base_link turned 180 deg about z (base_link x = -x here)",
        build: ur5,
    },
    BuiltinRobot {
        name: "panda",
        dof: 7,
        description: "Franka Emika Panda, modified DH with RTB's tool (flange + 0.103 m, -45 deg)",
        frames: "modified-DH frames = the URDF's panda_link0..6, frame 7 = panda_link8 (same base frame)",
        build: panda,
    },
    BuiltinRobot {
        name: "stanford",
        dof: 6,
        description: "Stanford arm, RRPRRR, standard DH (Scheinman; RTB models.DH.Stanford)",
        frames: "DH base frame (RTB models.DH.Stanford)",
        build: stanford,
    },
    BuiltinRobot {
        name: "arm4",
        dof: 4,
        description: "Seed 002's 4-DOF arm: two parallel vertical axes, then a roll and a pitch",
        frames: "DH base frame turned -90 deg about z (seed 002's axes)",
        build: arm4,
    },
    BuiltinRobot {
        name: "space6r",
        dof: 6,
        description:
            "Seed 004's 6R space arm, PUMA-like with a spherical wrist, with mass properties",
        frames: "DH base frame 0.30 m above the satellite's mount",
        build: space6r,
    },
    BuiltinRobot {
        name: "gantry9",
        dof: 9,
        description: "Seed 000's 9-DOF gantry: 3 prismatic axes carrying a 6R arm (rigid beam)",
        frames: "world: x along the rails, y along the beam, z up (floor)",
        build: gantry9,
    },
    BuiltinRobot {
        name: "gantry9-flex",
        dof: 9,
        description: "gantry9 on seed 000's flexible beam: 400 kg carriage, E = 200 GPa, 0.2 m square, L = 10 m",
        frames: "world: x along the rails, y along the beam, z up (floor)",
        build: gantry9_flex,
    },
];

/// Names of the built-in robots.
pub fn names() -> impl Iterator<Item = &'static str> {
    BUILTIN.iter().map(|r| r.name)
}

/// The built-in robot called `name` (case-insensitive).
pub fn by_name(name: &str) -> Result<Model> {
    BUILTIN
        .iter()
        .find(|r| r.name.eq_ignore_ascii_case(name))
        .map(|r| (r.build)())
        .unwrap_or_else(|| {
            Err(Error::UnknownRobot {
                name: name.to_string(),
                known: names().collect::<Vec<_>>().join(", "),
            })
        })
}

fn deg(angle: f64) -> f64 {
    angle.to_radians()
}

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

/// Seed 002's 4-DOF arm (Hao, Chen, Deng), standard DH, our dimensions.
///
/// The paper prints no link lengths; its inverse kinematics (eqs 8-9) says
/// the wrist moves in a horizontal plane with
/// `px = a1 s1 + d3 s12`, `py = -a1 c1 - d3 c12`: joints 1 and 2 are parallel
/// vertical axes, link 1 has length `a1`, link 2 runs `d3` along the axis of
/// joint 3 (a roll about the link), and joint 4 pitches the tool. The base is
/// turned by -90 deg about z so that the zero pose points along -y as in
/// those equations.
///
/// | link | theta | d (m) | a (m) | alpha | offset | limits |
/// | --- | --- | --- | --- | --- | --- | --- |
/// | 1 | q1 | 0.30 (column height) | 0.25 (`a1`) | 0 | 0 | +-150 deg |
/// | 2 | q2 | 0 | 0 | +90 deg | +90 deg | +-150 deg |
/// | 3 | q3 | 0.20 (`d3`, link 2's length) | 0 | +90 deg | 0 | +-180 deg |
/// | 4 | q4 | 0 | 0.08 (tool) | 0 | 0 | +-120 deg |
///
/// The +90 deg offset of joint 2 turns its z axis along link 2, so joint 3
/// rolls about the link; the tool (0.08 m along x4) makes every joint move
/// the tool point. The limits keep the two parallel links from folding onto
/// each other (a real arm's cables would not allow more). Velocity limit
/// pi rad/s on every joint.
pub fn arm4() -> Result<Model> {
    let links = [
        DhLink::revolute(0.30, 0.25, 0.0).with_limits(deg(-150.0), deg(150.0)),
        DhLink::revolute(0.0, 0.0, FRAC_PI_2)
            .with_offset(FRAC_PI_2)
            .with_limits(deg(-150.0), deg(150.0)),
        DhLink::revolute(0.20, 0.0, FRAC_PI_2).with_limits(-PI, PI),
        DhLink::revolute(0.0, 0.08, 0.0).with_limits(deg(-120.0), deg(120.0)),
    ]
    .map(|l| l.with_velocity_limit(PI));
    Model::from_dh_with_transforms(
        "arm4",
        DhConvention::Standard,
        &links,
        Pose::rot_z(-FRAC_PI_2),
        Pose::identity(),
    )
}

/// Seed 004's 6R space arm (Zhao, She, Huang, Huang), standard DH, PUMA-like
/// with a spherical wrist, from the lengths the paper prints.
///
/// | link | d (m) | a (m) | alpha | limits |
/// | --- | --- | --- | --- | --- |
/// | 1 | 0.30 (`d1`) | 0 | +90 deg | +-180 deg |
/// | 2 | 0.15 (`d2`, shoulder offset) | 0.83 (`a2`) | 0 | +-180 deg |
/// | 3 | 0 | 0.03 (`a3`) | -90 deg | +-180 deg |
/// | 4 | 0.70 (`d4`) | 0 | +90 deg | +-180 deg |
/// | 5 | 0 | 0 | -90 deg | +-180 deg |
/// | 6 | 0.2345 (`L7`, wrist centre to tool) | 0 | 0 | +-180 deg |
///
/// The DH table itself is lost in the extraction; this is the PUMA 560's
/// structure with the paper's `d1, d2, d4, a2, a3` and `L7` as the tool
/// length. The base transform puts joint 1 `L1 = 0.30` m above the base
/// body's centre. Mass properties (documented in [`space6r_mass_properties`])
/// are attached to the links for the free-floating model. Velocity limit
/// 0.5 rad/s (a space arm's joints are slow).
pub fn space6r() -> Result<Model> {
    let table = [
        (0.30, 0.0, FRAC_PI_2),
        (0.15, 0.83, 0.0),
        (0.0, 0.03, -FRAC_PI_2),
        (0.70, 0.0, FRAC_PI_2),
        (0.0, 0.0, -FRAC_PI_2),
        (0.2345, 0.0, 0.0),
    ];
    let masses = space6r_mass_properties();
    let mut links = [DhLink::revolute(0.0, 0.0, 0.0); 6];
    for (j, ((d, a, alpha), inertia)) in table.into_iter().zip(masses).enumerate() {
        links[j] = DhLink::revolute(d, a, alpha)
            .with_limits(-PI, PI)
            .with_velocity_limit(0.5)
            .with_inertia(inertia);
    }
    Model::from_dh_with_transforms(
        "space6r",
        DhConvention::Standard,
        &links,
        Pose::trans_z(0.30),
        Pose::identity(),
    )
}

/// Mass properties of space6r's links, in each link's standard-DH frame.
///
/// The paper takes them from its reference 19, which the extraction does
/// not include; these are plausible values for a 2 m class space arm of
/// aluminium tubes (uniform rods: `I = m l^2 / 12` about the transverse axes,
/// `m r^2 / 2` about the rod axis, r = 0.05 m), centres of mass at mid-link:
///
/// | link | mass (kg) | centre of mass in DH frame j (m) | rod length (m) |
/// | --- | --- | --- | --- |
/// | 1 | 20 | (0, -0.15, 0) | 0.30 |
/// | 2 | 40 | (-0.415, 0, 0.15) | 0.83 |
/// | 3 | 10 | (-0.015, 0, 0) | 0.15 (`L4`) |
/// | 4 | 30 | (0, -0.35, 0) | 0.70 |
/// | 5 | 8 | (0, 0, 0) | 0.10 (`L6`) |
/// | 6 | 10 | (0, 0, -0.117) | 0.2345 (`L7`) |
pub fn space6r_mass_properties() -> [LinkInertia; 6] {
    let rod = |mass: f64, com: [f64; 3], length: f64, axis: usize| {
        let transverse = mass * length * length / 12.0;
        let axial = mass * 0.05 * 0.05 / 2.0;
        let mut inertia = LinkInertia::point_mass(mass, Vector3::from(com));
        for k in 0..3 {
            inertia.inertia[(k, k)] = if k == axis { axial } else { transverse };
        }
        inertia
    };
    [
        rod(20.0, [0.0, -0.15, 0.0], 0.30, 1),
        rod(40.0, [-0.415, 0.0, 0.15], 0.83, 0),
        rod(10.0, [-0.015, 0.0, 0.0], 0.15, 0),
        rod(30.0, [0.0, -0.35, 0.0], 0.70, 1),
        rod(8.0, [0.0, 0.0, 0.0], 0.10, 2),
        rod(10.0, [0.0, 0.0, -0.117], 0.2345, 2),
    ]
}

/// space6r's spacecraft: a small satellite of 400 kg.
///
/// The paper prints no mass properties. We take a 400 kg body (a small
/// satellite; the arm's links weigh 118 kg in all, so the mass ratio of about
/// 3.4 makes the base's reaction clearly visible, as it is on real servicing
/// spacecraft) shaped as a uniform 1.2 m x 1.0 m x 1.0 m box (x, y, z),
/// density 333 kg/m^3, typical of small satellites:
///
/// * base frame at the centre of mass, axes along the box's edges;
/// * inertia `diag(m (b^2 + c^2), m (a^2 + c^2), m (a^2 + b^2)) / 12` =
///   `diag(66.67, 81.33, 81.33)` kg m^2;
/// * the arm is mounted at the centre of the top face: `mount = Tz(0.5)`; the
///   arm model's own base transform adds `L1 = 0.30` m, so joint 1 sits
///   0.80 m above the base's centre of mass.
pub fn space6r_base_body() -> BaseBody {
    let (mass, a, b, c) = (400.0, 1.2, 1.0, 1.0);
    BaseBody {
        name: "satellite".into(),
        mass,
        com: Vector3::zeros(),
        inertia: Matrix3::from_diagonal(&Vector3::new(
            mass * (b * b + c * c) / 12.0,
            mass * (a * a + c * c) / 12.0,
            mass * (a * a + b * b) / 12.0,
        )),
        mount: Pose::trans_z(0.5),
    }
}

/// Seed 004's space robot: [`space6r`] (links with the mass properties of
/// [`space6r_mass_properties`]) on the satellite of [`space6r_base_body`].
/// Total mass 518 kg.
pub fn space6r_free_floating() -> Result<FreeFloatingModel> {
    FreeFloatingModel::new(space6r_base_body(), space6r()?)
}

/// Height of gantry9's beam above the floor, m (the carriage's mounting plane
/// when `d3 = 0`).
pub const GANTRY9_BEAM_HEIGHT: f64 = 6.0;

/// Length of gantry9's beam between its supports, m (seed 000, Table 1).
pub const GANTRY9_BEAM_LENGTH: f64 = crate::beam::SEED000_BEAM_LENGTH;

/// Seed 000's 9-DOF gantry (Wang, Li, Xi), modified DH, our dimensions; rigid
/// beam (the deflection coupling is in [`crate::beam`]).
///
/// The paper's Table 2 is garbled and gives no lengths. World frame: x along
/// the rails, y along the beam, z up. Joint 1 moves the beam along the rails
/// (`x = d1`); joint 2 moves the carriage along the beam (`y = d2`, the
/// distance from the beam's left support, as in eq 1); joint 3 lowers the arm
/// mount (`z = 6.0 - d3`). A 6R arm with a spherical wrist hangs from the
/// carriage (Craig's PUMA structure, our lengths, an industrial arm of about
/// 1.5 m reach):
///
/// | joint | type | alpha_{i-1} | a_{i-1} (m) | theta | d (m) | limits (eq 24) | vmax (eq 23) |
/// | --- | --- | --- | --- | --- | --- | --- | --- |
/// | 1 | P | 0 | 0 | 0 | d1 | [0, 9] m | 0.6 m/s |
/// | 2 | P | -90 deg | 0 | 90 deg | d2 | [0, 5] m | 0.6 m/s |
/// | 3 | P | +90 deg | 0 | 0 | d3 | [0, 5] m | 0.6 m/s |
/// | 4 | R | 0 | 0 | q4 | 0.30 | +-2.62 rad | pi rad/s |
/// | 5 | R | -90 deg | 0.15 | q5 | 0 | [-0.78, 1.22] rad | pi rad/s |
/// | 6 | R | 0 | 0.70 | q6 | 0 | [-1.22, 1.05] rad | pi rad/s |
/// | 7 | R | +90 deg | 0.11 | q7 | 0.67 | +-3.14 rad | pi rad/s |
/// | 8 | R | -90 deg | 0 | q8 | 0 | +-2.18 rad | pi rad/s |
/// | 9 | R | +90 deg | 0 | q9 | 0 | +-6.28 rad | pi rad/s |
///
/// Base: `Tz(6.0) Ry(90 deg)` turns joint 1's z axis along the rails; tool:
/// 0.10 m flange along z9. At `q = 0` the arm hangs from the carriage with
/// its upper arm horizontal (along -x), the forearm pointing down and the
/// tool down. With these lengths the limits of eq 24 matter: the shoulder
/// (q5) and elbow (q6) ranges bound how far the hand reaches above or below
/// the carriage, and d3's 5 m stroke spans the 6 m beam height.
///
/// Link mass properties (400 kg carried by the beam, as in seed 000's
/// Table 1) are attached to every link: see [`gantry9_mass_properties`].
// The limits are eq 24's printed values (3.14 and 6.28, not pi and 2 pi).
#[allow(clippy::approx_constant)]
pub fn gantry9() -> Result<Model> {
    let vmax_prismatic = 0.6;
    let vmax_rotary = PI;
    let links = [
        DhLink::prismatic(0.0, 0.0, 0.0)
            .with_limits(0.0, 9.0)
            .with_velocity_limit(vmax_prismatic),
        DhLink::prismatic(FRAC_PI_2, 0.0, -FRAC_PI_2)
            .with_limits(0.0, 5.0)
            .with_velocity_limit(vmax_prismatic),
        DhLink::prismatic(0.0, 0.0, FRAC_PI_2)
            .with_limits(0.0, 5.0)
            .with_velocity_limit(vmax_prismatic),
        DhLink::revolute(0.30, 0.0, 0.0)
            .with_limits(-2.62, 2.62)
            .with_velocity_limit(vmax_rotary),
        DhLink::revolute(0.0, 0.15, -FRAC_PI_2)
            .with_limits(-0.78, 1.22)
            .with_velocity_limit(vmax_rotary),
        DhLink::revolute(0.0, 0.70, 0.0)
            .with_limits(-1.22, 1.05)
            .with_velocity_limit(vmax_rotary),
        DhLink::revolute(0.67, 0.11, FRAC_PI_2)
            .with_limits(-3.14, 3.14)
            .with_velocity_limit(vmax_rotary),
        DhLink::revolute(0.0, 0.0, -FRAC_PI_2)
            .with_limits(-2.18, 2.18)
            .with_velocity_limit(vmax_rotary),
        DhLink::revolute(0.0, 0.0, FRAC_PI_2)
            .with_limits(-6.28, 6.28)
            .with_velocity_limit(vmax_rotary),
    ];
    let mut links = links;
    for (link, inertia) in links.iter_mut().zip(gantry9_mass_properties()) {
        *link = link.with_inertia(inertia);
    }
    let base = Pose::trans_z(GANTRY9_BEAM_HEIGHT) * Pose::rot_y(FRAC_PI_2);
    Model::from_dh_with_transforms(
        "gantry9",
        DhConvention::Modified,
        &links,
        base,
        Pose::trans_z(0.10),
    )
}

/// Mass properties of gantry9's links, each in its link's modified-DH frame
/// (frame j on joint j's axis, as [`crate::kinematics::Data::joint_frames`]
/// reports it).
///
/// Seed 000 prints none but the load each carriage puts on the beam:
/// P = 400 kg (Table 1). We split those 400 kg into carriage 100 kg,
/// vertical ram 150 kg and arm 150 kg (a 1.5 m reach industrial arm of
/// about 10 kg payload class), so that everything the beam carries weighs
/// 400 kg. The beam itself is seed 000's section: solid steel 0.2 m x 0.2 m
/// x 10 m, 7850 kg/m^3 = 3140 kg, carried by the rails. Each body is a solid
/// box aligned with its frame's axes (`I = m/12 diag(ly^2 + lz^2, ...)`);
/// frames and directions are those at `q = 0` (world x along the rails, y
/// along the beam, z up):
///
/// | link | body | mass (kg) | centre of mass in frame j (m) | box lx, ly, lz (m) |
/// | --- | --- | --- | --- | --- |
/// | 1 | beam, centreline 0.1 m above the mounting plane, spans y = 0..10 m | 3140 | (-0.1, 5.0, 0) | 0.2, 10, 0.2 |
/// | 2 | carriage, on the beam | 100 | (0, 0.15, 0) | 0.5, 0.3, 0.5 |
/// | 3 | vertical ram, 5 m, lower end at joint 3's origin | 150 | (0, 0, -2.5) | 0.2, 0.2, 5.0 |
/// | 4 | arm base (turret) | 40 | (0.075, 0, -0.15) | 0.3, 0.3, 0.3 |
/// | 5 | upper arm, 0.70 m along x5 | 45 | (0.35, 0, 0) | 0.7, 0.15, 0.15 |
/// | 6 | forearm, elbow to wrist centre | 35 | (0.11, -0.335, 0) | 0.12, 0.67, 0.12 |
/// | 7 | wrist roll housing | 15 | (0, 0, -0.15) | 0.12, 0.12, 0.3 |
/// | 8 | wrist pitch body | 10 | (0, -0.05, 0) | 0.1, 0.1, 0.1 |
/// | 9 | flange and tool | 5 | (0, 0, 0.08) | 0.1, 0.1, 0.1 |
///
/// Carried by the beam (links 2-9): 400 kg; arm (links 4-9): 150 kg.
pub fn gantry9_mass_properties() -> [LinkInertia; 9] {
    let solid_box = |mass: f64, com: [f64; 3], size: [f64; 3]| {
        let [lx, ly, lz] = size.map(|l| l * l);
        let mut inertia = LinkInertia::point_mass(mass, Vector3::from(com));
        inertia.inertia =
            Matrix3::from_diagonal(&Vector3::new(ly + lz, lx + lz, lx + ly)) * (mass / 12.0);
        inertia
    };
    [
        solid_box(3140.0, [-0.1, 5.0, 0.0], [0.2, 10.0, 0.2]),
        solid_box(100.0, [0.0, 0.15, 0.0], [0.5, 0.3, 0.5]),
        solid_box(150.0, [0.0, 0.0, -2.5], [0.2, 0.2, 5.0]),
        solid_box(40.0, [0.075, 0.0, -0.15], [0.3, 0.3, 0.3]),
        solid_box(45.0, [0.35, 0.0, 0.0], [0.7, 0.15, 0.15]),
        solid_box(35.0, [0.11, -0.335, 0.0], [0.12, 0.67, 0.12]),
        solid_box(15.0, [0.0, 0.0, -0.15], [0.12, 0.12, 0.3]),
        solid_box(10.0, [0.0, -0.05, 0.0], [0.1, 0.1, 0.1]),
        solid_box(5.0, [0.0, 0.0, 0.08], [0.1, 0.1, 0.1]),
    ]
}

/// Seed 000's 9-DOF gantry on its flexible beam: [`gantry9`] whose carriage
/// sinks by the beam's deflection, `d3' = d3 + w(d2)` (eq 4 corrected), with
/// the Jacobian `J = J0 M`, `m2 = dw/dd2` (eqs 8-10 corrected).
///
/// The beam is [`crate::beam::CarriageDeflection::seed000`]: alloy steel,
/// `E = 200 GPa`, solid square section 0.2 m (`I = 1.333e-4 m^4`), span
/// [`GANTRY9_BEAM_LENGTH`] = 10 m, carriage load 400 kg x 10 m/s^2 = 4000 N
/// (the `g` that reproduces Table 1). `d2` is the carriage's distance from
/// the beam's left support; over its range [0, 5] m the deflection grows from
/// 0 to 3.125 mm. Named `gantry9-flex`; see [`gantry9_with_beam`] for other
/// loads or a rigid beam.
pub fn gantry9_flex() -> Result<Model> {
    gantry9_with_beam(&crate::beam::GantryBeam::default())
}

/// [`gantry9`] with the beam `beam`: [`crate::beam::GantryBeam::Rigid`] gives
/// back [`gantry9`] exactly (same name, same model); a flexible beam couples
/// joint 3 (index 2) to the carriage position `d2` (index 1) and names the
/// model `gantry9-flex`. Error: a beam shorter than `d2`'s travel (5 m).
pub fn gantry9_with_beam(beam: &crate::beam::GantryBeam) -> Result<Model> {
    let rigid = gantry9()?;
    match beam {
        crate::beam::GantryBeam::Rigid => Ok(rigid),
        crate::beam::GantryBeam::Flexible(deflection) => {
            let travel = rigid.joints()[1].limits.upper;
            if deflection.beam.length() < travel {
                return Err(Error::invalid_argument(
                    "beam",
                    format!(
                        "span {} m is shorter than the carriage's travel d2 <= {travel} m",
                        deflection.beam.length()
                    ),
                ));
            }
            Ok(rigid
                .with_coupling(beam.coupling(1, 2))?
                .renamed("gantry9-flex"))
        }
    }
}
