//! Linear-algebra aliases and the rigid transform type used throughout armkit.
//!
//! Everything is `f64`, SI units (metres, radians, seconds). Twists and
//! Jacobian rows are ordered `[linear; angular]` = `[vx, vy, vz, wx, wy, wz]`.
//!
//! ```
//! use armkit::math::{Pose, Vector3};
//! let a = Pose::from_translation(Vector3::new(1.0, 0.0, 0.0));
//! let b = Pose::rot_z(std::f64::consts::FRAC_PI_2);
//! let c = a * b; // first translate, then rotate about the new z
//! assert!((c.transform_point(&Vector3::x()) - Vector3::new(1.0, 1.0, 0.0)).norm() < 1e-15);
//! let (roll, pitch, yaw) = c.rpy();
//! assert!((yaw - std::f64::consts::FRAC_PI_2).abs() < 1e-15 && roll.abs() < 1e-15 && pitch.abs() < 1e-15);
//! ```

use std::ops::Mul;

pub use nalgebra::{
    DMatrix, DVector, Matrix3, Matrix4, Matrix6, Matrix6xX, Rotation3, UnitQuaternion, Vector3,
    Vector6,
};

mod lanes;
#[cfg(target_arch = "x86_64")]
mod lanes_avx;
pub(crate) mod roots;
mod trig;
pub use lanes::{F64x4, Lane, Lanes4, LANES};
#[cfg(target_arch = "x86_64")]
pub(crate) use lanes_avx::Avx4;
pub use trig::{sin_cos, sin_cos_slice, sin_cos_slice_x4, sin_cos_x4, sin_cos_x4_fused};

/// A rigid transform `T = [R p; 0 1]`: rotation `R` (orthonormal 3 x 3) and
/// translation `p` (metres).
///
/// `a * b` composes as homogeneous matrices (`T_a T_b`); a point `x` given in
/// the transform's own frame maps to `R x + p` in the parent frame. This is
/// Pinocchio's `SE3`, kept as a plain matrix pair because composing rotation
/// matrices is the cheapest form for forward kinematics.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pose {
    /// Rotation matrix: columns are the frame's x, y, z axes in parent coordinates.
    pub rotation: Matrix3<f64>,
    /// Origin of the frame in parent coordinates, metres.
    pub translation: Vector3<f64>,
}

impl Default for Pose {
    fn default() -> Self {
        Self::identity()
    }
}

impl Pose {
    /// The identity transform.
    pub fn identity() -> Self {
        Pose {
            rotation: Matrix3::identity(),
            translation: Vector3::zeros(),
        }
    }

    /// A transform from a rotation matrix and a translation (metres). The
    /// rotation is taken as given: see [`Pose::from_matrix4`] for a checked form.
    pub fn new(rotation: Matrix3<f64>, translation: Vector3<f64>) -> Self {
        Pose {
            rotation,
            translation,
        }
    }

    /// A pure translation (metres).
    pub fn from_translation(translation: Vector3<f64>) -> Self {
        Pose {
            rotation: Matrix3::identity(),
            translation,
        }
    }

    /// A pure rotation.
    pub fn from_rotation(rotation: Matrix3<f64>) -> Self {
        Pose {
            rotation,
            translation: Vector3::zeros(),
        }
    }

    /// Rotation of `angle` radians about the x axis.
    pub fn rot_x(angle: f64) -> Self {
        let (s, c) = angle.sin_cos();
        Self::from_rotation(Matrix3::new(1.0, 0.0, 0.0, 0.0, c, -s, 0.0, s, c))
    }

    /// Rotation of `angle` radians about the y axis.
    pub fn rot_y(angle: f64) -> Self {
        let (s, c) = angle.sin_cos();
        Self::from_rotation(Matrix3::new(c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c))
    }

    /// Rotation of `angle` radians about the z axis.
    pub fn rot_z(angle: f64) -> Self {
        let (s, c) = angle.sin_cos();
        Self::from_rotation(Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0))
    }

    /// Translation of `distance` metres along x.
    pub fn trans_x(distance: f64) -> Self {
        Self::from_translation(Vector3::new(distance, 0.0, 0.0))
    }

    /// Translation of `distance` metres along z.
    pub fn trans_z(distance: f64) -> Self {
        Self::from_translation(Vector3::new(0.0, 0.0, distance))
    }

    /// Position and roll-pitch-yaw as URDF writes them:
    /// `R = Rz(yaw) Ry(pitch) Rx(roll)` (fixed axes x, then y, then z), radians.
    pub fn from_xyz_rpy(xyz: [f64; 3], rpy: [f64; 3]) -> Self {
        let rotation = Rotation3::from_euler_angles(rpy[0], rpy[1], rpy[2]).into_inner();
        Pose::new(rotation, Vector3::from(xyz))
    }

    /// Roll, pitch and yaw (radians) with `R = Rz(yaw) Ry(pitch) Rx(roll)`,
    /// pitch in `[-pi/2, pi/2]`; at pitch = +-pi/2 roll is set to zero.
    pub fn rpy(&self) -> (f64, f64, f64) {
        Rotation3::from_matrix_unchecked(self.rotation).euler_angles()
    }

    /// The 4 x 4 homogeneous matrix.
    pub fn to_matrix4(&self) -> Matrix4<f64> {
        let mut m = Matrix4::identity();
        m.fixed_view_mut::<3, 3>(0, 0).copy_from(&self.rotation);
        m.fixed_view_mut::<3, 1>(0, 3).copy_from(&self.translation);
        m
    }

    /// Rows of the 4 x 4 homogeneous matrix (row-major, as in the reference files).
    pub fn to_rows(&self) -> [[f64; 4]; 4] {
        let m = self.to_matrix4();
        let mut rows = [[0.0; 4]; 4];
        for (r, row) in rows.iter_mut().enumerate() {
            for (c, value) in row.iter_mut().enumerate() {
                *value = m[(r, c)];
            }
        }
        rows
    }

    /// A transform from a 4 x 4 homogeneous matrix, checked: finite entries,
    /// last row `[0 0 0 1]`, and a proper rotation (orthonormal to [`ROTATION_TOLERANCE`],
    /// determinant +1). The error string says which check failed.
    pub fn from_matrix4(m: &Matrix4<f64>) -> Result<Pose, String> {
        if m.iter().any(|v| !v.is_finite()) {
            return Err("has a non-finite entry".into());
        }
        let last = [m[(3, 0)], m[(3, 1)], m[(3, 2)], m[(3, 3)]];
        if last != [0.0, 0.0, 0.0, 1.0] {
            return Err(format!("last row must be [0, 0, 0, 1], got {last:?}"));
        }
        let rotation: Matrix3<f64> = m.fixed_view::<3, 3>(0, 0).into_owned();
        let orthonormality = rotation_orthonormality(&rotation);
        if orthonormality > ROTATION_TOLERANCE {
            return Err(format!(
                "rotation block is not orthonormal (|R'R - I| = {orthonormality:.3e})"
            ));
        }
        if rotation.determinant() < 0.0 {
            return Err("rotation block is a reflection (determinant -1)".into());
        }
        Ok(Pose::new(rotation, m.fixed_view::<3, 1>(0, 3).into_owned()))
    }

    /// A transform from the row-major rows of a 4 x 4 homogeneous matrix, checked
    /// as in [`Pose::from_matrix4`].
    pub fn from_rows(rows: &[[f64; 4]; 4]) -> Result<Pose, String> {
        Pose::from_matrix4(&Matrix4::from_fn(|r, c| rows[r][c]))
    }

    /// The inverse transform `T^-1 = [R' -R'p; 0 1]`.
    pub fn inverse(&self) -> Pose {
        let rt = self.rotation.transpose();
        Pose::new(rt, -(rt * self.translation))
    }

    /// Maps a point given in this frame to the parent frame: `R x + p`.
    pub fn transform_point(&self, point: &Vector3<f64>) -> Vector3<f64> {
        self.rotation * point + self.translation
    }

    /// Maps a free vector (direction) given in this frame to the parent frame: `R v`.
    pub fn transform_vector(&self, vector: &Vector3<f64>) -> Vector3<f64> {
        self.rotation * vector
    }

    /// True when every entry is finite.
    pub fn is_finite(&self) -> bool {
        self.rotation
            .iter()
            .chain(self.translation.iter())
            .all(|v| v.is_finite())
    }

    /// The one pose validation: every entry finite, and a proper rotation
    /// (`|R'R - I|` entries at most [`ROTATION_TOLERANCE`], determinant +1).
    /// The error string says which check failed.
    ///
    /// ```
    /// use armkit::math::{Matrix3, Pose, Vector3};
    /// assert!(Pose::identity().check_rigid().is_ok());
    /// let mirrored = Pose::new(-Matrix3::identity(), Vector3::zeros());
    /// assert!(mirrored.check_rigid().unwrap_err().contains("not a proper rotation"));
    /// ```
    pub fn check_rigid(&self) -> Result<(), String> {
        if !self.is_finite() {
            return Err("has a non-finite entry".into());
        }
        let orthonormality = rotation_orthonormality(&self.rotation);
        let determinant = self.rotation.determinant();
        if orthonormality > ROTATION_TOLERANCE || determinant < 0.0 {
            return Err(format!(
                "rotation is not a proper rotation matrix (|R'R - I| = {orthonormality:.3e}, det = {determinant:.3})"
            ));
        }
        Ok(())
    }
}

/// Largest entry of `|R'R - I|` accepted for a rotation matrix anywhere in
/// armkit (poses, targets, paths, transforms read from files).
/// Dimensionless.
pub const ROTATION_TOLERANCE: f64 = 1e-6;

/// `max |R'R - I|` (entrywise), 0 for an exact rotation.
pub fn rotation_orthonormality(rotation: &Matrix3<f64>) -> f64 {
    (rotation.transpose() * rotation - Matrix3::identity()).amax()
}

impl Mul for Pose {
    type Output = Pose;
    #[inline]
    fn mul(self, rhs: Pose) -> Pose {
        Pose::new(
            self.rotation * rhs.rotation,
            self.rotation * rhs.translation + self.translation,
        )
    }
}

impl Mul<&Pose> for &Pose {
    type Output = Pose;
    #[inline]
    fn mul(self, rhs: &Pose) -> Pose {
        *self * *rhs
    }
}

/// The rotation that takes the z axis onto the unit vector `axis` by the
/// shortest arc (identity for +z, a half turn about x for -z).
pub fn rotation_z_to(axis: &Vector3<f64>) -> Matrix3<f64> {
    let z = Vector3::z();
    if (axis - z).norm() < 1e-15 {
        return Matrix3::identity();
    }
    if (axis + z).norm() < 1e-15 {
        return Pose::rot_x(std::f64::consts::PI).rotation;
    }
    let unit = nalgebra::Unit::new_normalize(*axis);
    Rotation3::rotation_between(&z, &unit)
        .unwrap_or_else(Rotation3::identity)
        .into_inner()
}

/// The rotation vector `k phi` of a rotation matrix (its matrix logarithm):
/// unit axis `k` times the angle `phi` in `[0, pi]`, radians.
///
/// Accurate to about machine precision over the whole range: the angle comes
/// from `atan2(sin, cos)` (not `acos` of the trace, which loses half the
/// digits near 0 and pi) and near `phi = pi`, where the skew part vanishes,
/// the axis comes from the symmetric part `R + R' = 2 cos(phi) I + 2 (1 - cos(phi)) k k'`.
pub fn rotation_log(rotation: &Matrix3<f64>) -> Vector3<f64> {
    let r = rotation;
    // vee((R - R') / 2) = sin(phi) k.
    let v = Vector3::new(
        0.5 * (r[(2, 1)] - r[(1, 2)]),
        0.5 * (r[(0, 2)] - r[(2, 0)]),
        0.5 * (r[(1, 0)] - r[(0, 1)]),
    );
    let sin = v.norm();
    let cos = (0.5 * (r.trace() - 1.0)).clamp(-1.0, 1.0);
    let angle = sin.atan2(cos);
    if cos > -0.5 {
        // phi < 2 pi / 3: the skew part carries the axis with full accuracy.
        if sin > 0.0 {
            return v * (angle / sin);
        }
        return Vector3::zeros();
    }
    // Near pi: k k' = (S - cos I) / (1 - cos) with S the symmetric part; take
    // the column with the largest diagonal entry (the best-conditioned one).
    let one_minus_cos = 1.0 - cos;
    let mut best = 0;
    for i in 1..3 {
        if r[(i, i)] > r[(best, best)] {
            best = i;
        }
    }
    let mut axis = Vector3::zeros();
    for i in 0..3 {
        let symmetric = 0.5 * (r[(i, best)] + r[(best, i)]);
        let identity = if i == best { cos } else { 0.0 };
        axis[i] = (symmetric - identity) / one_minus_cos;
    }
    let norm = axis.norm();
    if norm == 0.0 {
        return Vector3::zeros();
    }
    axis /= norm;
    // The symmetric part fixes the axis up to its sign; the skew part (tiny
    // but non-zero unless phi = pi exactly) fixes the sign.
    if axis.dot(&v) < 0.0 {
        axis = -axis;
    }
    axis * angle
}

/// The angle (rad, in `[0, pi]`) of a rotation matrix: `atan2` of its skew
/// and symmetric parts, accurate near 0 and pi (unlike `acos` of the trace).
pub fn rotation_angle(rotation: &Matrix3<f64>) -> f64 {
    let r = rotation;
    let sin = 0.5
        * Vector3::new(
            r[(2, 1)] - r[(1, 2)],
            r[(0, 2)] - r[(2, 0)],
            r[(1, 0)] - r[(0, 1)],
        )
        .norm();
    sin.atan2(0.5 * (r.trace() - 1.0))
}

/// The skew-symmetric matrix `[v]x` with `[v]x w = v x w`.
pub fn skew(v: &Vector3<f64>) -> Matrix3<f64> {
    Matrix3::new(0.0, -v.z, v.y, v.z, 0.0, -v.x, -v.y, v.x, 0.0)
}

/// Wraps an angle to `(-pi, pi]`, radians.
pub fn wrap_angle(angle: f64) -> f64 {
    let two_pi = std::f64::consts::TAU;
    let wrapped = angle - two_pi * (angle / two_pi).round();
    if wrapped <= -std::f64::consts::PI {
        wrapped + two_pi
    } else {
        wrapped
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rpy_round_trip_matches_urdf_convention() {
        let (r, p, y) = (0.3, -0.7, 2.1);
        let pose = Pose::from_xyz_rpy([0.0; 3], [r, p, y]);
        let expected = Pose::rot_z(y) * Pose::rot_y(p) * Pose::rot_x(r);
        assert!((pose.rotation - expected.rotation).amax() < 1e-15);
        let (r2, p2, y2) = pose.rpy();
        assert!((r - r2).abs() < 1e-12 && (p - p2).abs() < 1e-12 && (y - y2).abs() < 1e-12);
    }

    #[test]
    fn inverse_composes_to_identity() {
        let t = Pose::from_xyz_rpy([0.1, -2.0, 3.0], [0.4, 0.2, -1.0]);
        let i = t * t.inverse();
        assert!((i.to_matrix4() - Matrix4::identity()).amax() < 1e-15);
    }

    #[test]
    fn from_matrix4_rejects_bad_matrices() {
        let mut m = Matrix4::identity();
        m[(3, 0)] = 1.0;
        assert!(Pose::from_matrix4(&m).unwrap_err().contains("last row"));
        let mut m = Matrix4::identity();
        m[(0, 0)] = 2.0;
        assert!(Pose::from_matrix4(&m).unwrap_err().contains("orthonormal"));
        let mut m = Matrix4::identity();
        m[(0, 0)] = -1.0;
        assert!(Pose::from_matrix4(&m).unwrap_err().contains("reflection"));
        let mut m = Matrix4::identity();
        m[(1, 3)] = f64::NAN;
        assert!(Pose::from_matrix4(&m).unwrap_err().contains("non-finite"));
    }

    #[test]
    fn rotation_z_to_maps_z_onto_axis() {
        for axis in [
            Vector3::z(),
            -Vector3::z(),
            Vector3::x(),
            Vector3::new(0.3, -0.4, 0.5).normalize(),
        ] {
            let r = rotation_z_to(&axis);
            assert!((r * Vector3::z() - axis).norm() < 1e-15);
            assert!((r.transpose() * r - Matrix3::identity()).amax() < 1e-15);
        }
    }

    #[test]
    fn wrap_angle_lands_in_half_open_interval() {
        use std::f64::consts::PI;
        assert!((wrap_angle(3.0 * PI) - PI).abs() < 1e-12);
        assert!((wrap_angle(-PI) - PI).abs() < 1e-12);
        assert!((wrap_angle(0.5 + 4.0 * PI) - 0.5).abs() < 1e-12);
    }
}
