//! The seed papers' robots: seed 002's 4-DOF arm, seed 004's space arm on
//! its satellite, seed 000's gantry (rigid and on its flexible beam).

use std::f64::consts::{FRAC_PI_2, PI};

use super::deg;
use crate::error::{Error, Result};
use crate::math::{Matrix3, Pose, Vector3};
use crate::model::{DhConvention, DhLink, LinkInertia, Model};
use crate::space::{BaseBody, FreeFloatingModel};

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
