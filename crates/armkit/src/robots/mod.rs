//! Built-in robots: published arms and the three seed robots.
//!
//! | name | DOF | model | source |
//! | --- | --- | --- | --- |
//! | `puma560` | 6 | standard DH | Corke, Robotics Toolbox `models.DH.Puma560` |
//! | `ur5` | 6 | standard DH | Universal Robots' published DH, RTB `models.DH.UR5`; UR's masses and centres of mass, limits with effort ([`ur5`]) |
//! | `ur5-urdf` | 6 | standard DH + base | `ur5` with its poses in the UR URDF's `base_link` (turned 180 deg about z, d1 as the URDF's) ([`ur5_urdf`]) |
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

mod published;
mod seeds;

pub use published::{
    panda, panda_mass_properties, puma560, stanford, ur5, ur5_mass_properties, ur5_urdf,
};
pub use seeds::{
    arm4, gantry9, gantry9_flex, gantry9_mass_properties, gantry9_with_beam, space6r,
    space6r_base_body, space6r_free_floating, space6r_mass_properties, GANTRY9_BEAM_HEIGHT,
    GANTRY9_BEAM_LENGTH,
};

use crate::error::{Error, Result};
use crate::model::Model;

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
        name: "ur5-urdf",
        dof: 6,
        description: "ur5 (same table, masses and limits) with poses in the frame of UR's URDF",
        frames: "the UR URDF's base_link (ur5's DH base turned 180 deg about z, 0.3 mm lower): \
                 same poses as tests/data/urdf/ur5.urdf base_link -> tool0",
        build: ur5_urdf,
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
