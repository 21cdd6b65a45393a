//! The checks the fuzz targets run on one input. The same files are included
//! (`#[path]`) by the corpus replay test of the normal suite,
//! `crates/armkit-cli/tests/it/fuzz_corpus_replay.rs`, so a committed corpus
//! file is checked exactly as the fuzzer checked it.

pub mod armkit_checks;
pub mod cli_checks;
pub mod command_checks;
