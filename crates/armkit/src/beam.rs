//! Deflection of a simply supported beam under point loads, and the gantry
//! models built on it (seed 000, sec 3.1).
//!
//! # Model
//!
//! An Euler-Bernoulli beam of span `L` (m), supported at `x = 0` and
//! `x = L`, bending stiffness `E I` (Young's modulus in Pa times the second
//! moment of area of the section in m^4). Positions `x` are measured from the
//! left support along the beam, in metres. Forces are in newtons and
//! **positive downward**; deflections are in metres and **positive
//! downward** (seed 000's eq 1 counts them upward, hence its minus signs).
//!
//! A point load `P` at `c` deflects the beam at `x` by `P G(x, c)` with the
//! influence function (seed 000 eq 1 is the case `x = c`):
//!
//! * `x <= c`: `G = (L - c) x (L^2 - (L - c)^2 - x^2) / (6 E I L)`,
//! * `x >= c`: `G = c (L - x) (L^2 - c^2 - (L - x)^2) / (6 E I L)`,
//!
//! and at the load itself `G(c, c) = c^2 (L - c)^2 / (3 E I L)` (eq 1, with
//! `a^2 + b^2 - L^2 = -2 a b`). Several loads superpose (the beam is linear).
//! For two carriages at `a` and `b` on one beam this gives eqs 2-3 (errata:
//! the printed ones swap `P1` and `P2` in eq 3 and are garbled; derived here
//! from eq 1): see [`TwoCarriageBeam`].
//!
//! # Gantry
//!
//! On seed 000's gantry the arm's carriage rides the beam at `d2` and sinks by
//! `w(d2) = P d2^2 (L - d2)^2 / (3 E I L)`, so the vertical joint acts as
//! `d3' = d3 + w(d2)` (eq 4 corrected: the paper prints `d2 -` for `d3 +`),
//! and the Jacobian is `J = J0 M` with `M` the identity but
//! `M[2][1] = m2 = dw/dd2 = 2 P d2 (L - d2)(L - 2 d2) / (3 E I L)` (eqs 8-10
//! corrected), recomputed at every configuration by
//! [`crate::kinematics::jacobian`]. [`GantryBeam`] selects a rigid or a
//! flexible beam for [`crate::robots::gantry9_with_beam`];
//! [`crate::robots::gantry9_flex`] is the seed's flexible gantry.
//!
//! # Table 1 and the value of g
//!
//! Table 1 (E = 200 GPa, L = 10 m, square section 0.2 m, two 400 kg loads)
//! prints the deflection **under the loads** (equal under both, the cases
//! being symmetric). It is reproduced with `g = 10 m/s^2`
//! ([`SEED000_GRAVITY`]): 0.004574, 0.005600, 0.002200 m against the printed
//! 0.0046, 0.0056, 0.0022 (-0.6 %, 0 %, 0 %). Only `g` in
//! [9.948, 10.089) m/s^2 rounds to all three printed values; standard gravity
//! gives 0.004485, 0.005492, 0.002158 m (-2.5 %, -1.9 %, -1.9 %, still within
//! the paper's 4 %). The first case's "a = 3.3, b = 3.3" means 3.3 m from each
//! end (loads at 3.3 m and 6.7 m): both loads at 3.3 m would give 0.004889 m
//! (+6.3 %). Mid-span deflections (0.005289, 0.0059, 0.00355 m) do not match:
//! the paper's remark that the maximum lies under the loads is not true for
//! these symmetric cases, where mid-span deflects most.
//!
//! ```
//! use armkit::beam::{PointLoad, SimplySupportedBeam, SEED000_GRAVITY};
//! // Seed 000, Table 1, case (b): two 400 kg loads at 4 m and 6 m.
//! let beam = SimplySupportedBeam::with_rectangular_section(10.0, 200e9, 0.2, 0.2).unwrap();
//! let loads = [
//!     PointLoad::from_mass(4.0, 400.0, SEED000_GRAVITY).unwrap(),
//!     PointLoad::from_mass(6.0, 400.0, SEED000_GRAVITY).unwrap(),
//! ];
//! let w = beam.deflection(4.0, &loads).unwrap();
//! assert!((w - 0.0056).abs() < 1e-12); // the printed 0.0056 m
//! // A load outside the span is an error that names it.
//! let bad = [PointLoad::new(12.0, 1000.0)];
//! assert!(beam.deflection(4.0, &bad).unwrap_err().to_string().contains("loads[0].position"));
//! ```

use crate::error::{check_positive, Error, Result};
use std::sync::Arc;

use crate::model::{CouplingCurve, CouplingLaw, JointCoupling};

/// Span of seed 000's beam between its supports, m (Table 1): the gantry's
/// beam ([`crate::robots::GANTRY9_BEAM_LENGTH`] is this value).
pub const SEED000_BEAM_LENGTH: f64 = 10.0;

pub use crate::seeds::{SEED000_GRAVITY, STANDARD_GRAVITY};

/// Mass hanging from one carriage in seed 000, kg (arm and payload; Table 1's
/// `P1 = P2 = 400 kg`).
pub const SEED000_CARRIAGE_MASS: f64 = 400.0;

/// Young's modulus of seed 000's alloy-steel beam, Pa (200 GPa).
pub const SEED000_YOUNGS_MODULUS: f64 = 200e9;

/// Side of seed 000's square beam section, m.
pub const SEED000_SECTION_SIDE: f64 = 0.2;

/// Second moment of area (m^4) of a solid rectangular section about its
/// horizontal centroidal axis: `I = width height^3 / 12`, `height` measured
/// in the direction of bending (vertical), both in m and finite > 0.
pub fn rectangular_second_moment(width: f64, height: f64) -> Result<f64> {
    check_positive("width", width)?;
    check_positive("height", height)?;
    Ok(width * height.powi(3) / 12.0)
}

/// Second moment of area (m^4) of a solid square section of side `side` (m):
/// `I = side^4 / 12` (seed 000's `I = b^4 / 12`).
pub fn square_second_moment(side: f64) -> Result<f64> {
    check_positive("side", side)?;
    rectangular_second_moment(side, side)
}

/// The weight (N) of `mass` kg under gravity `gravity` m/s^2: mass finite and
/// >= 0, gravity finite and > 0.
pub fn weight(mass: f64, gravity: f64) -> Result<f64> {
    if !(mass.is_finite() && mass >= 0.0) {
        return Err(Error::invalid_argument(
            "mass",
            format!("must be finite and >= 0 kg, got {mass}"),
        ));
    }
    check_positive("gravity", gravity)?;
    Ok(mass * gravity)
}

/// A concentrated load on a beam: `position` m from the left support, `force`
/// N, positive downward (a weight); negative forces push up.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointLoad {
    /// Distance from the left support, m (must lie on the span `[0, L]`).
    pub position: f64,
    /// Force, N, positive downward (must be finite).
    pub force: f64,
}

impl PointLoad {
    /// A load of `force` N (downward positive) at `position` m; checked when used.
    pub fn new(position: f64, force: f64) -> Self {
        PointLoad { position, force }
    }

    /// The weight of `mass` kg under gravity `gravity` m/s^2, at `position` m.
    pub fn from_mass(position: f64, mass: f64, gravity: f64) -> Result<Self> {
        Ok(PointLoad::new(position, weight(mass, gravity)?))
    }
}

/// The influence function `G(x, c)` of a unit load at `c` on the deflection at
/// `x` (m/N, downward) and its partial derivatives with respect to `x` and `c`.
#[derive(Clone, Copy, Debug)]
struct Influence {
    value: f64,
    d_dx: f64,
    d_dc: f64,
}

/// A simply supported beam: span (m), Young's modulus (Pa), second moment of
/// area of its section (m^4). Always valid: every constructor checks its inputs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SimplySupportedBeam {
    length: f64,
    youngs_modulus: f64,
    second_moment: f64,
}

impl SimplySupportedBeam {
    /// A beam of span `length` m, Young's modulus `youngs_modulus` Pa and
    /// second moment of area `second_moment` m^4; each must be finite and > 0.
    pub fn new(length: f64, youngs_modulus: f64, second_moment: f64) -> Result<Self> {
        check_positive("length", length)?;
        check_positive("youngs_modulus", youngs_modulus)?;
        check_positive("second_moment", second_moment)?;
        Ok(SimplySupportedBeam {
            length,
            youngs_modulus,
            second_moment,
        })
    }

    /// A beam with a solid rectangular section `width` x `height` m (height
    /// vertical): `I = width height^3 / 12`.
    pub fn with_rectangular_section(
        length: f64,
        youngs_modulus: f64,
        width: f64,
        height: f64,
    ) -> Result<Self> {
        Self::new(
            length,
            youngs_modulus,
            rectangular_second_moment(width, height)?,
        )
    }

    /// Seed 000's beam (Table 1): alloy steel, `E = 200 GPa`, span
    /// `L = 10 m` (= [`SEED000_BEAM_LENGTH`]), solid square section of side
    /// 0.2 m, `I = 0.2^4 / 12 = 1.333e-4 m^4`; `E I = 2.667e7 N m^2`.
    pub fn seed000() -> Self {
        SimplySupportedBeam {
            length: SEED000_BEAM_LENGTH,
            youngs_modulus: SEED000_YOUNGS_MODULUS,
            second_moment: SEED000_SECTION_SIDE.powi(4) / 12.0,
        }
    }

    /// Span between the supports, m.
    pub fn length(&self) -> f64 {
        self.length
    }

    /// Young's modulus, Pa.
    pub fn youngs_modulus(&self) -> f64 {
        self.youngs_modulus
    }

    /// Second moment of area of the section, m^4.
    pub fn second_moment(&self) -> f64 {
        self.second_moment
    }

    /// Bending stiffness `E I`, N m^2.
    pub fn stiffness(&self) -> f64 {
        self.youngs_modulus * self.second_moment
    }

    /// Deflection (m, downward) at `x` m from the left support under all
    /// `loads` (superposition of the point-load formula, both branches).
    /// Errors: `x` or a load's position off the span `[0, L]` or not finite,
    /// a non-finite force.
    pub fn deflection(&self, x: f64, loads: &[PointLoad]) -> Result<f64> {
        self.sum_over_loads(x, loads, |g, force| g.value * force)
    }

    /// Slope `dw/dx` (m/m, deflection downward) of the deflected beam at `x`
    /// m under all `loads`; same errors as [`SimplySupportedBeam::deflection`].
    pub fn slope(&self, x: f64, loads: &[PointLoad]) -> Result<f64> {
        self.sum_over_loads(x, loads, |g, force| g.d_dx * force)
    }

    /// Deflection (m, downward) at `x` m caused by one `load` alone.
    pub fn deflection_due_to(&self, x: f64, load: PointLoad) -> Result<f64> {
        self.deflection(x, &[load])
    }

    /// Derivative (m/m) of the deflection at the fixed point `x` m with
    /// respect to the position of `load` (the other loads do not matter:
    /// superposition). With `x` at the load and moving with it, the total
    /// derivative is this plus [`SimplySupportedBeam::slope`] (see
    /// [`CarriageDeflection::deflection_and_slope`]).
    pub fn deflection_derivative_wrt_load_position(&self, x: f64, load: PointLoad) -> Result<f64> {
        self.sum_over_loads(x, &[load], |g, force| g.d_dc * force)
    }

    /// Deflection (m, downward) at the point of a single load of `force` N
    /// placed at `position` m from the left support:
    /// `w = F a^2 b^2 / (3 E I L)`, `b = L - a` (seed 000, eq 1).
    pub fn deflection_under_load(&self, position: f64, force: f64) -> Result<f64> {
        self.check_on_span(position, || "position".into())?;
        self.deflection(position, &[PointLoad::new(position, force)])
    }

    /// `sum_k term(G(x, c_k), P_k)` after checking `x` and every load.
    fn sum_over_loads(
        &self,
        x: f64,
        loads: &[PointLoad],
        term: impl Fn(Influence, f64) -> f64,
    ) -> Result<f64> {
        self.check_on_span(x, || "x".into())?;
        let mut total = 0.0;
        for (k, load) in loads.iter().enumerate() {
            self.check_on_span(load.position, || format!("loads[{k}].position"))?;
            if !load.force.is_finite() {
                return Err(Error::invalid_argument(
                    format!("loads[{k}].force"),
                    format!("must be finite, got {}", load.force),
                ));
            }
            total += term(self.influence(x, load.position), load.force);
        }
        Ok(total)
    }

    /// Checks `position` lies on `[0, L]`; `name` (only built on error, to
    /// keep the success path allocation-free) names the argument.
    fn check_on_span(&self, position: f64, name: impl FnOnce() -> String) -> Result<()> {
        if position.is_finite() && (0.0..=self.length).contains(&position) {
            Ok(())
        } else {
            Err(Error::invalid_argument(
                name(),
                format!(
                    "must lie on the span [0, {}] m, got {position}",
                    self.length
                ),
            ))
        }
    }

    /// `G(x, c)` and its partials, for `x`, `c` on the span (seed 000, eq 1
    /// generalised to any point: the standard point-load deflection curve).
    fn influence(&self, x: f64, c: f64) -> Influence {
        let l = self.length;
        let k = 1.0 / (6.0 * self.stiffness() * l);
        if x <= c {
            // Left of the load: G = b x (L^2 - b^2 - x^2) k, b = L - c.
            let b = l - c;
            Influence {
                value: k * b * x * (l * l - b * b - x * x),
                d_dx: k * b * (l * l - b * b - 3.0 * x * x),
                d_dc: k * x * (2.0 * l * l - 6.0 * l * c + 3.0 * c * c + x * x),
            }
        } else {
            // Right of the load: the mirror image, r = L - x the distance to
            // the right support: G = c r (L^2 - c^2 - r^2) k.
            let r = l - x;
            Influence {
                value: k * c * r * (l * l - c * c - r * r),
                d_dx: -k * c * (l * l - c * c - 3.0 * r * r),
                d_dc: k * r * (l * l - 3.0 * c * c - r * r),
            }
        }
    }

    /// `(w, dw/da)` under a single load `force` at `a` that moves with the
    /// point of interest, `a` clamped to the span (the derivative is zero
    /// outside it). Corrected seed 000 eq 8:
    /// `d/da [a^2 (L-a)^2] = 2 a (L-a)(L-2a)`. No checks: the hot path of
    /// forward kinematics.
    fn deflection_and_slope_under_load(&self, a: f64, force: f64) -> (f64, f64) {
        let l = self.length;
        if a.is_nan() {
            // NaN in, NaN out: `clamp` keeps NaN, so the branch below would
            // recurse on it forever (a stack overflow, found by
            // tests/invariants_nonfinite.rs).
            return (f64::NAN, f64::NAN);
        }
        if !(0.0..=l).contains(&a) {
            let clamped = a.clamp(0.0, l);
            return (self.deflection_and_slope_under_load(clamped, force).0, 0.0);
        }
        let b = l - a;
        let k = force / (3.0 * self.stiffness() * l);
        (k * a * a * b * b, k * 2.0 * a * b * (l - 2.0 * a))
    }
}

/// A carriage of weight `force` (N) riding on a beam: the deflection under it
/// as a function of its position (the gantry's `w(d2)`, seed 000 eq 4).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CarriageDeflection {
    /// The beam.
    pub beam: SimplySupportedBeam,
    /// The carriage's weight (arm and payload), N, downward positive.
    pub force: f64,
}

impl CarriageDeflection {
    /// A carriage of weight `force` N (finite, >= 0) on `beam`.
    pub fn new(beam: SimplySupportedBeam, force: f64) -> Result<Self> {
        let carriage = CarriageDeflection { beam, force };
        carriage.validate()?;
        Ok(carriage)
    }

    /// A carriage carrying `mass` kg under gravity `gravity` m/s^2 on `beam`.
    pub fn from_mass(beam: SimplySupportedBeam, mass: f64, gravity: f64) -> Result<Self> {
        Self::new(beam, weight(mass, gravity)?)
    }

    /// Seed 000's carriage: [`SimplySupportedBeam::seed000`] carrying
    /// [`SEED000_CARRIAGE_MASS`] = 400 kg under [`SEED000_GRAVITY`] = 10 m/s^2,
    /// a 4000 N load (the numbers of Table 1). The deflection is 3.125 mm at
    /// mid-span, 2.205 mm at `d2 = 3 m`.
    pub fn seed000() -> Self {
        CarriageDeflection {
            beam: SimplySupportedBeam::seed000(),
            force: SEED000_CARRIAGE_MASS * SEED000_GRAVITY,
        }
    }

    /// Checks the force is finite and >= 0 (a weight); the beam is valid by
    /// construction.
    pub fn validate(&self) -> Result<()> {
        if self.force.is_finite() && self.force >= 0.0 {
            Ok(())
        } else {
            Err(Error::invalid_argument(
                "force",
                format!(
                    "carriage weight must be finite and >= 0 N, got {}",
                    self.force
                ),
            ))
        }
    }

    /// `(w, dw/da)` in m and m/m for the carriage at `a` m from the left
    /// support; positions off the span are clamped to it (slope zero there).
    /// `dw/da` is seed 000's `m2` (eq 9).
    pub fn deflection_and_slope(&self, a: f64) -> (f64, f64) {
        self.beam.deflection_and_slope_under_load(a, self.force)
    }
}

/// The beam's deflection as the gantry's coupling curve: `d3' = d3 + w(d2)`
/// (seed 000 eq 4 corrected), slope `m2 = dw/dd2` (eq 9).
impl CouplingCurve for CarriageDeflection {
    fn value_and_slope(&self, x: f64) -> (f64, f64) {
        self.deflection_and_slope(x)
    }

    fn describe(&self) -> String {
        format!(
            "the deflection w of a simply supported {} m beam (E I = {:e} N m^2) under a {} N carriage",
            self.beam.length(),
            self.beam.stiffness(),
            self.force
        )
    }

    fn validate(&self) -> Result<()> {
        CarriageDeflection::validate(self)
    }
}

/// Whether a gantry's beam bends under its carriage.
///
/// Everywhere gantry9 is built ([`crate::robots::gantry9_with_beam`]), this
/// switches the deflection on or off; [`GantryBeam::Rigid`] gives back
/// [`crate::robots::gantry9`] exactly.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum GantryBeam {
    /// No deflection: `d3' = d3`.
    Rigid,
    /// The carriage sinks by `w(d2)`: `d3' = d3 + w(d2)` (seed 000 eq 4
    /// corrected), `J = J0 M` (eqs 8-10).
    Flexible(CarriageDeflection),
}

impl Default for GantryBeam {
    /// Seed 000's flexible beam, [`CarriageDeflection::seed000`].
    fn default() -> Self {
        GantryBeam::Flexible(CarriageDeflection::seed000())
    }
}

impl GantryBeam {
    /// The joint coupling that implements this beam when joint `carriage`
    /// (0-based) moves the carriage along the beam and joint `vertical`
    /// lowers the arm; `None` for a rigid beam.
    pub fn coupling(&self, carriage: usize, vertical: usize) -> Option<JointCoupling> {
        match self {
            GantryBeam::Rigid => None,
            GantryBeam::Flexible(deflection) => Some(JointCoupling {
                source: carriage,
                target: vertical,
                law: CouplingLaw::Additive(Arc::new(*deflection)),
            }),
        }
    }
}

/// Two carriages of weights `forces[0]`, `forces[1]` (N) on one beam: seed
/// 000's two-arm gantry (Fig 4, eqs 2-3), for the deflection under each.
///
/// With the carriages at `a` and `b` m from the left support, `a <= b`, the
/// deflection under each is (downward, corrected eqs 2-3):
///
/// * `wA = P1 a^2 (L-a)^2 / (3EIL) + P2 a (L-b) (L^2 - (L-b)^2 - a^2) / (6EIL)`,
/// * `wB = P2 b^2 (L-b)^2 / (3EIL) + P1 a (L-b) (L^2 - a^2 - (L-b)^2) / (6EIL)`.
///
/// Any order of `a` and `b` works (the influence function picks its branch).
///
/// ```
/// use armkit::beam::TwoCarriageBeam;
/// let gantry = TwoCarriageBeam::seed000();
/// let [wa, wb] = gantry.deflections([2.0, 8.0]).unwrap();
/// assert!((wa - 0.0022).abs() < 1e-12 && (wb - 0.0022).abs() < 1e-12); // Table 1 (c)
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TwoCarriageBeam {
    /// The beam.
    pub beam: SimplySupportedBeam,
    /// The weights of carriages A and B, N, downward positive.
    pub forces: [f64; 2],
}

impl TwoCarriageBeam {
    /// Two carriages of weights `forces` N (finite, >= 0) on `beam`.
    pub fn new(beam: SimplySupportedBeam, forces: [f64; 2]) -> Result<Self> {
        for (k, force) in forces.iter().enumerate() {
            if !(force.is_finite() && *force >= 0.0) {
                return Err(Error::invalid_argument(
                    format!("forces[{k}]"),
                    format!("carriage weight must be finite and >= 0 N, got {force}"),
                ));
            }
        }
        Ok(TwoCarriageBeam { beam, forces })
    }

    /// Seed 000's two-arm gantry: [`SimplySupportedBeam::seed000`] with two
    /// 400 kg carriages under `g = 10 m/s^2` (4000 N each), as in Table 1.
    pub fn seed000() -> Self {
        let force = SEED000_CARRIAGE_MASS * SEED000_GRAVITY;
        TwoCarriageBeam {
            beam: SimplySupportedBeam::seed000(),
            forces: [force, force],
        }
    }

    fn check_positions(&self, positions: [f64; 2]) -> Result<()> {
        for (k, position) in positions.iter().enumerate() {
            self.beam
                .check_on_span(*position, || format!("positions[{k}]"))?;
        }
        Ok(())
    }

    fn loads(&self, positions: [f64; 2]) -> [PointLoad; 2] {
        [
            PointLoad::new(positions[0], self.forces[0]),
            PointLoad::new(positions[1], self.forces[1]),
        ]
    }

    /// Deflections (m, downward) `[wA, wB]` under carriages A and B at
    /// `positions` m from the left support (eqs 2-3 corrected). Errors: a
    /// position off the span.
    pub fn deflections(&self, positions: [f64; 2]) -> Result<[f64; 2]> {
        self.check_positions(positions)?;
        let loads = self.loads(positions);
        Ok([
            self.beam.deflection(positions[0], &loads)?,
            self.beam.deflection(positions[1], &loads)?,
        ])
    }

    /// `D[i][j] = d w_i / d p_j` (m/m): how the deflection under carriage `i`
    /// changes when carriage `j` moves (the two-arm analogue of seed 000's
    /// `m2`). Diagonal: the beam's slope at the carriage plus the effect of
    /// moving its own load; off-diagonal: moving the other load only.
    pub fn deflection_jacobian(&self, positions: [f64; 2]) -> Result<[[f64; 2]; 2]> {
        self.check_positions(positions)?;
        let loads = self.loads(positions);
        let mut d = [[0.0; 2]; 2];
        for (i, row) in d.iter_mut().enumerate() {
            let x = positions[i];
            for (j, entry) in row.iter_mut().enumerate() {
                *entry = self
                    .beam
                    .deflection_derivative_wrt_load_position(x, loads[j])?;
            }
            row[i] += self.beam.slope(x, &loads)?;
        }
        Ok(d)
    }
}

/// One load case of seed 000's Table 1: two equal loads, the printed
/// theoretical deflection under them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Table1Case {
    /// The case as the paper labels it.
    pub label: &'static str,
    /// Positions of the two loads from the left support, m.
    pub positions: [f64; 2],
    /// The paper's theoretical deflection under the loads, m.
    pub paper: f64,
}

/// Seed 000's Table 1, theoretical column: the three symmetric load cases
/// ("a = 3.3, b = 3.3" read as 3.3 m from each end). Beam and loads:
/// [`TwoCarriageBeam::seed000`] (the printed values use `g = 10 m/s^2`).
pub const SEED000_TABLE1: [Table1Case; 3] = [
    Table1Case {
        label: "a=3.3, b=3.3",
        positions: [3.3, 6.7],
        paper: 0.0046,
    },
    Table1Case {
        label: "a=4, b=6",
        positions: [4.0, 6.0],
        paper: 0.0056,
    },
    Table1Case {
        label: "a=2, b=8",
        positions: [2.0, 8.0],
        paper: 0.0022,
    },
];
