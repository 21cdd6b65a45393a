//! # armkit
//!
//! Kinematics, redundancy resolution, trajectory planning and model-predictive
//! motion planning of serial robot manipulators, from 4-DOF arms to a 9-DOF
//! gantry with a flexible beam and free-floating space manipulators.
//!
//! Conventions, everywhere unless an item says otherwise:
//! * `f64`, SI units: metres, radians, seconds, kilograms, newtons.
//! * Poses are [`math::Pose`] (rotation matrix + translation) in the world frame,
//!   the frame in which a model's base transform is given.
//! * Twists and Jacobian rows are `[vx, vy, vz, wx, wy, wz]` (linear first).
//! * Roll-pitch-yaw is URDF's: `R = Rz(yaw) Ry(pitch) Rx(roll)`.
//!
//! The layout follows Pinocchio: an immutable [`model::Model`], a
//! [`kinematics::Data`] workspace sized once, and algorithms as free functions
//! `f(&Model, &mut Data, q)` that allocate nothing on their hot path.
//!
//! ```
//! use armkit::kinematics::{forward_kinematics, Data};
//! let model = armkit::robots::by_name("puma560").unwrap();
//! let mut data = Data::new(&model);
//! let pose = forward_kinematics(&model, &mut data, &[0.0; 6]).unwrap();
//! println!("{:?}", pose.translation);
//! ```

#![warn(missing_docs)]
// Library code returns errors; it never panics on user input.
#![cfg_attr(
    not(test),
    deny(clippy::unwrap_used, clippy::expect_used, clippy::panic)
)]

pub mod beam;
#[cfg(feature = "io")]
pub mod description;
pub mod dynamics;
pub mod error;
pub mod ik;
pub mod kinematics;
pub mod linalg;
pub mod math;
pub mod model;
pub mod mpc;
pub mod reach;
pub mod redundancy;
pub mod robots;
pub mod seeds;
pub mod singularity;
pub mod space;
pub mod study;
pub mod tracking;
pub mod trajectory;
#[cfg(feature = "urdf")]
pub mod urdf;

pub use error::{Error, Result};
pub use kinematics::{forward_kinematics, jacobian, Data, JacobianFrame};
pub use model::Model;

/// The README's Rust example, compiled and run as a doctest so that it stays true.
#[doc = include_str!("../../../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;
