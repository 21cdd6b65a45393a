//! Seed 002's inverse kinematics as the paper writes it (sec 2.2, eqs
//! 10-18): theta2 from the wrist's distance to axis 1 (eqs 10-11),
//! theta12 = theta1 + theta2 solved as one angle (eqs 13-16), theta1 =
//! theta12 - theta2, then theta3 and theta4 from the tool's approach and
//! orientation vectors turned back by theta12 (eqs 17-18). Each of eqs 11,
//! 15, 17 and 18 takes a square root with either sign: 16 candidates, of
//! which the ones that do not reproduce the pose are the paper's
//! extraneous roots ("增根", from the square roots).
//!
//! In DH angles (`theta = q + offset`) the paper's equations hold as
//! printed for the structure of [`Arm4Solver`] with `a2 = 0`: the wrist
//! point is `w = Rz(theta1) (a1, 0) + Rz(theta12) (0, b)` with
//! `b = -sin(alpha2) d3` (the paper's `-d3`), so
//! `|w|^2 = a1^2 + b^2 - 2 a1 b s2` (eq 10, `s2` as printed) and
//! `c12 w_y - s12 w_x = b - a1 s2` (eqs 13-14).

use super::Arm4Solver;
use crate::error::{Error, Result};
use crate::math::Pose;

impl Arm4Solver {
    /// The 16 candidates of seed 002's closed form (eqs 10-18) for
    /// `target` (end-effector pose, world frame), as joint positions (rad),
    /// one per choice of sign in eqs 11, 15, 17 and 18 (in that bit order:
    /// bit 0 eq 11's, bit 1 eq 15's, bit 2 eq 17's, bit 3 eq 18's); a choice
    /// whose square root is of a negative number (the wrist out of reach)
    /// is left out. No range filter and no check: which candidates
    /// reproduce `target` is for the caller to test (by forward kinematics).
    ///
    /// Errors: a model whose link 2 has `a2 != 0` (the paper's eqs 8-9
    /// have no such term).
    pub fn paper_candidates(&self, target: &Pose) -> Result<Vec<Vec<f64>>> {
        let l = &self.links;
        if l[1].a.abs() > 1e-12 {
            return Err(Error::invalid_argument(
                "model",
                format!(
                    "a2 = {}: seed 002's eqs 8-18 assume link 2 lies along axis 3 (a2 = 0)",
                    l[1].a
                ),
            ));
        }
        let chain = self.base_inverse * *target * self.tool_chain_inverse;
        let (w, r) = (chain.translation, chain.rotation);
        let (a1, b) = (l[0].a, -self.sign2 * l[2].d);
        // Eq 10: s2 from the wrist's distance to axis 1.
        let s2 = (a1 * a1 + b * b - (w.x * w.x + w.y * w.y)) / (2.0 * a1 * b);
        let rho2 = w.x * w.x + w.y * w.y;
        let phi = w.y.atan2(w.x);
        let root = |x: f64| (x >= -1e-12).then(|| x.max(0.0).sqrt());
        let mut candidates = Vec::with_capacity(16);
        for signs in 0..16u32 {
            let sign = |bit: u32| if signs & (1 << bit) == 0 { 1.0 } else { -1.0 };
            // Eq 11: theta2 = atan2(s2, +-sqrt(1 - s2^2)).
            let Some(c2) = root(1.0 - s2 * s2) else {
                continue;
            };
            let theta2 = s2.atan2(sign(0) * c2);
            // Eqs 14-16: sin(phi - theta12) = (b - a1 s2) / rho.
            let e = b - a1 * theta2.sin();
            let Some(c) = root(rho2 - e * e) else {
                continue;
            };
            let theta12 = phi - e.atan2(sign(1) * c);
            let theta1 = theta12 - theta2;
            let (s12, c12) = theta12.sin_cos();
            // Eq 17: s3 = c12 a_x + s12 a_y (the approach vector turned back
            // by theta12), theta3 = atan2(s3, +-c3).
            let s3 = self.sign3 * (c12 * r[(0, 2)] + s12 * r[(1, 2)]);
            let Some(c3) = root(1.0 - s3 * s3) else {
                continue;
            };
            let theta3 = s3.atan2(sign(2) * c3);
            // Eq 18: c4 = s12 o_x - c12 o_y, theta4 = atan2(+-s4, c4).
            let c4 = self.sign3 * self.sign2 * (s12 * r[(0, 1)] - c12 * r[(1, 1)]);
            let Some(s4) = root(1.0 - c4 * c4) else {
                continue;
            };
            let theta4 = (sign(3) * s4).atan2(c4);
            candidates.push(self.joint_values([theta1, theta2, theta3, theta4]));
        }
        Ok(candidates)
    }

    /// Joint positions (rad) of the DH angles `thetas` (rad): `q = theta -
    /// offset`, the angles seed 002's equations (eqs 7-18) are written in.
    pub fn joints_from_dh_angles(&self, thetas: [f64; 4]) -> Vec<f64> {
        self.joint_values(thetas)
    }

    /// Link 2's length `d3` (m, the paper's `d3` in eqs 8-9).
    pub fn link2_length(&self) -> f64 {
        self.links[2].d
    }
}
