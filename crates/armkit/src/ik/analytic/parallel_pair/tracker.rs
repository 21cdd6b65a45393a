//! Subproblem 6 solved at the successive values of a searched joint, its
//! roots tracked from evaluation to evaluation ([`Tracker`]), and a
//! branch's rates by implicit differentiation ([`branch_rates`]): what the
//! parallel-pair and end-parallel-pair searches share per evaluation.

use crate::ik::analytic::parallel_pair::NEAR;
use crate::ik::analytic::subproblem6::{CirclePoints, Eliminated, Sinusoids, TurnPairs, Wave};
use crate::ik::analytic::subproblems::Turn;
use crate::ik::analytic::trig2::{Trig2, TrigRoots};
use std::cell::Cell;

/// Subproblem 6's roots at one evaluation, as the next one tracks them.
#[derive(Clone, Copy)]
enum Tracked {
    /// The null-space form's circle points.
    Circle(CirclePoints),
    /// The eliminated form's roots in the other unknown.
    Roots(TrigRoots),
}

/// Subproblem 6 of one search (`N` samples per turn) at successive values
/// `t` of the searched joint: solved by the eliminated form where the
/// unknown whose waves do not move with `t` has a well-conditioned block
/// (`subproblem6::Eliminated`), else by the null-space form; its roots
/// tracked from the last evaluation's or the nearest sample's (within
/// [`NEAR`]), isolated from scratch otherwise.
pub(in crate::ik::analytic) struct Tracker<const N: usize> {
    elimination: Option<Eliminated>,
    /// The searched joint's value at the last evaluation and subproblem
    /// 6's roots there.
    last: Cell<Option<(f64, Tracked)>>,
    /// Subproblem 6's roots at each sample of the search (starts for the
    /// evaluations between samples, wherever the last one was).
    grid: [Cell<Option<Tracked>>; N],
}

impl<const N: usize> Tracker<N> {
    /// A tracker by the null-space form, nothing tracked yet.
    pub(in crate::ik::analytic) fn new() -> Tracker<N> {
        Tracker {
            elimination: None,
            last: Cell::new(None),
            grid: std::array::from_fn(|_| Cell::new(None)),
        }
    }

    /// Solves by eliminating `fixed` (0: the first unknown, 1: the second;
    /// its waves the same at every `t`) from `system` (the system at any
    /// `t`) where its block is well conditioned.
    pub(in crate::ik::analytic) fn eliminate(&mut self, system: &Sinusoids, fixed: usize) {
        self.elimination = system.eliminating(fixed);
    }

    /// The exact solutions of `system` with right-hand side `d` at `t`.
    pub(in crate::ik::analytic) fn solve(
        &self,
        t: f64,
        system: &Sinusoids,
        d: [f64; 2],
    ) -> TurnPairs {
        // The nearest sample of the search, and whether `t` is one.
        let step = std::f64::consts::TAU / N as f64;
        let index = ((t + std::f64::consts::PI) / step).round();
        let sample = -std::f64::consts::PI + step * index;
        let slot = self.grid.get(index as usize % N);
        let on_grid = (t - sample).abs() <= 1e-12;
        // Starts within NEAR, the nearer first: the last evaluation's
        // roots and the nearest sample's (when the first does not certify:
        // a fold between).
        let mut starts = [None, None];
        if let Some((at, tracked)) = self.last.get() {
            if (at - t).abs() <= NEAR {
                starts[0] = Some((at - t).abs()).zip(Some(tracked));
            }
        }
        if let (false, Some(tracked)) = (on_grid, slot.and_then(Cell::get)) {
            if (sample - t).abs() <= NEAR {
                starts[1] = Some((sample - t).abs()).zip(Some(tracked));
            }
        }
        if let [Some((a, _)), Some((b, _))] = starts {
            if b < a {
                starts.swap(0, 1);
            }
        }
        let (pairs, tracked) = match &self.elimination {
            Some(eliminated) => {
                let start = starts.map(|s| match s {
                    Some((_, Tracked::Roots(roots))) => Some(roots),
                    _ => None,
                });
                let (pairs, roots) = system.exact_solutions_eliminated(d, eliminated, start);
                (pairs, Some(Tracked::Roots(roots)))
            }
            None => {
                let start = match starts.iter().flatten().next() {
                    Some((_, Tracked::Circle(points))) => Some(points),
                    _ => None,
                };
                let (pairs, points) = system.exact_solutions_near(d, start);
                (pairs, points.map(Tracked::Circle))
            }
        };
        self.last.set(tracked.map(|tracked| (t, tracked)));
        if let (true, Some(slot)) = (on_grid, slot) {
            slot.set(tracked);
        }
        pairs
    }

    /// Subproblem 6's `f` (no roots) for the right-hand side `d`, in the
    /// form [`Tracker::solve`] uses; `None` without a circle.
    pub(in crate::ik::analytic) fn difference(
        &self,
        system: &Sinusoids,
        d: [f64; 2],
    ) -> Option<Trig2> {
        match &self.elimination {
            Some(eliminated) => Some(system.eliminated_polynomial(d, eliminated)),
            None => system.difference_polynomial(d),
        }
    }
}

/// A wave's value at the turn `t`.
#[inline]
fn wave_value(w: &Wave, t: &Turn) -> f64 {
    w.cos_part * t.cos + w.sin_part * t.sin + w.constant
}

/// `d/dt` of a wave at the turn `t`.
#[inline]
fn wave_slope(w: &Wave, t: &Turn) -> f64 {
    w.sin_part * t.cos - w.cos_part * t.sin
}

/// On the branch through the solution `(a, b)` of `system` (right-hand
/// side `d(t)`): the Jacobian determinant of its two equations by
/// `(a, b)`, and the branch's rates `(a, b)' = -J^-1 F_t`, with `moving`
/// the system's derivative by `t` (each wave's parts) and `d_slope` that
/// of `d`.
#[inline]
pub(in crate::ik::analytic) fn branch_rates(
    system: &Sinusoids,
    moving: &Sinusoids,
    d_slope: [f64; 2],
    a: &Turn,
    b: &Turn,
) -> (f64, (f64, f64)) {
    let j = [
        [
            wave_slope(&system.first[0], a),
            wave_slope(&system.second[0], b),
        ],
        [
            wave_slope(&system.first[1], a),
            wave_slope(&system.second[1], b),
        ],
    ];
    let determinant = j[0][0] * j[1][1] - j[0][1] * j[1][0];
    let f_t = [
        wave_value(&moving.first[0], a) + wave_value(&moving.second[0], b) - d_slope[0],
        wave_value(&moving.first[1], a) + wave_value(&moving.second[1], b) - d_slope[1],
    ];
    let rates = (
        -(j[1][1] * f_t[0] - j[0][1] * f_t[1]) / determinant,
        -(j[0][0] * f_t[1] - j[1][0] * f_t[0]) / determinant,
    );
    (determinant, rates)
}
