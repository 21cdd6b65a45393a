//! The classes of arms, and their detection from an [`ArmStructure`].

use super::structure::{ArmStructure, Motion, Relation, GEOMETRY_TOLERANCE};
use crate::math::Vector3;

/// How the special pair of consecutive axes of a one-pair arm lies.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PairKind {
    /// The two axes meet in one point.
    Intersecting,
    /// The two axes are parallel.
    Parallel,
}

/// Which end of the chain a structural feature is at.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ChainEnd {
    /// The last joints (the usual wrist).
    Tip,
    /// The first joints (solved on the reversed chain).
    Base,
}

/// How the three joints away from a spherical wrist position it (numbered
/// along the chain as solved, i.e. from the end opposite the wrist).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Positioning {
    /// Axes 2 and 3 parallel (PUMA, most industrial arms): subproblems 4, 3, 1.
    ParallelSecondThird,
    /// Axes 1 and 2 parallel: subproblems 4, 3, 1.
    ParallelFirstSecond,
    /// Axes 1 and 2 intersect (a shoulder offset beyond them is fine):
    /// subproblems 3, 2.
    IntersectingFirstSecond,
    /// Axes 2 and 3 intersect: subproblems 3, 2.
    IntersectingSecondThird,
    /// Axes 1 and 2 intersect, joint 3 prismatic (Stanford arm): a
    /// quadratic for the slide, then subproblem 2.
    PrismaticThird,
    /// No intersecting or parallel pair: subproblem 5 in closed form (a
    /// quartic; `three_axes`) places the wrist point.
    General,
}

/// The class of an arm, as far as the analytic solvers are concerned.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ArmClass {
    /// 6 joints, three consecutive rotation axes meeting in one point at
    /// one end: up to 8 solutions in closed form.
    SphericalWrist {
        /// Where the wrist is.
        end: ChainEnd,
        /// How the other three joints position it.
        positioning: Positioning,
    },
    /// 6 rotation joints, axes 2, 3, 4 parallel and axes 5, 6 intersecting
    /// (the Universal Robots family), counted from `end`'s opposite: up to 8
    /// solutions in closed form.
    ThreeParallel {
        /// The end the intersecting pair is at (`Tip` for UR arms).
        end: ChainEnd,
    },
    /// 6 rotation joints, axes 2, 3, 4 parallel (counted from `end`'s
    /// opposite), axes 1 and 5 not parallel to them, axes 5 and 6 not
    /// intersecting (else [`ArmClass::ThreeParallel`]; a UR-type arm with
    /// an offset wrist): subproblem 6, up to 8 solutions in closed form.
    ThreeParallelOffset {
        /// The end the general axes 5, 6 are at (`Tip`: axes 2-3-4 parallel).
        end: ChainEnd,
    },
    /// 7 rotation joints, axes 1-2-3 meeting at the shoulder, 5-6-7 at the
    /// wrist and 3-4-5 at the elbow (KUKA LWR4, iiwa): up to 8 solutions per
    /// elbow (arm) angle.
    SphericalShoulderElbowWrist,
    /// 6 rotation joints whose special consecutive axes (intersecting or
    /// parallel) fit no closed-form class: axes `first`, `first + 1`
    /// (1-based, model order) intersect, or are parallel on two distinct
    /// lines with no parallel neighbour (axis 3 not parallel to a pair at
    /// 1-2, axis 4 not to one at 5-6). Solved by elimination.
    OnePair {
        /// The pair's first joint, 1-based.
        first: u8,
        /// Intersecting or parallel.
        kind: PairKind,
    },
    /// 6 rotation joints without any intersecting or parallel consecutive
    /// axes: elimination.
    General,
    /// 6 rotation joints with special consecutive axes that fit neither a
    /// closed-form class nor [`ArmClass::OnePair`] (e.g. axes 1-2-3 parallel
    /// outside the UR family, where every parallel pair has a parallel neighbour, or a
    /// parallel pair on one line): elimination where it applies (axes 1-2-3
    /// parallel with the loop cut between joints 1 and 6), else no analytic
    /// solver.
    OtherPairs,
    /// Another number of joints, or prismatic joints where no class allows
    /// them.
    Other,
}

impl ArmClass {
    /// A short snake-case name (the CLI's JSON `class`).
    pub fn as_str(&self) -> &'static str {
        use ChainEnd::*;
        use Positioning::*;
        match self {
            ArmClass::SphericalWrist { end, positioning } => match (end, positioning) {
                (Tip, ParallelSecondThird) => "spherical_wrist_parallel_2_3",
                (Tip, ParallelFirstSecond) => "spherical_wrist_parallel_1_2",
                (Tip, IntersectingFirstSecond) => "spherical_wrist_intersecting_1_2",
                (Tip, IntersectingSecondThird) => "spherical_wrist_intersecting_2_3",
                (Tip, PrismaticThird) => "spherical_wrist_prismatic_3",
                (Tip, General) => "spherical_wrist_general_axes",
                (Base, ParallelSecondThird) => "spherical_base_parallel_5_4",
                (Base, ParallelFirstSecond) => "spherical_base_parallel_6_5",
                (Base, IntersectingFirstSecond) => "spherical_base_intersecting_6_5",
                (Base, IntersectingSecondThird) => "spherical_base_intersecting_5_4",
                (Base, PrismaticThird) => "spherical_base_prismatic_4",
                (Base, General) => "spherical_base_general_axes",
            },
            ArmClass::ThreeParallel { end: Tip } => "three_parallel_2_3_4_intersecting_5_6",
            ArmClass::ThreeParallel { end: Base } => "three_parallel_3_4_5_intersecting_1_2",
            ArmClass::ThreeParallelOffset { end: Tip } => "three_parallel_2_3_4",
            ArmClass::ThreeParallelOffset { end: Base } => "three_parallel_3_4_5",
            ArmClass::SphericalShoulderElbowWrist => "spherical_shoulder_elbow_wrist_7dof",
            ArmClass::OnePair { first, kind } => match (kind, first) {
                (PairKind::Intersecting, 1) => "one_pair_intersecting_1_2",
                (PairKind::Intersecting, 2) => "one_pair_intersecting_2_3",
                (PairKind::Intersecting, 3) => "one_pair_intersecting_3_4",
                (PairKind::Intersecting, 4) => "one_pair_intersecting_4_5",
                (PairKind::Intersecting, _) => "one_pair_intersecting_5_6",
                (PairKind::Parallel, 1) => "one_pair_parallel_1_2",
                (PairKind::Parallel, 2) => "one_pair_parallel_2_3",
                (PairKind::Parallel, 3) => "one_pair_parallel_3_4",
                (PairKind::Parallel, 4) => "one_pair_parallel_4_5",
                (PairKind::Parallel, _) => "one_pair_parallel_5_6",
            },
            ArmClass::General => "general_6r",
            ArmClass::OtherPairs => "other_special_pairs",
            ArmClass::Other => "other",
        }
    }

    /// A sentence for `--explain`.
    pub fn description(&self) -> &'static str {
        match self {
            ArmClass::SphericalWrist {
                end,
                positioning: Positioning::General,
            } => match end {
                ChainEnd::Tip => "spherical wrist at the tip, three general positioning axes: closed form (subproblem 5, a quartic, places the wrist point), up to 8 solutions",
                ChainEnd::Base => "spherical joint group at the base, three general positioning axes: closed form on the reversed chain (subproblem 5, a quartic), up to 8 solutions",
            },
            ArmClass::SphericalWrist { end: ChainEnd::Tip, .. } => {
                "spherical wrist at the tip (axes 4-5-6 meet in one point): closed form, up to 8 solutions"
            }
            ArmClass::SphericalWrist { end: ChainEnd::Base, .. } => {
                "spherical joint group at the base (axes 1-2-3 meet in one point): closed form on the reversed chain, up to 8 solutions"
            }
            ArmClass::ThreeParallel { .. } => {
                "three parallel axes and an intersecting pair (UR family): closed form, up to 8 solutions"
            }
            ArmClass::ThreeParallelOffset { .. } => {
                "three parallel axes, the two axes beyond them not intersecting (a UR with an offset wrist): closed form by subproblem 6 (a quartic, roots polished to round-off), up to 8 solutions"
            }
            ArmClass::SphericalShoulderElbowWrist => {
                "7-DOF spherical shoulder, elbow, spherical wrist: closed form per elbow angle, up to 8 solutions"
            }
            ArmClass::OnePair {
                kind: PairKind::Intersecting,
                ..
            } => {
                "one intersecting pair of consecutive axes, no closed-form class: by elimination, up to 16 solutions"
            }
            ArmClass::OnePair {
                kind: PairKind::Parallel,
                ..
            } => {
                "one parallel pair of consecutive axes, no intersecting pair, no closed-form class: by elimination, up to 16 solutions"
            }
            ArmClass::General => {
                "no intersecting or parallel consecutive axes: general 6R, by elimination"
            }
            ArmClass::OtherPairs => {
                "intersecting or parallel consecutive axes that fit no closed-form class and no one-pair class (a parallel pair with a parallel neighbour outside the UR family, or on one line): by elimination where it applies (axes 1-2-3 parallel with the loop cut between joints 1 and 6), else numeric solvers only"
            }
            ArmClass::Other => "not a 6-joint arm of a known class: numeric solver only",
        }
    }

    /// True for the classes with a solver by construction (closed forms and
    /// [`ArmClass::OnePair`]); [`ArmClass::General`] and
    /// [`ArmClass::OtherPairs`] are solved by elimination where it
    /// applies (see [`AnalyticSolver::method`](super::AnalyticSolver::method)).
    pub fn is_solvable(&self) -> bool {
        matches!(
            self,
            ArmClass::SphericalWrist { .. }
                | ArmClass::ThreeParallel { .. }
                | ArmClass::ThreeParallelOffset { .. }
                | ArmClass::SphericalShoulderElbowWrist
                | ArmClass::OnePair { .. }
        )
    }
}

impl std::fmt::Display for ArmClass {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// What detection found: the class and the points the solver needs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Detected {
    /// Spherical wrist; `wrist` the common point, `shoulder` the meeting
    /// point of the intersecting pair if any (chain as solved).
    SphericalWrist {
        end: ChainEnd,
        positioning: Positioning,
        wrist: Vector3<f64>,
        shoulder: Vector3<f64>,
    },
    /// Three parallel; `meet` the meeting point of axes 5 and 6.
    ThreeParallel {
        end: ChainEnd,
        meet: Vector3<f64>,
    },
    /// Three parallel without an intersecting end pair.
    ThreeParallelOffset {
        end: ChainEnd,
    },
    /// 7-DOF SRS: shoulder, elbow, wrist points.
    ShoulderElbowWrist {
        shoulder: Vector3<f64>,
        elbow: Vector3<f64>,
        wrist: Vector3<f64>,
    },
    /// One intersecting or parallel pair ([`ArmClass::OnePair`]), solved by
    /// elimination.
    Pair(ArmClass),
    Unsolvable(ArmClass),
}

impl Detected {
    pub(crate) fn class(&self) -> ArmClass {
        match *self {
            Detected::SphericalWrist {
                end, positioning, ..
            } => ArmClass::SphericalWrist { end, positioning },
            Detected::ThreeParallel { end, .. } => ArmClass::ThreeParallel { end },
            Detected::ThreeParallelOffset { end } => ArmClass::ThreeParallelOffset { end },
            Detected::ShoulderElbowWrist { .. } => ArmClass::SphericalShoulderElbowWrist,
            Detected::Pair(class) | Detected::Unsolvable(class) => class,
        }
    }
}

/// The class of `structure` (any number of joints).
pub(crate) fn detect(structure: &ArmStructure) -> Detected {
    if structure.dof() == 7 {
        return detect_seven(structure);
    }
    if structure.dof() != 6 {
        return Detected::Unsolvable(ArmClass::Other);
    }
    let reversed = structure.reversed();
    for (end, chain) in [(ChainEnd::Tip, structure), (ChainEnd::Base, &reversed)] {
        if let Some(found) = spherical_wrist(chain, end) {
            return found;
        }
    }
    for (end, chain) in [(ChainEnd::Tip, structure), (ChainEnd::Base, &reversed)] {
        if let Some(found) = three_parallel(chain, end) {
            return found;
        }
    }
    if structure.motions.contains(&Motion::Translation) {
        return Detected::Unsolvable(ArmClass::Other);
    }
    one_pair(structure, &reversed)
}

/// A 6R arm of no closed-form class: an intersecting pair (preferring
/// 5-6, 1-2, 4-5, 2-3, 3-4), else a lone parallel pair (2-3, 4-5, 3-4,
/// then 1-2, 5-6), else the first special pair (refused), else general.
fn one_pair(structure: &ArmStructure, reversed: &ArmStructure) -> Detected {
    let pair = |first, kind| Detected::Pair(ArmClass::OnePair { first, kind });
    // (1-based first joint in model order, chain, its 0-based first joint)
    let cases = [
        (5, structure, 4),
        (1, reversed, 4),
        (4, structure, 3),
        (2, reversed, 3),
        (3, structure, 2),
    ];
    for (first, chain, i) in cases {
        if let Relation::Intersecting(_) = chain.relation(i, i + 1) {
            return pair(first, PairKind::Intersecting);
        }
    }
    let parallel_cases = [(2, structure, 1), (4, reversed, 1), (3, structure, 2)];
    for (first, chain, p) in parallel_cases {
        if lone_parallel_pair(chain, p) {
            return pair(first, PairKind::Parallel);
        }
    }
    // Three consecutive parallel axes anywhere: no pair is lone, the arm
    // is named by its other special pairs below.
    let parallel_run = (0..4).any(|i| {
        structure.relation(i, i + 1) == Relation::Parallel
            && structure.relation(i + 1, i + 2) == Relation::Parallel
    });
    for (first, chain) in [(1, structure), (5, reversed)] {
        if !parallel_run && lone_end_parallel_pair(chain) {
            return pair(first, PairKind::Parallel);
        }
    }
    let special = (0..5).filter_map(|i| match structure.relation(i, i + 1) {
        Relation::Skew(_) => None,
        Relation::Parallel => Some((i, PairKind::Parallel)),
        Relation::Intersecting(_) => Some((i, PairKind::Intersecting)),
    });
    let mut any = false;
    for (i, kind) in special {
        any = true;
        let class = ArmClass::OnePair {
            first: i as u8 + 1,
            kind,
        };
        if !class.is_solvable() {
            return Detected::Unsolvable(class);
        }
    }
    // Special pairs only of solvable kinds that fit no pair above (a
    // parallel pair on one line, or with a parallel neighbour).
    Detected::Unsolvable(if any {
        ArmClass::OtherPairs
    } else {
        ArmClass::General
    })
}

/// True when axes `p`, `p + 1` (0-based) of `chain` are parallel, on two
/// distinct lines, and neither neighbour (`p - 1`, `p + 2`) is parallel to
/// them.
fn lone_parallel_pair(chain: &ArmStructure, p: usize) -> bool {
    chain.relation(p, p + 1) == Relation::Parallel
        && chain.relation(p - 1, p) != Relation::Parallel
        && chain.relation(p + 1, p + 2) != Relation::Parallel
        && chain.distance_to_axis(p + 1, &chain.points[p]) > GEOMETRY_TOLERANCE * chain.scale
}

/// True when axes 1-2 of `chain` are parallel on two distinct lines and
/// axis 3 is not parallel to them.
fn lone_end_parallel_pair(chain: &ArmStructure) -> bool {
    chain.relation(0, 1) == Relation::Parallel
        && chain.relation(1, 2) != Relation::Parallel
        && chain.distance_to_axis(1, &chain.points[0]) > GEOMETRY_TOLERANCE * chain.scale
}

fn rotational(chain: &ArmStructure, joints: std::ops::Range<usize>) -> bool {
    joints
        .into_iter()
        .all(|i| chain.motions[i] == Motion::Rotation)
}

fn spherical_wrist(chain: &ArmStructure, end: ChainEnd) -> Option<Detected> {
    if !rotational(chain, 3..6) {
        return None;
    }
    let wrist = chain.common_point(3, 4, 5)?;
    let found = |positioning, shoulder| {
        Some(Detected::SphericalWrist {
            end,
            positioning,
            wrist,
            shoulder,
        })
    };
    if chain.motions[2] == Motion::Translation {
        if !rotational(chain, 0..2) {
            return None;
        }
        return match chain.relation(0, 1) {
            Relation::Intersecting(o) => found(Positioning::PrismaticThird, o),
            _ => None,
        };
    }
    if !rotational(chain, 0..3) {
        return None;
    }
    let (r01, r12) = (chain.relation(0, 1), chain.relation(1, 2));
    match (r01, r12) {
        (Relation::Parallel, Relation::Parallel) => None,
        (_, Relation::Parallel) => found(Positioning::ParallelSecondThird, wrist),
        (Relation::Parallel, _) => found(Positioning::ParallelFirstSecond, wrist),
        (Relation::Intersecting(o), _) => found(Positioning::IntersectingFirstSecond, o),
        (_, Relation::Intersecting(o)) => found(Positioning::IntersectingSecondThird, o),
        _ => found(Positioning::General, wrist),
    }
}

fn three_parallel(chain: &ArmStructure, end: ChainEnd) -> Option<Detected> {
    if !rotational(chain, 0..6) {
        return None;
    }
    let parallel = |i, j| chain.relation(i, j) == Relation::Parallel;
    if !(parallel(1, 2) && parallel(2, 3)) || parallel(0, 1) || parallel(3, 4) {
        return None;
    }
    match chain.relation(4, 5) {
        Relation::Intersecting(meet) => Some(Detected::ThreeParallel { end, meet }),
        _ => Some(Detected::ThreeParallelOffset { end }),
    }
}

fn detect_seven(structure: &ArmStructure) -> Detected {
    if !rotational(structure, 0..7) {
        return Detected::Unsolvable(ArmClass::Other);
    }
    let shoulder = structure.common_point(0, 1, 2);
    let elbow = structure.common_point(2, 3, 4);
    let wrist = structure.common_point(4, 5, 6);
    match (shoulder, elbow, wrist) {
        (Some(shoulder), Some(elbow), Some(wrist))
            if (elbow - shoulder).norm() > 1e-6 && (wrist - elbow).norm() > 1e-6 =>
        {
            Detected::ShoulderElbowWrist {
                shoulder,
                elbow,
                wrist,
            }
        }
        _ => Detected::Unsolvable(ArmClass::Other),
    }
}
