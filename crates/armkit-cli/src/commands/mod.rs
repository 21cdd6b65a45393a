//! One module per `armkit` subcommand.

pub mod beam;
pub mod demo;
pub mod fk;
pub mod robots;
pub mod space;
