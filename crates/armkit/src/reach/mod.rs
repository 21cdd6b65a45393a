//! Reachability and capability maps: which tool poses an arm reaches, over a
//! position grid times a set of tool orientations.
//!
//! * [`MapLayout`]: cubic position cells (edge [`MapSpec::resolution`], m)
//!   over the box of the arm's reach bound ([`crate::ik::ReachBound`]),
//!   times [`MapSpec::approach_directions`] near-uniform approach directions
//!   of the tool z axis (a Fibonacci lattice) times [`MapSpec::rolls`] roll
//!   samples about each.
//! * [`build_chunk`]: one deterministic piece of the map. By
//!   [`Builder::InverseKinematics`] each (cell centre, orientation) pose is
//!   solved: analytic IK where the arm's class allows (every solution within
//!   the joint limits, counted), numeric IK with seeded restarts otherwise;
//!   per cell the best manipulability over the solutions found. By
//!   [`Builder::ForwardSampling`] (RM4D's way) configurations are drawn
//!   uniformly within the limits from a seeded RNG and each pose is binned.
//! * [`ReachMap`]: the merged map with the capability index per cell (the
//!   reachable fraction of the cell's orientations, after Zacharias et al.,
//!   "Capturing robot workspace structure", IROS 2007) and constant-time
//!   queries.
//! * [`build`]: the whole map on local threads; [`chunks`] partitions it for
//!   a distributed build whose merged result is the same.
//! * [`refine`]: the boundary between reachable and unreachable bins located
//!   within each disagreeing grid edge by bisection (after the merge), kept
//!   as a signed distance per bin ([`ReachMap::boundary`]) that the point
//!   query interpolates.
//! * [`MapTarget::Position`]: position-only maps (a cell is reachable when
//!   some configuration within the limits puts the tool point in it), for
//!   arms with fewer than six joints such as `arm4`.
//! * [`ReachBox`]: the box the map covers, the rails' travel plus the arm's
//!   reach for arms on prismatic axes (`gantry9`), else the reach ball's
//!   cube.
//! * [`base_placements`]: inverse reachability, the base positions on a
//!   floor grid ([`FloorGrid`]) from which every task pose is reachable,
//!   scored by the capability index.
//!
//! Frames and units: positions in the world frame (the frame of the model's
//! base transform), metres; tool orientations as rotation matrices in the
//! world frame; manipulability is Yoshikawa's `sqrt(det(J J'))` of the
//! world-frame geometric Jacobian (units mix m and rad).

mod bound;
mod build;
mod chunk;
mod directions;
mod layout;
mod map;
mod nearest;
mod oracle;
mod parallel;
mod placement;
mod refine;

pub use bound::ReachBox;
pub use build::{build, chunks, LOCAL_CHUNK_WORK};
pub use chunk::{build_chunk, Chunk, ChunkResult};
pub use layout::{fibonacci_directions, MapLayout, MAX_BINS};
pub use map::{ReachMap, BOUNDARY_UNITS};
pub use oracle::NUMERIC_RESTARTS;
pub use placement::{base_placements, BasePlacement, FloorGrid};
pub use refine::{apply_refinement, refine, refine_chunk, Crossing, Refinement};

use crate::error::{check_positive, Error, Result};
use crate::kinematics::{forward_kinematics, Data};
use crate::model::Model;

/// The smallest range of the last joint (rad) for which a redundant arm's
/// map takes one roll per approach direction ([`one_roll_suffices`]).
/// 300 degrees: the other joints' self-motion makes up the rest of the
/// turn. On the Panda (332 degrees, 7 joints) rolling the tool by a random
/// angle changes the ground truth's answer at 0.1 % of random poses in
/// the map's box, where snapping the orientation to 200 directions changes
/// it at 1.1 % and to 25 directions times 8 rolls at 3.0 % (20 000 poses,
/// the integration tests' `reach::snapping_cost_on_request`).
pub const REDUNDANT_ROLL_RANGE: f64 = 5.0 * std::f64::consts::PI / 3.0;

/// The range (rad) of the last joint when it turns the tool about the
/// tool's own z axis: the last joint is rotational and, at the neutral
/// configuration, its axis is the tool's z axis (parallel within 1e-9 rad)
/// through the tool's origin (within 1e-9 m). None otherwise.
fn tool_roll_range(model: &Model) -> Option<f64> {
    let last = model.joints().last()?;
    if !last.kind.is_rotational() || model.chain_joints().len() != model.dof() {
        return None;
    }
    let mut data = Data::new(model);
    let tool = *forward_kinematics(model, &mut data, &model.neutral_configuration()).ok()?;
    let joint = data.joint_frames().last()?;
    let axis = joint.rotation.column(2);
    let z = tool.rotation.column(2);
    let offset = tool.translation - joint.translation;
    (axis.cross(&z).norm() <= 1e-9 && offset.cross(&axis).norm() <= 1e-9)
        .then_some(last.limits.upper - last.limits.lower)
}

/// True when turning the tool about its own z axis is a motion of the last
/// joint alone over its whole range: the last joint turns the tool about
/// its z axis through its origin with a range of at least 2 pi. Then a
/// roll changes neither reachability nor the solutions' count or
/// manipulability, and a map needs one roll per approach direction.
pub fn roll_free(model: &Model) -> bool {
    tool_roll_range(model).is_some_and(|range| range >= std::f64::consts::TAU - 1e-9)
}

/// True when [`MapSpec::for_model`] gives `model` one roll per approach
/// direction: [`roll_free`] arms, and arms with more than six joints whose
/// last joint turns the tool about its z axis over at least
/// [`REDUNDANT_ROLL_RANGE`] (RM4D's assumption, Rudorfer ICRA 2025, which
/// it applies to the Panda too). For those the roll's effect is measured,
/// not exact: a pose whose roll only the missing part of the turn reaches
/// may be called reachable.
pub fn one_roll_suffices(model: &Model) -> bool {
    roll_free(model)
        || (model.dof() > 6
            && tool_roll_range(model).is_some_and(|range| range >= REDUNDANT_ROLL_RANGE))
}

/// How a map's bins are decided.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "io", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "io", serde(rename_all = "snake_case"))]
pub enum Builder {
    /// Inverse kinematics at every (cell centre, orientation) pose: exact at
    /// the bin's centre.
    InverseKinematics,
    /// Forward kinematics of `samples` configurations drawn uniformly within
    /// the joint limits (ChaCha8 seeded by `seed`; sample `s` from its own
    /// stream position, so any partition gives the same samples): a bin is
    /// reachable when a sample lands in it. Fast, but misses bins the
    /// samples did not hit (the coverage).
    ForwardSampling {
        /// Number of configurations drawn.
        samples: u64,
        /// RNG seed.
        seed: u64,
    },
}

/// What a bin asks of the tool.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "io", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "io", serde(rename_all = "snake_case"))]
pub enum MapTarget {
    /// The tool frame at the cell centre with each of the spec's
    /// orientations.
    #[default]
    Pose,
    /// The tool point at the cell centre, any orientation: one orientation
    /// per cell (the layout's orientation 0 is nominal, the query ignores
    /// the pose's rotation). The map of an arm with fewer than six joints,
    /// which cannot hold an arbitrary orientation anywhere.
    Position,
}

/// How the boundary between reachable and unreachable bins is kept.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "io", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "io", serde(rename_all = "snake_case"))]
pub enum Boundary {
    /// Halfway between the centres of neighbouring cells that disagree
    /// (the bits alone; maps saved before refinement existed read as this).
    #[default]
    Cells,
    /// Located by `steps` bisection steps (IK solves) along every grid
    /// edge whose two cells disagree, after the merge ([`refine`]): the
    /// crossing is known to `1 / 2^steps` of the edge (1 to 6 steps; the
    /// stored distance has [`BOUNDARY_UNITS`] units per cell).
    Bisection {
        /// IK solves per disagreeing edge (1..=6).
        steps: u8,
    },
}

impl Boundary {
    /// The constructors' choice for `builder`: [`DEFAULT_BISECTION_STEPS`]
    /// steps for the IK builder; the cells' boundary for the sampling
    /// builder, whose unhit bins inside the workspace would send the
    /// refinement after boundaries that are not there.
    pub fn default_for(builder: Builder) -> Boundary {
        match builder {
            Builder::InverseKinematics => Boundary::Bisection {
                steps: DEFAULT_BISECTION_STEPS,
            },
            Builder::ForwardSampling { .. } => Boundary::Cells,
        }
    }
}

/// Bisection steps of the default spec: 6, the crossing to 1/64 of a cell
/// edge (the stored distance's unit).
pub const DEFAULT_BISECTION_STEPS: u8 = 6;

/// What a map is: its resolution, orientation set and builder.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "io", derive(serde::Serialize, serde::Deserialize))]
pub struct MapSpec {
    /// Edge of a cubic position cell, m.
    pub resolution: f64,
    /// Near-uniform (Fibonacci) approach directions of the tool z axis.
    pub approach_directions: usize,
    /// Roll samples about each direction (orientations = directions x rolls).
    pub rolls: usize,
    /// How the bins are decided.
    pub builder: Builder,
    /// Tool poses or tool positions (absent in older files: poses).
    #[cfg_attr(feature = "io", serde(default))]
    pub target: MapTarget,
    /// How the boundary is kept (absent in older files: the cells' bits).
    #[cfg_attr(feature = "io", serde(default))]
    pub boundary: Boundary,
}

impl MapSpec {
    /// A position-only spec ([`MapTarget::Position`]): one nominal
    /// orientation (one direction, one roll), the boundary of
    /// [`Boundary::default_for`] the builder.
    pub fn position_only(resolution: f64, builder: Builder) -> MapSpec {
        MapSpec {
            resolution,
            approach_directions: 1,
            rolls: 1,
            builder,
            target: MapTarget::Position,
            boundary: Boundary::default_for(builder),
        }
    }

    /// A spec of `orientations` orientations split into directions and rolls
    /// with about equal angular spacing: the direction lattice's spacing
    /// `sqrt(4 pi / D)` equals the roll step `2 pi / R` when `R^3 = pi N`
    /// (`N = D R`); `R` the divisor of `N` nearest `round((pi N)^(1/3))`
    /// (within 2, else that value itself), `D = round(N / R)`, both >= 1.
    /// 200 orientations give 25 directions x 8 rolls. The boundary is
    /// [`Boundary::default_for`] the builder.
    pub fn with_orientations(resolution: f64, orientations: usize, builder: Builder) -> MapSpec {
        let n = orientations.max(1);
        let ideal = (std::f64::consts::PI * n as f64).cbrt().round() as usize;
        // The nearest roll count within 2 of the ideal that divides N, so
        // that directions x rolls is N itself where possible.
        let rolls = (0..=2)
            .flat_map(|d| [ideal.saturating_sub(d), ideal + d])
            .find(|&r| r >= 1 && r <= n && n % r == 0)
            .unwrap_or(ideal.clamp(1, n));
        let directions = ((n as f64 / rolls as f64).round() as usize).max(1);
        MapSpec {
            resolution,
            approach_directions: if orientations == 0 { 0 } else { directions },
            rolls,
            builder,
            target: MapTarget::Pose,
            boundary: Boundary::default_for(builder),
        }
    }

    /// The spec for `model`: position-only ([`MapSpec::position_only`],
    /// `orientations` unused) when the model has fewer than six joints (it
    /// cannot hold an arbitrary tool orientation anywhere, so per
    /// orientation the map would be nearly empty); when a roll of the tool
    /// about its z axis changes no answer, or on a redundant arm almost
    /// none ([`one_roll_suffices`]), the orientations are `orientations`
    /// approach directions with one roll each (RM4D's reduction, Rudorfer
    /// ICRA 2025); otherwise [`MapSpec::with_orientations`].
    pub fn for_model(
        model: &Model,
        resolution: f64,
        orientations: usize,
        builder: Builder,
    ) -> MapSpec {
        if model.dof() < 6 {
            MapSpec::position_only(resolution, builder)
        } else if one_roll_suffices(model) {
            MapSpec {
                approach_directions: orientations,
                rolls: 1,
                ..MapSpec::with_orientations(resolution, orientations, builder)
            }
        } else {
            MapSpec::with_orientations(resolution, orientations, builder)
        }
    }

    /// Orientations per cell (`approach_directions * rolls`).
    pub fn orientation_count(&self) -> usize {
        self.approach_directions.saturating_mul(self.rolls)
    }

    /// Checks the spec: a finite resolution > 0, at least one direction, one
    /// roll, exactly one of each for a position-only map, (sampling
    /// builder) one sample, 1 to 6 bisection steps; errors name the field.
    pub fn validate(&self) -> Result<()> {
        check_positive("resolution", self.resolution)?;
        if self.target == MapTarget::Position && (self.approach_directions, self.rolls) != (1, 1) {
            return Err(Error::invalid_argument(
                "approach_directions",
                format!(
                    "a position-only map has one nominal orientation (1 direction x 1 roll), got {} x {}: the tool's orientation is free",
                    self.approach_directions, self.rolls
                ),
            ));
        }
        if let Boundary::Bisection { steps } = self.boundary {
            if !(1..=DEFAULT_BISECTION_STEPS).contains(&steps) {
                return Err(Error::invalid_argument(
                    "steps",
                    format!("bisection steps must be 1 to {DEFAULT_BISECTION_STEPS} (the boundary is stored to 1/{BOUNDARY_UNITS} of a cell), got {steps}"),
                ));
            }
        }
        if self.approach_directions == 0 {
            return Err(Error::invalid_argument(
                "approach_directions",
                "must be at least 1 (zero orientations make an empty map)",
            ));
        }
        if self.rolls == 0 {
            return Err(Error::invalid_argument(
                "rolls",
                "must be at least 1 (zero orientations make an empty map)",
            ));
        }
        if let Builder::ForwardSampling { samples: 0, .. } = self.builder {
            return Err(Error::invalid_argument(
                "samples",
                "must be at least 1 for the forward-sampling builder",
            ));
        }
        Ok(())
    }
}
