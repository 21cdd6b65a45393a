//! Random configurations and the benchmark protocol's targets.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use crate::error::{Error, Result};
use crate::kinematics::{forward_kinematics, Data};
use crate::math::Pose;
use crate::model::{Joint, JointKind, Model};

/// One joint position drawn uniformly within the joint's limits; a
/// rotational joint without finite limits in `[-pi, pi]`, a prismatic one
/// without them within 1 m of `around`.
pub(crate) fn sample_joint(joint: &Joint, around: f64, rng: &mut impl Rng) -> f64 {
    use std::f64::consts::PI;
    let limits = &joint.limits;
    let (lo, hi) = if limits.is_bounded() {
        (limits.lower, limits.upper)
    } else if joint.kind.is_rotational() {
        (
            (-PI).clamp(limits.lower, limits.upper),
            PI.clamp(limits.lower, limits.upper),
        )
    } else {
        (
            (around - 1.0).clamp(limits.lower, limits.upper),
            (around + 1.0).clamp(limits.lower, limits.upper),
        )
    };
    let value = if hi > lo { rng.gen_range(lo..=hi) } else { lo };
    if joint.kind == JointKind::Continuous {
        crate::math::wrap_angle(value)
    } else {
        value
    }
}

/// A configuration drawn uniformly within `model`'s limits (rad or m; see
/// [`benchmark_targets`] for joints without finite limits).
pub fn random_configuration(model: &Model, rng: &mut impl Rng) -> Vec<f64> {
    model
        .joints()
        .iter()
        .map(|joint| sample_joint(joint, joint.limits.midpoint(), rng))
        .collect()
}

/// The IK benchmark's targets (TRAC-IK's protocol): `count` configurations
/// drawn uniformly within the joint limits by a ChaCha8 generator seeded
/// with `seed` (rotational joints without finite limits in `[-pi, pi]`,
/// prismatic ones within 1 m of mid-range), each with its end-effector pose
/// (world frame). Every target is reachable by construction. Solves start
/// from [`Model::neutral_configuration`] (mid-range).
pub fn benchmark_targets(model: &Model, count: usize, seed: u64) -> Result<Vec<(Vec<f64>, Pose)>> {
    if count == 0 {
        return Err(Error::invalid_argument("count", "must be >= 1"));
    }
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut data = Data::new(model);
    (0..count)
        .map(|_| {
            let q = random_configuration(model, &mut rng);
            let pose = *forward_kinematics(model, &mut data, &q)?;
            Ok((q, pose))
        })
        .collect()
}
