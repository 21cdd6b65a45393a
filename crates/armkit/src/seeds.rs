//! Constants from the seed papers, in one place, and the standard gravity.
//!
//! Each constant says which seed and which equation, table or example it
//! comes from. Units are SI; joint vectors follow the joint order of the
//! robot named.
//!
//! ```
//! use armkit::seeds::{SEED000_GRAVITY, SEED000_PRIORITY_WEIGHTS, STANDARD_GRAVITY};
//! assert_eq!(SEED000_PRIORITY_WEIGHTS[0], 100.0); // the rail: lowest priority
//! assert!(SEED000_GRAVITY > STANDARD_GRAVITY);    // Table 1 rounds g up to 10
//! ```

/// Standard gravity, m/s^2 (the conventional value, exact by definition):
/// the one standard gravity of armkit. The seed studies keep the rounding
/// their numbers were computed with: [`SEED000_GRAVITY`] (Table 1) and
/// [`SEED001_GRAVITY`] (the energy study).
pub const STANDARD_GRAVITY: f64 = 9.80665;

/// The gravity of seed 001's energy study in armkit, m/s^2: `g` to three
/// figures, the value [`crate::redundancy::Load::with_seed001_gravity`] puts
/// on the links and that the demo's and the tests' energy measures were
/// computed with.
pub const SEED001_GRAVITY: f64 = 9.81;

/// Seed 000's gravity, m/s^2: its Table 1 (theoretical beam deflections)
/// is computed with `g = 10`; armkit reproduces the printed values with it.
pub const SEED000_GRAVITY: f64 = 10.0;

/// Seed 000's joint priorities for the 9-DOF gantry (sec 4.4, example 1):
/// weight 100 on the rail joint `d1` (lowest priority: long, heavy,
/// imprecise), 10 on the beam joints `d2`, `d3`, and 1 on the six arm joints
/// (highest priority). Dimensionless; joint order of
/// [`crate::robots::gantry9`]. Used as redundancy weights and as the MPC's
/// increment weights `R`.
pub const SEED000_PRIORITY_WEIGHTS: [f64; 9] = [100.0, 10.0, 10.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0];

/// The start configuration of seed 001's four-way comparison on gantry9
/// (m for the three prismatic joints, rad for the six arm joints): mid-rail,
/// the arm bent away from its singularities.
pub const SEED001_GANTRY_START: [f64; 9] = [3.0, 2.5, 1.0, 0.3, 0.4, -0.5, 0.2, 0.8, 0.1];

/// The end-effector displacement of that comparison, world frame, m.
pub const SEED001_GANTRY_MOVE: [f64; 3] = [0.4, 0.3, -0.3];
