//! Random vectors for the analytic solvers' unit tests (one definition for
//! every test module here).

use crate::math::Vector3;
use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// A random unit vector, roughly uniform in direction (rejection from the
/// unit ball, away from its centre so that normalising is well conditioned).
pub(crate) fn unit(rng: &mut ChaCha8Rng) -> Vector3<f64> {
    loop {
        let v = Vector3::new(
            rng.gen_range(-1.0..1.0),
            rng.gen_range(-1.0..1.0),
            rng.gen_range(-1.0..1.0),
        );
        if v.norm() > 0.2 && v.norm() < 1.0 {
            return v.normalize();
        }
    }
}

/// A random vector of length 0.1 to 2 (m or unitless).
pub(crate) fn vector(rng: &mut ChaCha8Rng) -> Vector3<f64> {
    unit(rng) * rng.gen_range(0.1..2.0)
}

/// A random point in the cube of side 1 centred at the origin, m.
pub(crate) fn point(rng: &mut ChaCha8Rng) -> Vector3<f64> {
    Vector3::new(
        rng.gen_range(-0.5..0.5),
        rng.gen_range(-0.5..0.5),
        rng.gen_range(-0.5..0.5),
    )
}
