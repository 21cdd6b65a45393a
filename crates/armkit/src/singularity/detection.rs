//! Detection of the singular region along a path (seed 004, sec 2.3.1).

use crate::error::{check_positive, Error, Result};
use crate::math::{Matrix6, Matrix6xX};

/// The determinant measure of a 6 x n Jacobian: `|det J|` when it is square
/// (n = 6), Yoshikawa's manipulability `sqrt(det(J J'))` otherwise
/// (`sqrt(det(J' J))` when n < 6), i.e. the product of the singular values in
/// every case.
///
/// Units: the product of the row units over the rank: m^3 for a 6R arm's
/// `[v; w]` Jacobian (three rows in m/rad, three in rad/rad). Zero at a
/// singularity. Computed on the stack; allocates nothing.
pub fn jacobian_determinant(jacobian: &Matrix6xX<f64>) -> f64 {
    let n = jacobian.ncols();
    if n == 6 {
        return Matrix6::from_column_slice(jacobian.as_slice())
            .determinant()
            .abs();
    }
    if n > 6 {
        return crate::linalg::manipulability(jacobian);
    }
    let mut gram = Matrix6::zeros();
    for r in 0..6 {
        for c in 0..6 {
            gram[(r, c)] = if r < n && c < n {
                jacobian.column(r).dot(&jacobian.column(c))
            } else if r == c {
                1.0
            } else {
                0.0
            };
        }
    }
    gram.determinant().max(0.0).sqrt()
}

/// True when `determinant` is below `threshold` or is NaN (an unusable
/// Jacobian counts as singular).
pub(crate) fn below_threshold(determinant: f64, threshold: f64) -> bool {
    determinant < threshold || determinant.is_nan()
}

/// The two tests that declare the motion singular (seed 004, sec 2.3.1).
///
/// The paper enters the singular region when the joint angles jump (a joint
/// step larger than `eps_dq`) and derives from that point the threshold on
/// `|det J|` below which the Jacobian is treated as singular. Either test
/// triggers here.
///
/// Defaults, for space6r with `dt` = 0.01 s (see the module documentation
/// of [`super`] for their derivation and the paper's `eps_dq = 5`):
///
/// * `determinant_threshold` 0.004 m^3: on seed 004's path as rebuilt by
///   [`super::seed004_path`] (straight through the wrist singularity at
///   10 s), `|det J|` of plain tracking falls below it at 8.86 s and the
///   avoidance's region ends at 11.43 s, the paper's 8.8 s to 11.2 s. The
///   paper's own rule ([`super::calibrate_determinant_threshold`] on the
///   plain run) gives only 1.6e-4 m^3 (9.96 s to 10.04 s) on this path,
///   because plain tracking through the exact singularity jumps only in
///   the last 0.05 s before it. [`crate::study::AvoidanceStudy`] (the demo,
///   `armkit singularity`) uses the paper's rule by default and runs this
///   fitted value beside it as a labelled comparison.
/// * `joint_step_threshold` 0.005 rad per control period: space6r's joint
///   speed limit, 0.5 rad/s, over 0.01 s.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "io", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "io", serde(deny_unknown_fields))]
pub struct DetectionOptions {
    /// `eps_det`: the motion is singular where `|det J| <`
    /// this ([`jacobian_determinant`]; m^3 for a 6R arm), > 0.
    pub determinant_threshold: f64,
    /// `eps_dq`: the motion is singular where the velocity-level solution
    /// would move some joint by more than this in one control period (rad or
    /// m), > 0.
    pub joint_step_threshold: f64,
}

impl Default for DetectionOptions {
    fn default() -> Self {
        DetectionOptions {
            determinant_threshold: 0.004,
            joint_step_threshold: 0.005,
        }
    }
}

impl DetectionOptions {
    /// Checks both thresholds are finite and > 0.
    pub fn validate(&self) -> Result<()> {
        check_positive("determinant_threshold", self.determinant_threshold)?;
        check_positive("joint_step_threshold", self.joint_step_threshold)
    }
}

/// Which test found the motion singular.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Trigger {
    /// `|det J|` below the threshold only.
    Determinant,
    /// The velocity-level joint step above `eps_dq` only.
    JointStep,
    /// Both.
    Both,
}

impl Trigger {
    /// `determinant`, `joint_step` or `both`.
    pub fn as_str(&self) -> &'static str {
        match self {
            Trigger::Determinant => "determinant",
            Trigger::JointStep => "joint_step",
            Trigger::Both => "both",
        }
    }
}

/// The outcome of one detection check.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Detection {
    /// `|det J|` ([`jacobian_determinant`]).
    pub determinant: f64,
    /// Largest joint displacement of the candidate step, rad or m.
    pub joint_step: f64,
    /// `None` when the motion is regular.
    pub trigger: Option<Trigger>,
}

impl Detection {
    /// True when a test triggered.
    pub fn is_singular(&self) -> bool {
        self.trigger.is_some()
    }
}

/// One detection check: the Jacobian at the current state and the joint
/// displacement `candidate_step` (rad or m, one per joint) the plain
/// velocity-level solution would make over the next control period
/// (`h J^-1 x_dot`). Allocates nothing.
///
/// Errors: a step of the wrong size, non-finite values.
pub fn detect(
    jacobian: &Matrix6xX<f64>,
    candidate_step: &[f64],
    options: &DetectionOptions,
) -> Result<Detection> {
    if candidate_step.len() != jacobian.ncols() {
        return Err(Error::DimensionMismatch {
            what: "candidate_step",
            expected: jacobian.ncols(),
            got: candidate_step.len(),
        });
    }
    // A non-finite step (an exactly singular inverse) is a jump.
    let joint_step = candidate_step
        .iter()
        .map(|v| {
            if v.is_finite() {
                v.abs()
            } else {
                f64::INFINITY
            }
        })
        .fold(0.0, f64::max);
    let determinant = jacobian_determinant(jacobian);
    let low = below_threshold(determinant, options.determinant_threshold);
    let jump = joint_step > options.joint_step_threshold;
    let trigger = match (low, jump) {
        (true, true) => Some(Trigger::Both),
        (true, false) => Some(Trigger::Determinant),
        (false, true) => Some(Trigger::JointStep),
        (false, false) => None,
    };
    Ok(Detection {
        determinant,
        joint_step,
        trigger,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 6 x 6 Jacobian whose determinant is `det` (diagonal `[det, 1, ...]`
    /// turned by a fixed rotation of the rows, so no entry is special).
    fn jacobian_with_determinant(det: f64) -> Matrix6xX<f64> {
        let mut d = Matrix6::identity();
        d[(0, 0)] = det;
        let (c, s) = (0.6, 0.8);
        let mut turn = Matrix6::identity();
        turn[(0, 0)] = c;
        turn[(0, 3)] = -s;
        turn[(3, 0)] = s;
        turn[(3, 3)] = c;
        Matrix6xX::from_column_slice((turn * d).as_slice())
    }

    const OPTIONS: DetectionOptions = DetectionOptions {
        determinant_threshold: 0.004,
        joint_step_threshold: 0.005,
    };

    /// A step of one joint by `step` (rad), the others still.
    fn step(joint: usize, step: f64) -> [f64; 6] {
        let mut out = [0.0; 6];
        out[joint] = step;
        out
    }

    /// A jump of either sign triggers the joint-step test, and the step
    /// reported is its magnitude; a step within the threshold of either
    /// sign does not.
    #[test]
    fn jumps_of_either_sign_trigger_the_joint_step_test() {
        let regular = jacobian_with_determinant(1.0);
        for joint in 0..6 {
            for sign in [1.0, -1.0] {
                let jump = detect(&regular, &step(joint, sign * 0.0051), &OPTIONS).unwrap();
                assert_eq!(
                    jump.trigger,
                    Some(Trigger::JointStep),
                    "joint {joint}, sign {sign}"
                );
                assert!((jump.joint_step - 0.0051).abs() < 1e-15, "{jump:?}");
                assert!(jump.is_singular());
                let small = detect(&regular, &step(joint, sign * 0.0049), &OPTIONS).unwrap();
                assert_eq!(small.trigger, None, "joint {joint}, sign {sign}");
                assert!((small.joint_step - 0.0049).abs() < 1e-15, "{small:?}");
                assert!(!small.is_singular());
            }
        }
        // The largest magnitude counts, whatever the signs of the others.
        let mixed = detect(
            &regular,
            &[0.004, -0.009, 0.001, -0.002, 0.0, 0.003],
            &OPTIONS,
        )
        .unwrap();
        assert_eq!(mixed.trigger, Some(Trigger::JointStep));
        assert!((mixed.joint_step - 0.009).abs() < 1e-15);
    }

    /// Each trigger on its own and both together; a non-finite step is a
    /// jump; a NaN Jacobian is singular.
    #[test]
    fn each_trigger_and_both() {
        let regular = jacobian_with_determinant(0.5);
        let low = jacobian_with_determinant(-0.003);
        let still = [0.0; 6];
        let cases = [
            (&regular, step(2, 0.001), None),
            (&regular, step(2, -0.01), Some(Trigger::JointStep)),
            (&low, step(2, 0.001), Some(Trigger::Determinant)),
            (&low, still, Some(Trigger::Determinant)),
            (&low, step(4, -0.01), Some(Trigger::Both)),
            (&low, step(4, 0.01), Some(Trigger::Both)),
        ];
        for (jacobian, candidate, expected) in cases {
            let detection = detect(jacobian, &candidate, &OPTIONS).unwrap();
            assert_eq!(detection.trigger, expected, "{candidate:?}: {detection:?}");
        }
        // |det J| is reported, whatever its sign.
        let d = detect(&low, &still, &OPTIONS).unwrap().determinant;
        assert!((d - 0.003).abs() < 1e-15, "{d}");
        let d = detect(&regular, &still, &OPTIONS).unwrap().determinant;
        assert!((d - 0.5).abs() < 1e-15, "{d}");
        for value in [f64::INFINITY, f64::NEG_INFINITY, f64::NAN] {
            let detection = detect(&regular, &step(1, value), &OPTIONS).unwrap();
            assert_eq!(detection.trigger, Some(Trigger::JointStep), "{value}");
            assert_eq!(detection.joint_step, f64::INFINITY);
        }
        let broken = Matrix6xX::from_element(6, f64::NAN);
        let detection = detect(&broken, &still, &OPTIONS).unwrap();
        assert_eq!(detection.trigger, Some(Trigger::Determinant));
        // A step of the wrong size is an error naming it.
        let error = detect(&regular, &[0.0; 5], &OPTIONS).unwrap_err();
        assert!(error.to_string().contains("candidate_step"), "{error}");
    }

    /// Each test is strict: a determinant exactly at the threshold and a
    /// joint step exactly at the threshold, of either sign, are regular; one
    /// ulp beyond either triggers it.
    #[test]
    fn the_thresholds_are_strict_on_both_tests() {
        let jacobian = jacobian_with_determinant(0.3);
        let determinant = jacobian_determinant(&jacobian);
        let at = DetectionOptions {
            determinant_threshold: determinant,
            joint_step_threshold: 0.005,
        };
        for sign in [1.0, -1.0] {
            let detection = detect(&jacobian, &step(3, sign * 0.005), &at).unwrap();
            assert_eq!(detection.trigger, None, "sign {sign}: {detection:?}");
            assert_eq!(detection.joint_step, 0.005);
            assert_eq!(detection.determinant, determinant);
            let beyond = sign * 0.005_f64.next_up();
            let detection = detect(&jacobian, &step(3, beyond), &at).unwrap();
            assert_eq!(detection.trigger, Some(Trigger::JointStep), "{beyond}");
        }
        let above = DetectionOptions {
            determinant_threshold: determinant.next_up(),
            ..at
        };
        let detection = detect(&jacobian, &step(0, -0.005), &above).unwrap();
        assert_eq!(detection.trigger, Some(Trigger::Determinant));
        let detection = detect(&jacobian, &step(0, -0.0051), &above).unwrap();
        assert_eq!(detection.trigger, Some(Trigger::Both));
        // The same through the threshold test the other callers use.
        assert!(!below_threshold(determinant, determinant));
        assert!(below_threshold(determinant, determinant.next_up()));
        assert!(!below_threshold(determinant.next_up(), determinant));
        assert!(below_threshold(f64::NAN, determinant));
    }

    /// Both thresholds must be finite and > 0; the message names the field.
    #[test]
    fn validate_rejects_a_threshold_that_is_not_positive_and_finite() {
        assert!(OPTIONS.validate().is_ok());
        for bad in [0.0, -0.004, f64::NAN, f64::INFINITY] {
            let options = DetectionOptions {
                determinant_threshold: bad,
                ..OPTIONS
            };
            let error = options.validate().unwrap_err().to_string();
            assert!(error.contains("determinant_threshold"), "{bad}: {error}");
            let options = DetectionOptions {
                joint_step_threshold: bad,
                ..OPTIONS
            };
            let error = options.validate().unwrap_err().to_string();
            assert!(error.contains("joint_step_threshold"), "{bad}: {error}");
        }
    }

    /// The determinant measure is the product of the singular values for
    /// fewer, six and more than six columns.
    #[test]
    fn the_determinant_is_the_product_of_the_singular_values() {
        let entry = |r: usize, c: usize| {
            ((r * 7 + c * 3) % 11) as f64 / 5.0 - 1.0 + 0.3 * (r == c) as u8 as f64
        };
        for n in [3, 5, 6, 7, 9] {
            let j = Matrix6xX::from_fn(n, entry);
            let product: f64 = j.clone().svd(false, false).singular_values.iter().product();
            let measure = jacobian_determinant(&j);
            assert!(product > 1e-3, "n = {n}: a rank-deficient test matrix");
            assert!(
                (measure - product).abs() <= 1e-12 * product.max(1.0),
                "n = {n}: {measure} vs {product}"
            );
        }
    }
}
