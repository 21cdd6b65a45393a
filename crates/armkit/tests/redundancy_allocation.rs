//! A redundancy solve allocates nothing once its workspace exists: a counting
//! global allocator sees zero allocations across many solves (weighted least
//! norm, damped, toward a preferred velocity, projector, seed 001's
//! partitioned form and eq 17, torques, energy weights, null-space directions).

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

use armkit::kinematics::{jacobian, Data, JacobianFrame};
use armkit::math::Vector6;
use armkit::redundancy::nullspace::SecondaryTask;
use armkit::redundancy::{
    best_partition, joint_torques, Damping, JointWeights, Load, PartitionedSolver,
    SecondaryObjective, SolverOptions, TorqueFloor, WeightedLeastNorm,
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
fn redundancy_solves_do_not_allocate() {
    let model = armkit::robots::by_name("gantry9").unwrap();
    let mut data = Data::new(&model);
    let q = [3.0, 2.5, 1.0, 0.3, 0.4, -0.5, 0.2, 0.8, 0.1];
    let j = jacobian(&model, &mut data, &q, JacobianFrame::World)
        .unwrap()
        .clone();
    let twist = Vector6::new(0.1, 0.05, -0.05, 0.0, 0.1, 0.0);
    let load = Load::payload(50.0).with_standard_gravity();
    let mut weights = JointWeights::uniform(9);
    let mut torques = [0.0; 9];
    let preferred = [0.01; 9];
    let mut z = [0.0; 9];
    let mut exact = WeightedLeastNorm::new(9, SolverOptions::default()).unwrap();
    let mut damped = WeightedLeastNorm::new(
        9,
        SolverOptions {
            damping: Damping::Adaptive {
                threshold: 0.1,
                max: 0.05,
            },
            ..SolverOptions::default()
        },
    )
    .unwrap();
    let partition = best_partition(&j, None, 1e10).unwrap().partition;
    let mut partitioned = PartitionedSolver::new(9, 1e10).unwrap();
    let mut limits =
        SecondaryTask::new(&model, SecondaryObjective::JointLimits { gain: 1.0 }).unwrap();
    let mut dexterity = SecondaryTask::new(
        &model,
        SecondaryObjective::Manipulability {
            gain: 1.0,
            step: 1e-6,
        },
    )
    .unwrap();
    let before = ALLOCATIONS.load(Ordering::SeqCst);
    for _ in 0..100 {
        joint_torques(&model, &mut data, &q, &load, &mut torques).unwrap();
        weights
            .set_from_torques(&torques, TorqueFloor::default())
            .unwrap();
        exact.solve(&j, &weights, &twist).unwrap();
        exact
            .solve_toward(&j, &weights, &twist, &preferred)
            .unwrap();
        exact.null_space_projector(&j, &weights).unwrap();
        damped.solve(&j, &weights, &twist).unwrap();
        partitioned.solve(&j, &weights, &twist, &partition).unwrap();
        partitioned
            .solve_energy_optimal(&j, &torques, &twist, &partition)
            .unwrap();
        limits
            .preferred_velocity(&model, &q, &weights, &mut z)
            .unwrap();
        dexterity
            .preferred_velocity(&model, &q, &weights, &mut z)
            .unwrap();
    }
    let after = ALLOCATIONS.load(Ordering::SeqCst);
    assert_eq!(after - before, 0, "{} allocations", after - before);
}
