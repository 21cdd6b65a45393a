//! The `armkit` command-line tool as a library: the commands, the shared
//! argument parsing (`common`), plots, reports and scenario files. The
//! `armkit` binary (`main.rs`) is a thin clap front end over these modules;
//! the library target exists so that the fuzz targets (`fuzz/`) and the
//! integration tests can call the parsers (`common::parse_numbers`,
//! `common::parse_pose`, `scenario::parse`) directly.

pub mod commands;
pub mod common;
pub mod plot;
pub mod report;
pub mod scenario;
