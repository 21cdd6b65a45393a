//! The one tracking loop: an overflow inside a run is an error (not a
//! singularity), a singular Jacobian is a status, and the statuses print.

use std::f64::consts::FRAC_PI_2;

use armkit::math::{Pose, Vector3};
use armkit::redundancy::{Distribution, DistributionOptions, JointWeights, ResolvedRateTracker};
use armkit::tracking::{track_samples, FixedBase, LeastSquares, TrackingOptions, TrackingStatus};
use armkit::trajectory::TimeFn;
use armkit::{Data, Error};

/// Six joints whose forward kinematics overflows at `q = [1e308, 0, ...]`
/// (finite lengths and positions whose sum passes `f64::MAX`).
fn overflowing_arm() -> armkit::Model {
    let mut text = format!(
        "convention = \"standard\"\n[[links]]\ntype = \"P\"\nd = 1e308\na = 0\nalpha = 0\nqlim = [0, 1e308]\n\
         [[links]]\ntype = \"R\"\nd = 1e308\na = 0\nalpha = {FRAC_PI_2}\n",
    );
    for alpha in [-FRAC_PI_2, FRAC_PI_2, -FRAC_PI_2, 0.0] {
        text.push_str(&format!(
            "[[links]]\ntype = \"R\"\nd = 0.1\na = 0.2\nalpha = {alpha}\n"
        ));
    }
    armkit::description::parse_str(&text, armkit::description::Format::Toml, "<huge>").unwrap()
}

fn is_overflow(result: &armkit::Result<impl std::fmt::Debug>) -> bool {
    matches!(result, Err(Error::Numerical { reason, .. }) if reason.contains("overflowed"))
}

#[test]
fn an_overflow_inside_a_tracking_run_is_an_error_not_a_singularity() {
    let model = overflowing_arm();
    let q0 = [1e308, 0.0, 0.0, 0.0, 0.0, 0.0];
    // A finite target: the run itself overflows, not its input.
    let path = TimeFn::new(0.1, |_| Pose::from_translation(Vector3::new(0.1, 0.2, 0.3))).unwrap();
    // The generic loop, plain least squares.
    let mut data = Data::new(&model);
    let mut plant = FixedBase::new(&model, &mut data, &q0).unwrap();
    let report = track_samples(
        &mut plant,
        &mut LeastSquares { damping: 0.0 },
        &path,
        &TrackingOptions::default(),
    );
    assert!(is_overflow(&report), "{report:?}");
    // The redundancy tracker, fixed weights and energy weights.
    for distribution in [
        Distribution::Weights(JointWeights::uniform(6)),
        Distribution::Energy {
            load: armkit::redundancy::Load::payload(1.0),
            floor: armkit::redundancy::TorqueFloor::default(),
        },
    ] {
        let mut tracker =
            ResolvedRateTracker::new(&model, distribution, DistributionOptions::default()).unwrap();
        let report = tracker.run(&model, &q0, &path);
        assert!(is_overflow(&report), "{report:?}");
    }
}

#[test]
fn a_singular_jacobian_is_a_status_with_its_time() {
    // UR5 at q = 0: shoulder and wrist singular (rank < 6).
    let model = armkit::robots::by_name("ur5").unwrap();
    let q0 = [0.0; 6];
    let mut data = Data::new(&model);
    let start = *armkit::forward_kinematics(&model, &mut data, &q0).unwrap();
    let path = TimeFn::new(0.5, move |t| {
        Pose::from_translation(Vector3::new(0.0, 0.0, 0.1 * t)) * start
    })
    .unwrap();
    let mut plant = FixedBase::new(&model, &mut data, &q0).unwrap();
    let report = track_samples(
        &mut plant,
        &mut LeastSquares { damping: 0.0 },
        &path,
        &TrackingOptions::default(),
    )
    .unwrap();
    assert_eq!(report.status, TrackingStatus::Singular { time: 0.0 });
    assert_eq!(report.status.to_string(), "singular at 0.00 s");
    assert_eq!(report.samples.len(), 1);
    assert!(report.samples[0].joint_rates.iter().all(|&r| r == 0.0));
    // Damped, the same run completes.
    let mut plant = FixedBase::new(&model, &mut data, &q0).unwrap();
    let report = track_samples(
        &mut plant,
        &mut LeastSquares { damping: 0.05 },
        &path,
        &TrackingOptions::default(),
    )
    .unwrap();
    assert_eq!(report.status, TrackingStatus::Completed);
    assert_eq!(report.samples.len(), 51);
}
