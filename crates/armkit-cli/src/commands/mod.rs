//! One module per `armkit` subcommand.

pub mod demo;
pub mod fk;
pub mod robots;
