//! The free-floating hot paths allocate nothing once `SpaceData` exists: a
//! counting global allocator sees zero allocations across many calls of
//! `generalized_jacobian`, `step`, `center_of_mass`, `end_effector_pose` and
//! `momentum`, in both base modes.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

use armkit::math::{Pose, Vector6};
use armkit::space::{
    center_of_mass, end_effector_pose, generalized_jacobian, momentum, space6r_free_floating, step,
    BaseMode, FreeFloatingState, SpaceData,
};

struct CountingAllocator;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for CountingAllocator {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static GLOBAL: CountingAllocator = CountingAllocator;

#[test]
fn free_floating_hot_paths_do_not_allocate() {
    let model = space6r_free_floating().unwrap();
    let mut data = SpaceData::new(&model);
    let mut state = FreeFloatingState::new(
        Pose::from_xyz_rpy([0.1, 0.2, 0.3], [0.3, 0.2, 0.1]),
        vec![0.3, 0.6, -0.9, 0.4, 0.7, -0.2],
    );
    let rates = [0.1, -0.2, 0.3, 0.1, 0.2, -0.1];
    let twist = Vector6::new(0.01, 0.0, 0.0, 0.0, 0.01, 0.0);
    for mode in [BaseMode::AttitudeHeld, BaseMode::FreeFloating] {
        let before = ALLOCATIONS.load(Ordering::SeqCst);
        for _ in 0..100 {
            generalized_jacobian(&model, &mut data, &state.base, &state.q, mode).unwrap();
            step(&model, &mut data, &mut state, &rates, 0.01, mode).unwrap();
            center_of_mass(&model, &mut data, &state.base, &state.q).unwrap();
            end_effector_pose(&model, &mut data, &state.base, &state.q).unwrap();
            momentum(&model, &mut data, &state.base, &state.q, &twist, &rates).unwrap();
        }
        let after = ALLOCATIONS.load(Ordering::SeqCst);
        assert_eq!(
            after - before,
            0,
            "{mode:?}: {} allocations",
            after - before
        );
    }
}
