//! Scenario files: parsing, errors that name the file, line and column,
//! and the shipped list equal to the `scenarios/` folder.

use std::path::Path;

use armkit_cli::commands::run::SHIPPED;
use armkit_cli::scenario::parse;

/// The error of parsing `text`, or else of running it.
fn error(text: &str) -> String {
    match parse(text, "s.toml", Path::new(".")) {
        Err(e) => e.0,
        Ok(scenario) => scenario.run().unwrap_err().0,
    }
}

#[test]
fn a_beam_scenario_parses_and_runs() {
    let scenario = parse(
        "name = \"b\"\ntitle = \"Beam\"\n[beam]\nsamples = 5\n",
        "s.toml",
        Path::new("."),
    )
    .unwrap();
    let report = scenario.run().unwrap();
    assert_eq!(report.name, "b");
    assert!(report.checks.len() >= 3);
    assert_eq!(report.passed(), report.checks.len());
}

#[test]
fn errors_name_file_line_and_column() {
    assert_eq!(
        error("name = \"b\"\ntitle = 3\n[beam]\n"),
        "s.toml: line 2, column 9 (`title = 3`): invalid type: integer `3`, expected a string"
    );
    assert_eq!(
        error("name = \"b\"\ntitle = \"t\"\n[robot]\nbuiltin = \"r2d2\"\n[beam]\n"),
        "s.toml: line 4, column 11: unknown robot `r2d2`; the built-in robots are: puma560, ur5, ur5-urdf, panda, stanford, arm4, space6r, gantry9, gantry9-flex"
    );
    assert!(error("title = \"t\"\n[beam]\n").contains("missing field `name`"));
    let untitled = parse("name = \"b\"\n[beam]\n", "s.toml", Path::new(".")).unwrap();
    assert_eq!(untitled.title, "b");
    assert_eq!(
        error("name = \"b\"\ntitle = \"t\"\n"),
        "s.toml: line 1, column 1: no method table: expected exactly one of [beam], [mpc], [redundancy], [continuous_path], [singularity], [space]"
    );
    assert_eq!(
        error("name = \"a b\"\ntitle = \"t\"\n[beam]\n"),
        "s.toml: line 1, column 8: `name` must be letters, digits, `-` or `_` (it names the output folder), got \"a b\""
    );
    assert_eq!(
        error("name = \"b\"\ntitle = \"t\"\n[beam]\nmas = 3.0\n"),
        "s.toml: line 4, column 1: [beam]: unknown key `mas`; the keys of [beam] are: gravity, mass, samples"
    );
    assert_eq!(
        error("name = \"b\"\ntitle = \"t\"\n[beam]\nmass = \"heavy\"\n"),
        "s.toml: line 4, column 1: [beam]: invalid value 'heavy' for `mass`: invalid float literal"
    );
    assert_eq!(
        error("name = \"b\"\ntitle = \"t\"\n[robot]\nbuiltin = \"ur5\"\n[beam]\n"),
        "s.toml: line 4, column 11: [beam] takes no [robot]: it runs seed 000's own gantry beam (remove the [robot] table)"
    );
    assert_eq!(
        error("name = \"b\"\ntitle = \"t\"\n[beam]\nmass = -400.0\n"),
        "s.toml: line 4, column 1: [beam]: invalid argument `mass`: must be finite and >= 0 kg, got -400"
    );
}

#[test]
fn the_shipped_list_is_the_scenarios_folder() {
    let dir = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenarios"));
    let mut on_disk: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().to_string())
        .filter(|n| n.ends_with(".toml"))
        .collect();
    on_disk.sort();
    let mut shipped: Vec<String> = SHIPPED.iter().map(|(n, _)| n.to_string()).collect();
    shipped.sort();
    assert_eq!(on_disk, shipped);
    for (name, text) in SHIPPED {
        let from_disk = std::fs::read_to_string(dir.join(name)).unwrap();
        assert_eq!(&from_disk, text);
    }
}
