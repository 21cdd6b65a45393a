//! Helpers shared by the CLI tests: run the binary, read its output, make
//! scratch folders.
#![allow(dead_code)]

use std::path::PathBuf;
use std::process::{Command, Output};

/// Runs `armkit` with `args`, from the repository root.
pub fn armkit(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_armkit"))
        .args(args)
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
        .output()
        .unwrap()
}

/// Standard output as text.
pub fn stdout(output: &Output) -> String {
    String::from_utf8_lossy(&output.stdout).to_string()
}

/// Standard error as trimmed text.
pub fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).trim().to_string()
}

/// Standard output parsed as JSON, after checking the command succeeded.
pub fn json(output: &Output) -> serde_json::Value {
    assert!(output.status.success(), "{}", stderr(output));
    serde_json::from_slice(&output.stdout).unwrap()
}

/// Standard output parsed as JSON, after checking the command ended with an
/// honest "not met" status (exit 3) and said why on standard error, which is
/// returned beside it.
pub fn json_unmet(output: &Output) -> (serde_json::Value, String) {
    assert_eq!(output.status.code(), Some(3), "{}", stderr(output));
    let reason = stderr(output);
    assert!(!reason.is_empty(), "exit 3 with nothing on stderr");
    (serde_json::from_slice(&output.stdout).unwrap(), reason)
}

/// An empty scratch folder for this test binary and `name`.
pub fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "armkit-{}-{name}-{}",
        env!("CARGO_CRATE_NAME"),
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}
