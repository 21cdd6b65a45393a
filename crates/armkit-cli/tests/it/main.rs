//! The integration tests of the `armkit` command-line tool, one module per
//! command, linked into one test binary (one link step for the whole suite).

mod common;

mod bad_inputs;
mod beam;
mod bench_preemption;
mod demo_browser;
mod dynamics;
mod fk;
mod fuzz_corpus_replay;
mod ik;
mod manipulability;
mod mpc;
mod numbers;
mod plot;
mod reach;
mod readme;
mod redundancy;
mod report;
mod scenario_parse;
mod scenario_user;
mod singularity;
mod space;
mod traj;
mod urdf;
mod view_browser;
