//! Example 09: seed 004's singularity avoidance on space6r.
//!
//! * The path: a straight pose line through the wrist singularity (`q5 = 0`)
//!   at mid-path, 20 s with 4 s of acceleration and deceleration.
//! * Plain resolved-rate tracking, seed 004's avoidance for k = 1, 5, 10
//!   (Newton-Raphson IK every k-th planned pose of the singular region and a
//!   C2 cubic through the knots), damped least squares (Nakamura) and the
//!   singularity-robust inverse (Chiaverini), on the fixed base and with the
//!   base attitude held (the generalized Jacobian `J*`).
//! * The table per method: peak joint rate, maximum and final position and
//!   orientation error, time in the singular region, IK solves.
//! * The classification of the singular configuration and the manipulability
//!   ellipsoid there.
//!
//! Run: `cargo run --release --example 09_singularity`

use armkit::math::Pose;
use armkit::robots::space6r_free_floating;
use armkit::singularity::{
    classify, manipulability_ellipsoid, seed004_path, AvoidanceOptions, Baselines, ClassifyOptions,
    Comparison, JacobianPart, Manipulator, PathTracker, SEED004_THROUGH,
};
use armkit::{jacobian, Data, JacobianFrame};

fn print_table(title: &str, comparison: &Comparison) {
    // One row per method, then the singular regions of the avoidance runs.
    println!("\n{title}\n{comparison}");
}

fn main() -> Result<(), armkit::Error> {
    let options = AvoidanceOptions::default();
    let baselines = Baselines::for_detection(&options.detection);
    let ks = [1, 5, 10];

    let arm = armkit::robots::space6r()?;
    let fixed = Manipulator::FixedBase(&arm);
    let line = seed004_path(&fixed)?;
    println!(
        "path: start q {:.3?} rad, through q {:?} (q5 = 0) at 10 s",
        line.start, SEED004_THROUGH
    );
    let tracker = PathTracker::new(fixed, line.task(20.0, 4.0), options)?;
    print_table("space6r, fixed base", &tracker.compare(&baselines, &ks)?);

    // The same path on the free-floating system with its base attitude held:
    // the line is built through the same joint configuration.
    let system = space6r_free_floating()?;
    let at_through = Manipulator::AttitudeHeld {
        system: &system,
        base: Pose::identity(),
    };
    let held_line = seed004_path(&at_through)?;
    let held = PathTracker::new(
        Manipulator::AttitudeHeld {
            system: &system,
            base: held_line.base,
        },
        held_line.task(20.0, 4.0),
        options,
    )?;
    print_table(
        "space6r, base attitude held (J*)",
        &held.compare(&baselines, &ks)?,
    );

    // What kind of singularity the path crosses, and the ellipsoids there.
    let mut data = Data::new(&arm);
    let found = classify(
        &arm,
        &mut data,
        &SEED004_THROUGH,
        &ClassifyOptions::default(),
    )?;
    println!(
        "\nat q = {SEED004_THROUGH:?}: {:?}, rank {}, singular values {:.3?}",
        found.kinds, found.rank, found.singular_values
    );
    let j = jacobian(&arm, &mut data, &SEED004_THROUGH, JacobianFrame::World)?;
    for part in [JacobianPart::Translational, JacobianPart::Rotational] {
        let e = manipulability_ellipsoid(j, part)?;
        println!(
            "{part:?} ellipsoid: radii {:.3?}, smallest along {:.3?}",
            e.radii,
            e.axes[2].as_slice()
        );
    }
    Ok(())
}
