//! The value enums of `armkit mpc`'s flags and what they map to.

use armkit::mpc::qp::QpSolverKind;
use armkit::mpc::PriorityMode;
use clap::ValueEnum;

/// `--reach` values.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ReachArg {
    /// The goal posture (IK with restarts), pulled toward in the cost.
    GoalPosture,
    /// Seed 000's plain planner.
    Off,
}

/// `--priority-mode` values.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum PriorityArg {
    /// The increment weights R in one cost (seed 000's eq 20).
    Weighted,
    /// Strict (lexicographic) priority by R, one QP per level.
    Strict,
}

impl From<PriorityArg> for PriorityMode {
    fn from(p: PriorityArg) -> Self {
        match p {
            PriorityArg::Weighted => PriorityMode::Weighted,
            PriorityArg::Strict => PriorityMode::Strict,
        }
    }
}

/// `--solver` values.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum SolverArg {
    /// The dense active-set solver (Goldfarb-Idnani), Clarabel as fallback.
    ActiveSet,
    /// Clarabel (interior point, pure Rust).
    Clarabel,
    /// OSQP (ADMM; needs armkit's `osqp` feature).
    Osqp,
}

impl From<SolverArg> for QpSolverKind {
    fn from(s: SolverArg) -> Self {
        match s {
            SolverArg::ActiveSet => QpSolverKind::ActiveSet,
            SolverArg::Clarabel => QpSolverKind::Clarabel,
            SolverArg::Osqp => QpSolverKind::Osqp,
        }
    }
}
