//! The integration tests of the `armkit` library, one module per concept,
//! linked into one test binary (one link step for the whole suite).

mod common;
mod seed000_common;

mod beam;
mod build_features;
mod coupling;
mod description;
mod dynamics;
mod dynamics_coupled;
mod dynamics_published;
mod ik;
mod ik_analytic;
mod ik_answers;
mod ik_closed_form;
mod invariants;
mod invariants_nonfinite;
mod kinematics;
mod kinematics_batch;
mod layers;
mod mimic;
mod mpc;
mod mpc_priority;
mod mpc_qp;
mod mpc_random;
mod no_allocation;
mod reach;
mod reach_bound;
mod reach_placement;
mod reach_refine;
mod redundancy;
mod reference_dh;
mod seed000_claims;
mod seed000_precision;
mod seed001_claims;
mod seed002_claims;
mod seed002_path_error;
mod singularity;
mod space;
mod studies;
mod tracking;
mod trajectory;
mod urdf;
mod urdf_corpus;
