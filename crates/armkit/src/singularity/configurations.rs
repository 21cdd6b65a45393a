//! Singular configurations of any arm: classification (wrist, elbow,
//! shoulder for 6R arms with a spherical wrist) and a search that finds them.
//!
//! For a 6R arm whose last three axes meet at a point `c` (the wrist
//! centre), the Jacobian referred to `c` is block triangular,
//! `[[J_c, 0], [Z_a, Z_w]]` with `J_c = [z_i x (c - o_i)]` (i = 1..3, the
//! velocity of `c`) and `Z_w = [z4 z5 z6]`, so `det J = det J_c det Z_w`
//! (moving the reference point does not change the determinant). When axes 2
//! and 3 are parallel (PUMA-type arms: PUMA 560, seed 004's space6r) `J_c`
//! factors further: the columns `u2, u3` lie in the plane normal to `z2`, so
//! `det J_c = (u2 x u3)·z2 · (c - o1)·(z2 x z1)`. Three geometric factors
//! thus make `det J`, each zero exactly on one kind of singularity:
//!
//! * wrist: `det[z4 z5 z6]` (axes 4 and 6 aligned, `q5 = 0` on a PUMA wrist);
//! * elbow: the sine of the angle between `u2` and `u3` (arm stretched or
//!   folded: `c`, axis 2 and axis 3 in one plane);
//! * shoulder: the sine of the angle between `c - o1` and the plane through
//!   axis 1 parallel to axis 2 (the wrist centre on axis 1; with a shoulder
//!   offset along axis 2, as on the PUMA and space6r, in that plane, i.e. on
//!   the line parallel to axis 1 at the offset).
//!
//! The UR family (axes 2, 3 and 4 parallel, axes 5 and 6 meeting at a point
//! `p`: UR3/5/10 and their e-series) has the same three kinds, with `p` in
//! the place of the wrist centre: `det J = s3 s5 a2 a3 (a2 c2 + a3 c23 +
//! d5 s234)`, wrist `s5 = 0` (`det[z4 z5 z6]`), elbow `s3 = 0` (the two long
//! links in line) and shoulder (`p` in the plane through axis 1 parallel to
//! axis 2). Other arms (redundant ones, 6R arms of other classes) get the
//! rank of `J` and [`SingularityKind::Unclassified`] when it is deficient.

use crate::error::{check_finite_vector, check_positive, Error, Result};
use crate::kinematics::{jacobian, Data, JacobianFrame};
use crate::math::{DMatrix, Matrix3, Vector3};
use crate::model::{JointKind, Model};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// The kind of a singular configuration.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SingularityKind {
    /// Wrist: axes 4 and 6 aligned (`det[z4 z5 z6] = 0`); the end effector
    /// loses one rotation, joints 4 and 6 spin against each other.
    Wrist,
    /// Elbow: the arm stretched or folded; the wrist centre loses the radial
    /// direction.
    Elbow,
    /// Shoulder: the wrist centre on axis 1 (or, with a shoulder offset, in
    /// the plane through axis 1 parallel to axis 2); it loses the direction
    /// normal to the arm's plane.
    Shoulder,
    /// The Jacobian is rank-deficient but the arm has no spherical wrist (or
    /// no factor is below the tolerance): no geometric name.
    Unclassified,
}

impl SingularityKind {
    /// `wrist`, `elbow`, `shoulder` or `unclassified`.
    pub fn as_str(&self) -> &'static str {
        match self {
            SingularityKind::Wrist => "wrist",
            SingularityKind::Elbow => "elbow",
            SingularityKind::Shoulder => "shoulder",
            SingularityKind::Unclassified => "unclassified",
        }
    }
}

/// Tolerance of the classification and of the search.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClassifyOptions {
    /// A singular value below `tolerance * sigma_max` counts as lost rank,
    /// and a geometric factor (dimensionless, in `[-1, 1]`) whose magnitude is
    /// below `tolerance` names its kind. > 0; default 1e-6.
    pub tolerance: f64,
}

impl Default for ClassifyOptions {
    fn default() -> Self {
        ClassifyOptions { tolerance: 1e-6 }
    }
}

impl ClassifyOptions {
    /// Checks the tolerance is finite and > 0.
    pub fn validate(&self) -> Result<()> {
        check_positive("tolerance", self.tolerance)
    }
}

/// The three geometric factors of a 6R spherical-wrist arm (see the module
/// documentation), each dimensionless, signed, in `[-1, 1]`, and zero on
/// its kind of singularity; the sign tells the side (on a PUMA wrist, that of
/// `q5`; elbow up or down; which side of axis 1 the wrist centre is on).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WristFactors {
    /// Wrist centre, world frame, m (for the UR family, the point where axes
    /// 5 and 6 meet).
    pub centre: Vector3<f64>,
    /// `det[z4 z5 z6]`: plus or minus the sine of the angle between axes 4
    /// and 6 on an orthogonal wrist.
    pub wrist: f64,
    /// Sine of the angle from the wrist centre's velocity due to joint 2 to
    /// that due to joint 3, about axis 2 (0 with the arm stretched or folded).
    pub elbow: f64,
    /// Sine of the angle between `c - o1` and the plane through axis 1
    /// parallel to axis 2, signed along `z2 x z1` (0 with the wrist centre on axis 1, or on the
    /// offset line).
    pub shoulder: f64,
}

/// What [`classify`] found at one configuration.
#[derive(Clone, Debug, PartialEq)]
pub struct Classification {
    /// Singular values of the world-frame Jacobian (6 x n, rows
    /// `[vx vy vz wx wy wz]`), largest first; `min(6, n)` of them, in the rows'
    /// mixed units (m/rad and rad/rad for a revolute arm).
    pub singular_values: Vec<f64>,
    /// Number of singular values above `tolerance * sigma_max`.
    pub rank: usize,
    /// The kinds found, in the order wrist, elbow, shoulder (several at
    /// once are possible); `[Unclassified]` when the rank is deficient and
    /// no factor names it; empty at a regular configuration.
    pub kinds: Vec<SingularityKind>,
    /// The factors, for a 6R arm with a spherical wrist and parallel axes 2
    /// and 3; `None` otherwise.
    pub factors: Option<WristFactors>,
}

impl Classification {
    /// True when the Jacobian lost rank (`rank < min(6, n)`) or a factor
    /// named a kind.
    pub fn is_singular(&self) -> bool {
        !self.kinds.is_empty()
    }
}

/// Lines closer than this (m) meet.
const AXIS_MEET_TOLERANCE: f64 = 1e-9;
/// Unit axes whose cross product is shorter than this are parallel.
const PARALLEL_TOLERANCE: f64 = 1e-9;

/// The wrist factors at the last forward kinematics of `data`, or `None` when
/// the arm is not a 6R arm with parallel axes 2 and 3 and either a spherical
/// wrist or the UR family's axes (see the module documentation).
fn wrist_factors(model: &Model, data: &Data) -> Option<WristFactors> {
    let revolute = model
        .joints()
        .iter()
        .all(|j| matches!(j.kind, JointKind::Revolute | JointKind::Continuous));
    // The factors read the joint frames as the six joints of `q`: a chain
    // with mimic joints has more frames than joints in `q`, so it is not one.
    if model.dof() != 6 || model.chain_joints().len() != 6 || !revolute {
        return None;
    }
    let frames = data.joint_frames();
    let axis = |i: usize| frames[i].rotation.column(2).into_owned();
    let origin = |i: usize| frames[i].translation;
    let (z1, z2, z3, z4, z5, z6) = (axis(0), axis(1), axis(2), axis(3), axis(4), axis(5));
    if z2.cross(&z3).norm() > PARALLEL_TOLERANCE {
        return None;
    }
    // Wrist centre: the closest point of axis 4 to axis 5 (never parallel
    // on a spherical wrist), then axes 4, 5 and 6 must all pass through it.
    let (o4, o5) = (origin(3), origin(4));
    let n = z4.cross(&z5);
    let n2 = n.norm_squared();
    if n2 < PARALLEL_TOLERANCE {
        return None;
    }
    let w = o5 - o4;
    let s = w.cross(&z5).dot(&n) / n2;
    let centre = o4 + z4 * s;
    let distance = |point: Vector3<f64>, i: usize| {
        let d = point - origin(i);
        (d - axis(i) * d.dot(&axis(i))).norm()
    };
    let wrist = Matrix3::from_columns(&[z4, z5, z6]).determinant();
    let (centre, elbow) = if (3..6).all(|i| distance(centre, i) <= AXIS_MEET_TOLERANCE) {
        let u2 = z2.cross(&(centre - origin(1)));
        let u3 = z3.cross(&(centre - origin(2)));
        (centre, signed_sine(&u2, &u3, &z2))
    } else {
        // The UR family: axes 2, 3 and 4 parallel, axes 5 and 6 meeting at
        // `p`. `det J = s3 s5 a2 a3 (a2 c2 + a3 c23 + d5 s234)` (Hawkins,
        // "Analytic inverse kinematics for the Universal Robots UR-5/UR-10
        // arms", 2013): wrist `s5` (axes 4 and 6 aligned, `det[z4 z5 z6]`),
        // elbow `s3` (the links between axes 2, 3 and 4 in line) and
        // shoulder: `p` in the plane through axis 1 parallel to axis 2.
        if z3.cross(&z4).norm() > PARALLEL_TOLERANCE {
            return None;
        }
        let n = z5.cross(&z6);
        let n2 = n.norm_squared();
        if n2 < PARALLEL_TOLERANCE {
            return None;
        }
        let (o5, o6) = (origin(4), origin(5));
        let p = o5 + z5 * ((o6 - o5).cross(&z6).dot(&n) / n2);
        if distance(p, 5) > AXIS_MEET_TOLERANCE {
            return None;
        }
        // In the plane normal to the parallel axes: joint 2 to 3, 3 to 4.
        let in_plane = |d: Vector3<f64>| d - z2 * d.dot(&z2);
        let link2 = in_plane(origin(2) - origin(1));
        let link3 = in_plane(origin(3) - origin(2));
        (p, signed_sine(&link2, &link3, &z2))
    };
    let normal = z2.cross(&z1);
    let radial = centre - origin(0);
    let shoulder = if normal.norm() < PARALLEL_TOLERANCE {
        // Axes 1 and 2 parallel: joint 1 cannot move c out of the arm's plane.
        0.0
    } else if radial.norm() == 0.0 {
        0.0
    } else {
        radial.dot(&normal) / (normal.norm() * radial.norm())
    };
    Some(WristFactors {
        centre,
        wrist,
        elbow,
        shoulder,
    })
}

/// `(a x b)·n / (|a| |b|)` for a unit `n`, 0 when `a` or `b` is zero.
fn signed_sine(a: &Vector3<f64>, b: &Vector3<f64>, n: &Vector3<f64>) -> f64 {
    let scale = a.norm() * b.norm();
    if scale == 0.0 {
        0.0
    } else {
        (a.cross(b).dot(n) / scale).clamp(-1.0, 1.0)
    }
}

/// Classifies the configuration `q` (rad or m) of `model`: singular values
/// and rank of the world-frame Jacobian, and, for a 6R arm with parallel
/// axes 2 and 3 and a spherical wrist or the UR family's axes, the wrist /
/// elbow / shoulder factors and the kinds they name (see the module
/// documentation). Allocates (SVD).
///
/// Errors: `q` of the wrong size or not finite, bad options.
///
/// ```
/// use armkit::singularity::{classify, ClassifyOptions, SingularityKind};
/// let puma = armkit::robots::puma560()?;
/// let mut data = armkit::Data::new(&puma);
/// // q5 = 0: axes 4 and 6 aligned.
/// let q = [0.3, 0.5, -0.4, 0.2, 0.0, 0.1];
/// let found = classify(&puma, &mut data, &q, &ClassifyOptions::default())?;
/// assert_eq!(found.kinds, vec![SingularityKind::Wrist]);
/// assert_eq!(found.rank, 5);
/// # Ok::<(), armkit::Error>(())
/// ```
pub fn classify(
    model: &Model,
    data: &mut Data,
    q: &[f64],
    options: &ClassifyOptions,
) -> Result<Classification> {
    options.validate()?;
    check_finite_vector("q", q, model.dof())?;
    let j = jacobian(model, data, q, JacobianFrame::World)?;
    let dense = DMatrix::from_column_slice(6, j.ncols(), j.as_slice());
    let mut singular_values: Vec<f64> = dense
        .svd(false, false)
        .singular_values
        .iter()
        .copied()
        .collect();
    singular_values.sort_by(|a, b| b.total_cmp(a));
    let largest = singular_values.first().copied().unwrap_or(0.0);
    let rank = singular_values
        .iter()
        .filter(|&&s| s > options.tolerance * largest)
        .count();
    let factors = wrist_factors(model, data);
    let mut kinds = Vec::new();
    if let Some(f) = &factors {
        for (factor, kind) in [
            (f.wrist, SingularityKind::Wrist),
            (f.elbow, SingularityKind::Elbow),
            (f.shoulder, SingularityKind::Shoulder),
        ] {
            if factor.abs() < options.tolerance {
                kinds.push(kind);
            }
        }
    }
    if kinds.is_empty() && rank < singular_values.len() {
        kinds.push(SingularityKind::Unclassified);
    }
    Ok(Classification {
        singular_values,
        rank,
        kinds,
        factors,
    })
}

/// What [`nearest_singularity`] drives to zero.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SearchTarget {
    /// Any singularity: the smallest singular value of `J` over the
    /// largest (any arm).
    Any,
    /// One kind (not [`SingularityKind::Unclassified`]): its factor (6R
    /// spherical-wrist arms only).
    Kind(SingularityKind),
}

/// Options of [`nearest_singularity`] and [`find_singularities`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SearchOptions {
    /// Converged when the target measure is below this, and the result is
    /// classified with it (> 0). Default 1e-8.
    pub tolerance: f64,
    /// Newton iterations, in `1..=`[`super::MAX_IK_ITERATIONS`]. Default 100.
    pub max_iterations: usize,
    /// Largest joint move per iteration, rad or m (> 0). Default 0.3.
    pub max_step: f64,
}

impl Default for SearchOptions {
    fn default() -> Self {
        SearchOptions {
            tolerance: 1e-8,
            max_iterations: 100,
            max_step: 0.3,
        }
    }
}

impl SearchOptions {
    /// Checks every field; the error names it.
    pub fn validate(&self) -> Result<()> {
        check_positive("tolerance", self.tolerance)?;
        check_positive("max_step", self.max_step)?;
        if !(1..=super::MAX_IK_ITERATIONS).contains(&self.max_iterations) {
            return Err(Error::invalid_argument(
                "max_iterations",
                format!(
                    "must be in 1..={}, got {}",
                    super::MAX_IK_ITERATIONS,
                    self.max_iterations
                ),
            ));
        }
        Ok(())
    }
}

/// Whether a search reached a singular configuration.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SearchStatus {
    /// The measure fell below the tolerance.
    Converged,
    /// It did not within the iterations (a joint limit in the way, or a
    /// flat measure); the best configuration is returned.
    NotConverged,
}

impl SearchStatus {
    /// `"converged"` or `"not_converged"`.
    pub fn as_str(&self) -> &'static str {
        match self {
            SearchStatus::Converged => "converged",
            SearchStatus::NotConverged => "not_converged",
        }
    }
}

impl std::fmt::Display for SearchStatus {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// A singular configuration found by [`nearest_singularity`].
#[derive(Clone, Debug, PartialEq)]
pub struct SingularConfiguration {
    /// Joint positions, rad or m, within the limits.
    pub q: Vec<f64>,
    /// The target measure there (dimensionless, signed: see [`WristFactors`]).
    pub measure: f64,
    /// Newton iterations used.
    pub iterations: usize,
    /// Converged or not.
    pub status: SearchStatus,
    /// Its classification (with the search tolerance, relaxed 100 times:
    /// the kinds of a converged search are always named).
    pub classification: Classification,
}

/// Finite-difference step of the measure's gradient, rad or m.
const GRADIENT_STEP: f64 = 1e-6;

fn target_measure(model: &Model, data: &mut Data, q: &[f64], target: SearchTarget) -> Result<f64> {
    let j = jacobian(model, data, q, JacobianFrame::World)?;
    match target {
        SearchTarget::Any => {
            let dense = DMatrix::from_column_slice(6, j.ncols(), j.as_slice());
            // A square Jacobian: signed by det J, so that the measure is
            // smooth through zero at a simple singularity.
            let sign = if j.ncols() == 6 && dense.determinant() < 0.0 {
                -1.0
            } else {
                1.0
            };
            let values = dense.svd(false, false).singular_values;
            let largest = values.max();
            Ok(if largest > 0.0 {
                sign * values.min() / largest
            } else {
                0.0
            })
        }
        SearchTarget::Kind(kind) => {
            let factors = wrist_factors(model, data).ok_or_else(|| {
                Error::invalid_argument(
                    "target",
                    format!(
                        "{} singularities are defined for 6R arms with parallel axes 2 and 3 and \
                         a spherical wrist or the UR family's axes; {} is not one (search \
                         SearchTarget::Any)",
                        kind.as_str(),
                        model.name()
                    ),
                )
            })?;
            match kind {
                SingularityKind::Wrist => Ok(factors.wrist),
                SingularityKind::Elbow => Ok(factors.elbow),
                SingularityKind::Shoulder => Ok(factors.shoulder),
                SingularityKind::Unclassified => Err(Error::invalid_argument(
                    "target",
                    "search SearchTarget::Any for unclassified singularities",
                )),
            }
        }
    }
}

/// The singular configuration of `target` nearest to `q0` (rad or m), found
/// by minimum-norm Newton steps on the target measure `f`
/// (`dq = -f grad f / |grad f|^2`, gradient by central differences, steps
/// limited to `max_step` and clamped into the joint limits). The measures
/// are signed (the factors of [`WristFactors`]; for `Any`, the ratio of the
/// smallest to the largest singular value, signed by `det J` when `J` is
/// square), so Newton converges quadratically through a simple zero.
///
/// Errors: `q0` of the wrong size, not finite or outside the limits; bad
/// options; a `Kind` target on an arm without a spherical wrist.
pub fn nearest_singularity(
    model: &Model,
    data: &mut Data,
    q0: &[f64],
    target: SearchTarget,
    options: &SearchOptions,
) -> Result<SingularConfiguration> {
    options.validate()?;
    model.check_joint_positions(q0)?;
    model.check_limits(q0)?;
    let n = model.dof();
    let mut q = q0.to_vec();
    let mut probe = q0.to_vec();
    let mut gradient = vec![0.0; n];
    let mut measure = target_measure(model, data, &q, target)?;
    let mut iterations = 0;
    while measure.abs() >= options.tolerance && iterations < options.max_iterations {
        iterations += 1;
        // A stencil narrower than the distance to zero: the unsigned
        // measure of a non-square Jacobian has a kink there.
        let delta = GRADIENT_STEP.min(0.1 * measure.abs()).max(1e-12);
        for i in 0..n {
            probe.copy_from_slice(&q);
            probe[i] = q[i] + delta;
            let plus = target_measure(model, data, &probe, target)?;
            probe[i] = q[i] - delta;
            let minus = target_measure(model, data, &probe, target)?;
            gradient[i] = (plus - minus) / (2.0 * delta);
        }
        let g2: f64 = gradient.iter().map(|g| g * g).sum();
        if g2.is_nan() || g2 <= 0.0 {
            break;
        }
        let scale = measure / g2;
        let length = scale.abs() * g2.sqrt();
        let limited = if length > options.max_step {
            scale * options.max_step / length
        } else {
            scale
        };
        for ((qi, g), joint) in q.iter_mut().zip(&gradient).zip(model.joints()) {
            *qi = (*qi - limited * g).clamp(joint.limits.lower, joint.limits.upper);
        }
        measure = target_measure(model, data, &q, target)?;
    }
    let status = if measure.abs() < options.tolerance {
        SearchStatus::Converged
    } else {
        SearchStatus::NotConverged
    };
    let classification = classify(
        model,
        data,
        &q,
        &ClassifyOptions {
            tolerance: 100.0 * options.tolerance,
        },
    )?;
    Ok(SingularConfiguration {
        q,
        measure,
        iterations,
        status,
        classification,
    })
}

/// Singular configurations of `model` from `samples` random starts (uniform
/// within the limits, unbounded joints in `[-pi, pi]`, fixed `seed`), each
/// driven to the nearest singularity of `target`; only converged searches
/// are returned, in start order. Deterministic for a given seed.
///
/// Errors: those of [`nearest_singularity`].
pub fn find_singularities(
    model: &Model,
    target: SearchTarget,
    samples: usize,
    seed: u64,
    options: &SearchOptions,
) -> Result<Vec<SingularConfiguration>> {
    options.validate()?;
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut data = Data::new(model);
    let mut found = Vec::new();
    for _ in 0..samples {
        let q0: Vec<f64> = model
            .joints()
            .iter()
            .map(|j| {
                let lower = if j.limits.lower.is_finite() {
                    j.limits.lower
                } else {
                    -std::f64::consts::PI
                };
                let upper = if j.limits.upper.is_finite() {
                    j.limits.upper
                } else {
                    std::f64::consts::PI
                };
                if upper > lower {
                    rng.gen_range(lower..=upper)
                } else {
                    lower
                }
            })
            .collect();
        let result = nearest_singularity(model, &mut data, &q0, target, options)?;
        if result.status == SearchStatus::Converged {
            found.push(result);
        }
    }
    Ok(found)
}
