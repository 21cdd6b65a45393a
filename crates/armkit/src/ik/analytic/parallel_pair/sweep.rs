//! The sides and subproblem 6 of a parallel-pair search as functions of
//! the searched joint's turn, read once per solve ([`Sweep`]).

use super::Sides;
use crate::ik::analytic::subproblem6::{Sinusoids, Wave};
use crate::ik::analytic::subproblems::Turn;
use crate::math::Vector3;

/// Values an evaluation reads, flattened: subproblem 6's four waves (cos
/// part, sin part, constant), `d`, and the sides' vectors `left[0]`,
/// `left[1]`, `right[0]`, `right[1]`.
const FLAT: usize = 25;

/// The sides and subproblem 6 of one search as functions of the searched
/// joint's turn `t`: each value is affine in `(cos t, sin t)` (joint `k`
/// turns `h` or the sides' vectors once, by Rodrigues, and the waves and
/// `d` are linear in those), `a + b cos t + c sin t`, read once per solve
/// at `t = 0`, `pi / 2`, `pi`.
/// `N` values (the parallel-pair search's [`FLAT`]; the end-pair search's
/// its own).
#[derive(Clone, Copy)]
pub(in crate::ik::analytic) struct Sweep<const N: usize = FLAT> {
    parts: [[f64; N]; 3],
}

impl<const N: usize> Sweep<N> {
    /// All zero (a placeholder until read).
    pub(in crate::ik::analytic) const ZERO: Sweep<N> = Sweep {
        parts: [[0.0; N]; 3],
    };

    /// The sweep of `exact`, the values at a turn.
    pub(in crate::ik::analytic) fn of(exact: impl Fn(&Turn) -> [f64; N]) -> Sweep<N> {
        let turn = |angle, sin, cos| Turn { angle, sin, cos };
        let zero = exact(&turn(0.0, 0.0, 1.0));
        let quarter = exact(&turn(std::f64::consts::FRAC_PI_2, 1.0, 0.0));
        let half = exact(&turn(std::f64::consts::PI, 0.0, -1.0));
        let mut parts = [[0.0; N]; 3];
        for i in 0..N {
            let a = 0.5 * (zero[i] + half[i]);
            parts[0][i] = a;
            parts[1][i] = 0.5 * (zero[i] - half[i]);
            parts[2][i] = quarter[i] - a;
        }
        Sweep { parts }
    }

    /// The values at `t`.
    pub(in crate::ik::analytic) fn at(&self, t: &Turn) -> [f64; N] {
        let mut out = [0.0; N];
        for (i, o) in out.iter_mut().enumerate() {
            *o = self.parts[0][i] + self.parts[1][i] * t.cos + self.parts[2][i] * t.sin;
        }
        out
    }

    /// The values' derivatives by `t` at `t`.
    pub(in crate::ik::analytic) fn slope_at(&self, t: &Turn) -> [f64; N] {
        let mut out = [0.0; N];
        for (i, o) in out.iter_mut().enumerate() {
            *o = self.parts[2][i] * t.cos - self.parts[1][i] * t.sin;
        }
        out
    }
}

/// Subproblem 6 and the sides as [`Sweep`] stores them.
pub(super) fn flatten(v: &Sides, system: &Sinusoids) -> [f64; FLAT] {
    let mut out = [0.0; FLAT];
    write_system(system, &mut out[..12]);
    out[12] = v.d;
    let vectors = [v.left[0], v.left[1], v.right[0], v.right[1]];
    for (i, x) in vectors.iter().enumerate() {
        out[13 + 3 * i..16 + 3 * i].copy_from_slice(x.as_slice());
    }
    out
}

/// [`flatten`]'s inverse, with the searched joint's turn.
pub(super) fn unflatten(flat: &[f64; FLAT], k: Turn) -> (Sides, Sinusoids) {
    let vector = |i: usize| Vector3::new(flat[13 + 3 * i], flat[14 + 3 * i], flat[15 + 3 * i]);
    (
        Sides {
            k,
            left: [vector(0), vector(1)],
            right: [vector(2), vector(3)],
            d: flat[12],
        },
        read_system(&flat[..12]),
    )
}

/// Subproblem 6's four waves into 12 values (each wave's cos part, sin
/// part, constant; `first[0]`, `first[1]`, `second[0]`, `second[1]`).
pub(in crate::ik::analytic) fn write_system(system: &Sinusoids, out: &mut [f64]) {
    let waves = [
        system.first[0],
        system.first[1],
        system.second[0],
        system.second[1],
    ];
    for (i, w) in waves.iter().enumerate() {
        out[3 * i] = w.cos_part;
        out[3 * i + 1] = w.sin_part;
        out[3 * i + 2] = w.constant;
    }
}

/// [`write_system`]'s inverse.
pub(in crate::ik::analytic) fn read_system(flat: &[f64]) -> Sinusoids {
    let wave = |i: usize| Wave {
        cos_part: flat[3 * i],
        sin_part: flat[3 * i + 1],
        constant: flat[3 * i + 2],
    };
    Sinusoids {
        first: [wave(0), wave(1)],
        second: [wave(2), wave(3)],
    }
}
