//! Fixed-size working forms: a 6-joint chain as lines, and a stack buffer
//! of candidate solutions (nothing here allocates).

use super::structure::{ArmStructure, Motion};
use crate::math::{Pose, Vector3};

/// Most candidate solutions one solve produces (8 for every class here;
/// room for tangent duplicates).
pub(crate) const MAX_CANDIDATES: usize = 32;
/// Most joints of an arm the analytic solvers handle (7-DOF arms).
pub(crate) const MAX_JOINTS: usize = 7;

/// A 6-joint chain as lines at zero configuration (see
/// [`super::structure`]), in fixed-size arrays.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Chain {
    /// A point on each axis, m.
    pub c: [Vector3<f64>; 6],
    /// Unit axis directions.
    pub h: [Vector3<f64>; 6],
    /// Which joints slide.
    pub translation: [bool; 6],
    /// `home^-1`.
    pub home_inverse: Pose,
}

impl Chain {
    /// The chain of a 6-joint structure (`None` for another size).
    pub(crate) fn of(structure: &ArmStructure) -> Option<Chain> {
        if structure.dof() != 6 {
            return None;
        }
        let mut chain = Chain {
            c: [Vector3::zeros(); 6],
            h: [Vector3::zeros(); 6],
            translation: [false; 6],
            home_inverse: structure.home.inverse(),
        };
        for i in 0..6 {
            chain.c[i] = structure.points[i];
            chain.h[i] = structure.axes[i];
            chain.translation[i] = structure.motions[i] == Motion::Translation;
        }
        Some(chain)
    }
}

/// One candidate: joint values as solved (chain order) and whether every
/// subproblem on its way was exact.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Candidate {
    pub q: [f64; MAX_JOINTS],
    pub exact: bool,
}

/// A stack buffer of up to [`MAX_CANDIDATES`] candidates.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Candidates {
    items: [Candidate; MAX_CANDIDATES],
    len: usize,
}

impl Candidates {
    pub(crate) fn new() -> Candidates {
        Candidates {
            items: [Candidate {
                q: [0.0; MAX_JOINTS],
                exact: false,
            }; MAX_CANDIDATES],
            len: 0,
        }
    }

    /// Appends a candidate (the first `values.len()` joints); ignored when full.
    pub(crate) fn push(&mut self, values: &[f64], exact: bool) {
        if self.len < MAX_CANDIDATES {
            let item = &mut self.items[self.len];
            item.q = [0.0; MAX_JOINTS];
            for (slot, v) in item.q.iter_mut().zip(values) {
                *slot = *v;
            }
            item.exact = exact;
            self.len += 1;
        }
    }

    pub(crate) fn clear(&mut self) {
        self.len = 0;
    }

    pub(crate) fn as_slice(&self) -> &[Candidate] {
        &self.items[..self.len]
    }
}
