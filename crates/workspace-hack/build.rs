//! Empty: it exists so that cargo resolves this crate's build-dependencies,
//! whose features unify with the proc macros' (see Cargo.toml).
fn main() {}
