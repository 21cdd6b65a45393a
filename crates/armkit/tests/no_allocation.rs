//! Forward kinematics and the Jacobian allocate nothing once `Data` exists:
//! a counting global allocator sees zero allocations across many calls.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

use armkit::kinematics::{forward_kinematics, jacobian, Data, JacobianFrame};

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
fn fk_and_jacobian_do_not_allocate() {
    for name in ["ur5", "panda", "gantry9", "gantry9-flex", "stanford"] {
        let model = armkit::robots::by_name(name).unwrap();
        let mut data = Data::new(&model);
        let q = model.neutral_configuration();
        let before = ALLOCATIONS.load(Ordering::SeqCst);
        for _ in 0..100 {
            forward_kinematics(&model, &mut data, &q).unwrap();
            jacobian(&model, &mut data, &q, JacobianFrame::World).unwrap();
            jacobian(&model, &mut data, &q, JacobianFrame::EndEffector).unwrap();
        }
        let after = ALLOCATIONS.load(Ordering::SeqCst);
        assert_eq!(after - before, 0, "{name}: {} allocations", after - before);
    }
}
