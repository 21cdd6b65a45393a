//! Sampling a trajectory allocates nothing: a counting global allocator sees
//! zero allocations across many `sample_into` calls (joint space) and
//! `CartesianTrajectory::sample` calls (built-in paths), counted per thread.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

use armkit::math::{Pose, Vector3};
use armkit::trajectory::cartesian::{
    ArcOrientation, ArcPath, CartesianTrajectory, LinePath, TimeLaw,
};
use armkit::trajectory::profile::{self, ProfileShape};
use armkit::trajectory::spline::clamped_cubic_spline;
use armkit::trajectory::JointState;

struct CountingAllocator;

thread_local! {
    // Per thread: the test harness's own threads allocate at times too.
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

fn allocations() -> usize {
    ALLOCATIONS.with(Cell::get)
}

unsafe impl GlobalAlloc for CountingAllocator {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let _ = ALLOCATIONS.try_with(|c| c.set(c.get() + 1));
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static GLOBAL: CountingAllocator = CountingAllocator;

#[test]
fn sampling_does_not_allocate() {
    let q0 = [0.0, -0.3, 0.0, -2.2, 0.0, 2.0, 0.8];
    let qf = [1.0, 0.4, -0.5, -1.2, 0.7, 1.2, -0.3];
    let times: Vec<f64> = (0..=20).map(|i| i as f64 * 0.25).collect();
    let points: Vec<Vec<f64>> = times
        .iter()
        .map(|t| q0.iter().map(|q| q + t.sin()).collect())
        .collect();
    let joint = [
        profile::rest_to_rest(ProfileShape::Quintic, &q0, &qf, 2.0, None).unwrap(),
        profile::trapezoidal(&q0, &qf, 20.0, 4.0).unwrap(),
        clamped_cubic_spline(&times, &points, &[0.0; 7], &[0.0; 7]).unwrap(),
    ];
    let start = Pose::from_xyz_rpy([0.4, 0.0, 0.3], [0.1, 0.2, 0.3]);
    let end = Pose::from_xyz_rpy([0.4, 0.3, 0.1], [0.3, -0.2, 1.3]);
    let line = CartesianTrajectory::new(
        LinePath::new(start, end).unwrap(),
        TimeLaw::Quintic.timing(2.0).unwrap(),
    )
    .unwrap();
    let arc = ArcPath::new(
        start,
        Vector3::new(0.2, 0.0, 0.3),
        Vector3::z(),
        1.0,
        ArcOrientation::FollowArc,
    )
    .unwrap();
    let arc = CartesianTrajectory::new(
        arc,
        TimeLaw::Trapezoidal {
            acceleration_time: 0.5,
        }
        .timing(2.0)
        .unwrap(),
    )
    .unwrap();
    let mut out = JointState::zeros(7);
    let before = allocations();
    let mut checksum = 0.0;
    for k in 0..1000 {
        let t = k as f64 * 0.0051;
        for traj in &joint {
            traj.sample_into(t, &mut out).unwrap();
            checksum += out.position[0] + out.velocity[6] + out.acceleration[3];
        }
        for path in [&line, &arc] {
            let state = path.sample(t).unwrap();
            checksum += state.pose.translation.x + state.twist[5] + path.pose_at(t).translation.y;
        }
    }
    let after = allocations();
    assert!(checksum.is_finite());
    assert_eq!(after - before, 0, "{} allocations", after - before);
}
