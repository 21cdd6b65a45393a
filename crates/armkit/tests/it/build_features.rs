//! The CLI (`cargo run`), the test suite (`cargo test --workspace`) and the
//! Python wheel (maturin's build of `armkit-py`) share one build of armkit
//! and its dependencies only while cargo resolves the same features on every
//! crate they share; otherwise each build compiles those crates, and armkit,
//! again. `crates/workspace-hack` asks for the union of the features. This
//! test asks `cargo tree` for the three builds' features and names every
//! shared crate on which they differ: add the missing features there.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;
use std::process::Command;

/// Package ("name version") -> its enabled features, for one `cargo tree`
/// selection of packages and dependency kinds.
type Features = BTreeMap<String, BTreeSet<String>>;

fn resolved_features(selection: &[&str], edges: &str) -> Features {
    let workspace = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let output = Command::new(cargo)
        .current_dir(&workspace)
        .args(["tree", "--prefix", "none", "-f", "{p} [{f}]"])
        .args(["-e", edges])
        .args(selection)
        .output()
        .expect("cargo runs");
    assert!(
        output.status.success(),
        "cargo tree {selection:?}: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    parse_tree(&String::from_utf8(output.stdout).unwrap())
}

/// Reads `cargo tree -f "{p} [{f}]"` lines: `serde v1.0.0 [default,std]`,
/// with an optional `(path)` after the version and `(*)` after a repeat.
fn parse_tree(text: &str) -> Features {
    let mut features = Features::new();
    for line in text.lines() {
        let mut words = line.split_whitespace();
        let (Some(name), Some(version)) = (words.next(), words.next()) else {
            continue;
        };
        let (Some(open), Some(close)) = (line.rfind('['), line.rfind(']')) else {
            continue;
        };
        features
            .entry(format!("{name} {version}"))
            .or_default()
            .extend(
                line[open + 1..close]
                    .split(',')
                    .filter(|f| !f.is_empty())
                    .map(String::from),
            );
    }
    features
}

#[test]
fn parse_tree_reads_names_versions_and_features() {
    let parsed = parse_tree(
        "armkit v0.1.0 (/x/crates/armkit) [default,io]\nrawpointer v0.2.1 []\nserde v1.0.1 [std] (*)\n",
    );
    assert_eq!(parsed.len(), 3);
    assert_eq!(
        parsed["armkit v0.1.0"],
        BTreeSet::from(["default".into(), "io".into()])
    );
    assert!(parsed["rawpointer v0.2.1"].is_empty());
    assert_eq!(parsed["serde v1.0.1"], BTreeSet::from(["std".to_string()]));
}

#[test]
fn the_cli_the_tests_and_the_wheel_resolve_the_same_features() {
    let builds = [
        (
            "the CLI",
            resolved_features(&["-p", "armkit-cli", "-p", "armkit"], "normal,build"),
        ),
        (
            "the tests",
            resolved_features(&["--workspace"], "normal,build,dev"),
        ),
        (
            "the wheel",
            resolved_features(&["-p", "armkit-py"], "normal,build"),
        ),
    ];
    let mut differences = Vec::new();
    for (i, (first, a)) in builds.iter().enumerate() {
        for (second, b) in &builds[i + 1..] {
            for (package, features) in a {
                if let Some(other) = b.get(package).filter(|other| *other != features) {
                    differences.push(format!(
                        "{package}: {first} {features:?}, {second} {other:?}"
                    ));
                }
            }
        }
    }
    assert!(
        differences.is_empty(),
        "add these features to crates/workspace-hack/Cargo.toml:\n{}",
        differences.join("\n")
    );
    assert!(builds.iter().all(|(_, f)| f.contains_key("armkit v0.1.0")));
}
