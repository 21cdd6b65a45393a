//! Pieper's solution for 6R arms with a spherical wrist, PUMA layout.
//!
//! The structure (standard DH, row j = link j): `alpha1 = +-90 deg` (a
//! vertical first axis turning a horizontal shoulder axis), `alpha2 = 0`
//! (shoulder and elbow axes parallel), `alpha3 = +-90 deg`, and a spherical
//! wrist: `a4 = a5 = d5 = 0`, `alpha4, alpha5 = +-90 deg`, so that axes 4, 5
//! and 6 meet at the wrist centre, the origin of DH frames 4 and 5. Any
//! `d1, a1, d2` (shoulder offset), `a2 != 0`, `d3, a3, d4`, `d6, a6, alpha6`,
//! base and tool transforms, joint offsets and constant thetas are allowed.
//!
//! With `T = base A1 ... A6 tool`, the chain target
//! `Tc = base^-1 T (Tz(d6) Tx(a6) Rx(alpha6) tool)^-1 = A1 ... A5 Rz(theta6)`
//! has its origin at the wrist centre `p`, which depends on theta1..theta3 only:
//! * theta1 (2 branches, shoulder left/right): in frame 1 the wrist centre
//!   lies at the constant height `d2 + d3` above the plane of the arm,
//!   `-sin(alpha1) (py cos(theta1) - px sin(theta1)) = d2 + d3`.
//! * theta3 (2 branches, elbow up/down): in frame 1 the wrist centre is
//!   `Rz(theta2) [(a2, 0) + Rz(theta3) (a3, -sin(alpha3) d4)]`, a planar 2R
//!   arm; the law of cosines gives theta3, then theta2 by `atan2`.
//! * theta4, theta5, theta6 (2 branches, wrist flip): from
//!   `R36 = R03' Rc = Rz(theta4) Rx(alpha4) Rz(theta5) Rx(alpha5) Rz(theta6)`,
//!   whose third column is `(c4 s5 s_a5, s4 s5 s_a5, -s_a4 s_a5 c5)`.
//!
//! At a wrist singularity (`sin(theta5) = 0`) theta4 and theta6 are not
//! unique: theta4 is kept at its current value and the flip branch merges.

use super::{
    angle_is, check_arguments, dh_angle, finish, joint_value, quarter_turn_sign, rot_x_quarter,
    solve_cos_sin, standard_dh_table, ClosedFormSolution, RangeFilter,
};
use crate::error::{Error, Result};
use crate::math::{Matrix3, Pose, Vector3};
use crate::model::{DhLink, Model};

/// Closed-form IK of a PUMA-type 6R arm with a spherical wrist (see the
/// module documentation for the structure it accepts): up to 8 solutions.
#[derive(Clone, Debug)]
pub struct SphericalWristSolver {
    model: Model,
    links: Vec<DhLink>,
    /// `base^-1`.
    base_inverse: Pose,
    /// `(Tz(d6) Tx(a6) Rx(alpha6) tool)^-1`.
    end_inverse: Pose,
    /// sin(alpha) of links 1, 3, 4, 5 (each +-1).
    sign1: f64,
    sign3: f64,
    sign4: f64,
    sign5: f64,
}

impl SphericalWristSolver {
    /// Reads `model`'s DH table; the error names the first parameter that
    /// does not fit the structure.
    pub fn new(model: &Model) -> Result<SphericalWristSolver> {
        let links = standard_dh_table(model, 6)?;
        let not_fit = |why: String| Error::invalid_argument("model", why);
        let sign = |j: usize| {
            quarter_turn_sign(links[j].alpha)
                .ok_or_else(|| not_fit(format!("alpha{} is not +-90 deg", j + 1)))
        };
        let sign1 = sign(0)?;
        if !angle_is(links[1].alpha, 0.0) {
            return Err(not_fit(
                "alpha2 is not 0 (shoulder and elbow axes not parallel)".into(),
            ));
        }
        let sign3 = sign(2)?;
        let sign4 = sign(3)?;
        let sign5 = sign(4)?;
        for (value, name) in [(links[3].a, "a4"), (links[4].a, "a5"), (links[4].d, "d5")] {
            if value.abs() > 1e-12 {
                return Err(not_fit(format!(
                    "{name} = {value} is not 0 (the wrist axes do not meet in a point)"
                )));
            }
        }
        if links[1].a.abs() < 1e-9 {
            return Err(not_fit("a2 is 0 (no upper arm)".into()));
        }
        let last = &links[5];
        let end =
            Pose::trans_z(last.d) * Pose::trans_x(last.a) * Pose::rot_x(last.alpha) * *model.tool();
        Ok(SphericalWristSolver {
            model: model.clone(),
            base_inverse: model.base().inverse(),
            end_inverse: end.inverse(),
            links,
            sign1,
            sign3,
            sign4,
            sign5,
        })
    }

    /// Every solution within the joint limits, nearest `current` first.
    pub fn solve(&self, target: &Pose, current: &[f64]) -> Result<Vec<ClosedFormSolution>> {
        self.solve_with(target, current, RangeFilter::WithinLimits)
    }

    /// Every solution (up to 8), filtered by `filter`, nearest `current` first.
    ///
    /// `target`: end-effector pose in the world frame; `current`: joint
    /// positions (rad), used for the nearest ordering, for the 2 pi multiple
    /// of each angle, and for theta4 at a wrist singularity.
    pub fn solve_with(
        &self,
        target: &Pose,
        current: &[f64],
        filter: RangeFilter,
    ) -> Result<Vec<ClosedFormSolution>> {
        check_arguments(&self.model, target, current)?;
        let chain = self.base_inverse * *target * self.end_inverse;
        let l = &self.links;
        let p = chain.translation;
        let mut candidates = Vec::with_capacity(8);
        // theta1: -sin(alpha1) (py c1 - px s1) = d2 + d3 (the constant
        // height of the wrist centre over the arm's plane, seen in frame 1).
        let height = l[1].d + l[2].d;
        let theta1s = if p.x.hypot(p.y) < 1e-12 {
            // Wrist centre on axis 1: any theta1 works; keep the current one.
            vec![dh_angle(&l[0], current[0])]
        } else {
            solve_cos_sin(p.y, -p.x, -self.sign1 * height)
        };
        for theta1 in theta1s {
            let a1 = link_transform(&l[0], theta1);
            let p1 = a1.inverse().transform_point(&p);
            // Planar 2R in frame 1: p1 = Rz(t2) [(a2, 0) + Rz(t3) v3].
            let (a2, v3x, v3y) = (l[1].a, l[2].a, -self.sign3 * l[3].d);
            let reach2 = p1.x * p1.x + p1.y * p1.y;
            let k = (reach2 - a2 * a2 - v3x * v3x - v3y * v3y) / (2.0 * a2);
            for theta3 in solve_cos_sin(v3x, -v3y, k) {
                let (s3, c3) = theta3.sin_cos();
                let wx = a2 + c3 * v3x - s3 * v3y;
                let wy = s3 * v3x + c3 * v3y;
                let theta2 = p1.y.atan2(p1.x) - wy.atan2(wx);
                let r03 =
                    (a1 * link_transform(&l[1], theta2) * link_transform(&l[2], theta3)).rotation;
                let r36 = r03.transpose() * chain.rotation;
                for (theta4, theta5, theta6) in self.wrist(&r36, dh_angle(&l[3], current[3])) {
                    candidates.push(
                        [theta1, theta2, theta3, theta4, theta5, theta6]
                            .iter()
                            .zip(l.iter())
                            .map(|(t, link)| joint_value(link, *t))
                            .collect(),
                    );
                }
            }
        }
        finish(&self.model, &candidates, target, current, filter)
    }

    /// The (up to two) wrist solutions of
    /// `R36 = Rz(t4) Rx(alpha4) Rz(t5) Rx(alpha5) Rz(t6)`.
    fn wrist(&self, r36: &Matrix3<f64>, current_theta4: f64) -> Vec<(f64, f64, f64)> {
        let z = Vector3::new(r36[(0, 2)], r36[(1, 2)], r36[(2, 2)]);
        let (s4a, s5a) = (self.sign4, self.sign5);
        let cos5 = -s4a * s5a * z.z;
        let rho = z.x.hypot(z.y);
        let mut out = Vec::with_capacity(2);
        let branches: &[f64] = if rho < 1e-12 { &[0.0] } else { &[1.0, -1.0] };
        for &branch in branches {
            let sin5 = branch * rho;
            let theta5 = sin5.atan2(cos5);
            let theta4 = if rho < 1e-12 {
                current_theta4
            } else {
                // (c4, s4) s5 s_a5 = (zx, zy).
                let scale = branch * s5a;
                (scale * z.y).atan2(scale * z.x)
            };
            let r = rot_z(theta4) * rot_x_quarter(s4a) * rot_z(theta5) * rot_x_quarter(s5a);
            let m = r.transpose() * r36;
            let theta6 = m[(1, 0)].atan2(m[(0, 0)]);
            out.push((theta4, theta5, theta6));
        }
        out
    }
}

/// The standard DH transform of `link` at DH angle `theta`:
/// `Rz(theta) Tz(d) Tx(a) Rx(alpha)`.
fn link_transform(link: &DhLink, theta: f64) -> Pose {
    Pose::rot_z(theta) * Pose::trans_z(link.d) * Pose::trans_x(link.a) * Pose::rot_x(link.alpha)
}

fn rot_z(theta: f64) -> Matrix3<f64> {
    Pose::rot_z(theta).rotation
}
