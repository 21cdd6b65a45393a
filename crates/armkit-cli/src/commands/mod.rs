//! One module per `armkit` subcommand.

pub mod beam;
pub mod dynamics;
pub mod fk;
pub mod ik;
pub mod info;
pub mod manipulability;
pub mod mpc;
pub mod reach;
pub mod redundancy;
pub mod robots;
pub mod run;
pub mod singularity;
pub mod space;
pub mod traj;
pub mod view;
