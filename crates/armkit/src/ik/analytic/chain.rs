//! Fixed-size working forms: a 6-joint chain as lines, a stack buffer of
//! candidate solutions, and the lines' forward kinematics prepared for the
//! solutions' check (nothing here allocates after set-up).

use super::structure::{ArmStructure, Motion};
use crate::math::{sin_cos_slice, wrap_angle, Matrix3, Pose, Vector3};

/// Most candidate solutions one solve produces (8 for every class here;
/// room for tangent duplicates).
pub(crate) const MAX_CANDIDATES: usize = 32;
/// Largest difference (rad, every joint, modulo 2 pi) of two candidates of
/// one solve that are the same solution.
pub(crate) const SAME_SOLUTION: f64 = 1e-9;
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
        Some(Chain {
            c: std::array::from_fn(|i| structure.points[i]),
            h: std::array::from_fn(|i| structure.axes[i]),
            translation: std::array::from_fn(|i| structure.motions[i] == Motion::Translation),
            home_inverse: structure.home.inverse(),
        })
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

    /// Appends a candidate (the first `values.len()` joints; the rest keep
    /// whatever they held); ignored when full.
    #[inline]
    pub(crate) fn push(&mut self, values: &[f64], exact: bool) {
        if self.len < MAX_CANDIDATES {
            let item = &mut self.items[self.len];
            for (slot, v) in item.q.iter_mut().zip(values) {
                *slot = *v;
            }
            item.exact = exact;
            self.len += 1;
        }
    }

    /// [`Candidates::push`] unless a candidate held already has each of
    /// the first `values.len()` joints within [`SAME_SOLUTION`] of it
    /// (modulo 2 pi): how elimination's candidates from nearby roots are
    /// merged.
    #[inline]
    pub(crate) fn push_distinct(&mut self, values: &[f64], exact: bool) {
        let repeated = self.as_slice().iter().any(|held| {
            held.q
                .iter()
                .zip(values)
                .all(|(a, b)| wrap_angle(a - b).abs() < SAME_SOLUTION)
        });
        if !repeated {
            self.push(values, exact);
        }
    }

    pub(crate) fn clear(&mut self) {
        self.len = 0;
    }

    pub(crate) fn as_slice(&self) -> &[Candidate] {
        &self.items[..self.len]
    }
}

/// Forward kinematics of an arm's product of exponentials (see
/// [`super::structure`]), prepared for a fast, allocation-free evaluation:
/// with `F_i` a frame on joint `i`'s line whose z axis is the joint axis,
/// `E_i(t) = F_i Z(t) F_i^-1` (`Z` a turn about or a slide along z), so
/// `T(q) = E_1(q_1) ... E_n(q_n) home = G_0 Z(q_1) G_1 Z(q_2) ... Z(q_n) G_n`
/// with the fixed `G_0 = F_1`, `G_i = F_i^-1 F_(i+1)`, `G_n = F_n^-1 home`
/// read once. Transforms are kept as the three rows of `[R | p]`; a step
/// costs one sine-cosine and three row-times-matrix products.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct LineKinematics {
    dof: usize,
    first: Rows,
    motions: [Motion; MAX_JOINTS],
    /// `G_i` as rows of `[R | p]`.
    after: [Rows; MAX_JOINTS],
}

/// A rigid transform as the three rows of `[R | p]` (3 x 4).
type Rows = [[f64; 4]; 3];

fn rows_of(pose: &Pose) -> Rows {
    let (r, p) = (&pose.rotation, &pose.translation);
    let mut rows = [[0.0; 4]; 3];
    for (i, row) in rows.iter_mut().enumerate() {
        *row = [r[(i, 0)], r[(i, 1)], r[(i, 2)], p[i]];
    }
    rows
}

fn pose_of(rows: &Rows) -> Pose {
    let [a, b, c] = rows;
    Pose::new(
        Matrix3::new(a[0], a[1], a[2], b[0], b[1], b[2], c[0], c[1], c[2]),
        Vector3::new(a[3], b[3], c[3]),
    )
}

impl LineKinematics {
    /// The prepared product of `structure` (`None` beyond [`MAX_JOINTS`]
    /// joints).
    pub(crate) fn new(structure: &ArmStructure) -> Option<LineKinematics> {
        let dof = structure.dof();
        if dof == 0 || dof > MAX_JOINTS {
            return None;
        }
        let frame = |i: usize| {
            Pose::new(
                crate::math::rotation_z_to(&structure.axes[i]),
                structure.points[i],
            )
        };
        let mut kinematics = LineKinematics {
            dof,
            first: rows_of(&frame(0)),
            motions: [Motion::Rotation; MAX_JOINTS],
            after: [[[0.0; 4]; 3]; MAX_JOINTS],
        };
        for i in 0..dof {
            kinematics.motions[i] = structure.motions[i];
            let next = if i + 1 < dof {
                frame(i + 1)
            } else {
                structure.home
            };
            kinematics.after[i] = rows_of(&(frame(i).inverse() * next));
        }
        Some(kinematics)
    }

    /// Number of joints.
    pub(crate) fn dof(&self) -> usize {
        self.dof
    }

    /// `G_0 Z(q_1) G_1 ... Z(q_i) G_i` from the product up to joint `i - 1`
    /// (`frame`) and joint `i`'s value with its sine and cosine: one step.
    /// With `frame = [X Y Z | p]` and `G_i`'s rows `g0, g1, g2`, a turn by
    /// `t` gives the rows `X_r a + Y_r b + Z_r g2 (+ p_r)` with
    /// `a = cos t g0 - sin t g1`, `b = sin t g0 + cos t g1`; a slide by `d`
    /// is the same with `t = 0` and `p` moved by `d Z`.
    #[inline]
    fn step(&self, frame: &Rows, i: usize, value: f64, (s, c): (f64, f64)) -> Rows {
        let [g0, g1, g2] = &self.after[i];
        let (s, c, slide) = match self.motions[i] {
            Motion::Rotation => (s, c, 0.0),
            Motion::Translation => (0.0, 1.0, value),
        };
        let mut a = [0.0; 4];
        let mut b = [0.0; 4];
        for j in 0..4 {
            a[j] = c * g0[j] - s * g1[j];
            b[j] = s * g0[j] + c * g1[j];
        }
        let mut out = [[0.0; 4]; 3];
        for (row, f) in out.iter_mut().zip(frame) {
            for j in 0..4 {
                row[j] = f[0] * a[j] + f[1] * b[j] + f[2] * g2[j];
            }
            row[3] += f[3] + slide * f[2];
        }
        out
    }
}

/// [`LineKinematics`] with the products of the last configuration kept, so
/// that a configuration sharing its first joints with the previous one (the
/// candidates of one solve come in such runs) starts from there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct LineForwardKinematics {
    kinematics: LineKinematics,
    /// The last configuration and its partial products (`frames[i]` after
    /// joint `i`); the first `valid` are current.
    q: [f64; MAX_JOINTS],
    frames: [Rows; MAX_JOINTS],
    valid: usize,
}

impl LineForwardKinematics {
    pub(crate) fn new(kinematics: LineKinematics) -> LineForwardKinematics {
        LineForwardKinematics {
            kinematics,
            q: [0.0; MAX_JOINTS],
            frames: [kinematics.first; MAX_JOINTS],
            valid: 0,
        }
    }

    /// Forgets the kept products.
    pub(crate) fn reset(&mut self) {
        self.valid = 0;
    }

    /// The end-effector pose at `q` (one value per joint, rad or m).
    pub(crate) fn pose(&mut self, q: &[f64]) -> Pose {
        let dof = self.kinematics.dof;
        // Joints equal (bit for bit) to the last configuration's keep their
        // products.
        let mut start = 0;
        while start < self.valid && q[start].to_bits() == self.q[start].to_bits() {
            start += 1;
        }
        let mut frame = if start == 0 {
            self.kinematics.first
        } else {
            self.frames[start - 1]
        };
        // The trigonometry first, in one loop of independent calls (slides
        // get a sine-cosine they do not use).
        let mut sin_cos = [(0.0, 1.0); MAX_JOINTS];
        sin_cos_slice(&q[start..dof], &mut sin_cos[start..dof]);
        for i in start..dof {
            frame = self.kinematics.step(&frame, i, q[i], sin_cos[i]);
            self.frames[i] = frame;
            self.q[i] = q[i];
        }
        self.valid = dof;
        pose_of(&frame)
    }
}
