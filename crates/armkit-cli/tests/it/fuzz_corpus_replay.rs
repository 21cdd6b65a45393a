//! Replays the committed fuzz corpus (`fuzz/corpus/<target>/*`) through the
//! very checks the fuzz targets run (the files of `fuzz/src`, included by
//! path), so an input that once found a bug, or reached new code, is checked
//! in every normal test run without cargo-fuzz or a nightly toolchain.

#[allow(dead_code)]
#[path = "../../../../fuzz/src/armkit_checks.rs"]
mod armkit_checks;
#[allow(dead_code)]
#[path = "../../../../fuzz/src/cli_checks.rs"]
mod cli_checks;
#[allow(dead_code)]
#[path = "../../../../fuzz/src/command_checks.rs"]
mod command_checks;

use std::path::PathBuf;

/// Runs `check` on every file of the target's corpus; returns how many.
fn replay(target: &str, check: fn(&[u8])) -> usize {
    let folder = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../fuzz/corpus")
        .join(target);
    let entries =
        std::fs::read_dir(&folder).unwrap_or_else(|e| panic!("{}: {e}", folder.display()));
    let mut count = 0;
    for entry in entries {
        let path = entry.unwrap().path();
        let bytes = std::fs::read(&path).unwrap();
        // A panic inside `check` fails the test; name the input first.
        let outcome = std::panic::catch_unwind(|| check(&bytes));
        assert!(
            outcome.is_ok(),
            "{target}: {} fails its check",
            path.display()
        );
        count += 1;
    }
    assert!(
        count > 10,
        "{target}: only {count} corpus files in {}",
        folder.display()
    );
    count
}

#[test]
fn urdf_corpus() {
    replay("urdf", armkit_checks::urdf);
}

#[test]
fn description_corpus() {
    replay("description", armkit_checks::description);
}

#[test]
fn scenario_corpus() {
    replay("scenario", cli_checks::scenario);
}

#[test]
fn cli_numbers_corpus() {
    replay("cli_numbers", cli_checks::cli_numbers);
}

#[test]
fn scenario_tables_corpus() {
    replay("scenario_tables", cli_checks::scenario_tables);
}

#[test]
fn dynamics_command_corpus() {
    replay("dynamics_command", command_checks::dynamics_command);
}

#[test]
fn ik_command_corpus() {
    replay("ik_command", command_checks::ik_command);
}
