//! No code. This crate's dependencies ask for the union of the features
//! that the workspace's three builds (the CLI, the test suite, the Python
//! wheel) enable on shared crates, so that the three share one build of
//! armkit and its dependencies (see Cargo.toml).
