//! Every `armkit ...` command of the README's `sh` blocks runs and exits 0,
//! in a scratch folder (the repository's `tests`, `scenarios` and `examples`
//! linked into it, so that the README's relative paths resolve and what a
//! command writes stays out of the repository). A README example that stops
//! working fails here; the Python blocks are run by
//! `crates/armkit-py/tests/test_readme.py`.

use crate::common::{scratch, stderr};
use std::path::Path;
use std::process::Command;

/// The README's text.
fn readme() -> String {
    std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../README.md")).unwrap()
}

/// The bodies of the fenced blocks of `language` (` ```sh ` etc.).
fn fenced_blocks(text: &str, language: &str) -> Vec<String> {
    let mut blocks = Vec::new();
    let mut current: Option<String> = None;
    for line in text.lines() {
        match current.as_mut() {
            Some(body) if line.trim_start().starts_with("```") => {
                blocks.push(std::mem::take(body));
                current = None;
            }
            Some(body) => {
                body.push_str(line);
                body.push('\n');
            }
            None if line.trim() == format!("```{language}") => current = Some(String::new()),
            None => {}
        }
    }
    blocks
}

/// Splits a shell line into words: whitespace outside double quotes, quotes
/// removed, a word starting with `#` ends the line (a comment).
fn shell_words(line: &str) -> Vec<String> {
    let mut words = Vec::new();
    let mut word = String::new();
    let mut in_word = false;
    let mut quoted = false;
    for c in line.chars() {
        match c {
            '"' => {
                quoted = !quoted;
                in_word = true;
            }
            c if c.is_whitespace() && !quoted => {
                if in_word {
                    words.push(std::mem::take(&mut word));
                    in_word = false;
                }
            }
            '#' if !quoted && !in_word => break,
            c => {
                word.push(c);
                in_word = true;
            }
        }
    }
    assert!(!quoted, "unbalanced quotes in the README's line `{line}`");
    if in_word {
        words.push(word);
    }
    words
}

/// A README command: its arguments after `armkit`, and the exit code the
/// README promises (0, or 3 where its comment says `exit 3`: a run that
/// did not meet its goal, with the reason on stderr).
pub struct ReadmeCommand {
    pub args: Vec<String>,
    pub exit: i32,
}

/// Every `armkit` command of the README's `sh` blocks (continuation lines
/// joined).
pub fn readme_commands() -> Vec<ReadmeCommand> {
    let mut commands = Vec::new();
    for block in fenced_blocks(&readme(), "sh") {
        let joined = block.replace("\\\n", " ");
        for line in joined.lines() {
            let words = shell_words(line);
            if words.first().map(String::as_str) == Some("armkit") {
                commands.push(ReadmeCommand {
                    args: words[1..].to_vec(),
                    exit: if line.contains("# exit 3") { 3 } else { 0 },
                });
            }
        }
    }
    commands
}

#[cfg(unix)]
fn link_repository_folders(into: &Path) {
    let root = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."));
    for folder in ["tests", "scenarios", "examples"] {
        std::os::unix::fs::symlink(root.join(folder).canonicalize().unwrap(), into.join(folder))
            .unwrap();
    }
}

#[test]
fn the_readme_has_commands_for_every_section() {
    let commands = readme_commands();
    assert!(commands.len() >= 25, "{} commands", commands.len());
    for command in &commands {
        for word in &command.args {
            assert!(
                !(word.contains("...") || word.starts_with('[') || word.starts_with('<')),
                "a placeholder in the README's `armkit {}`: write a value that runs",
                command.args.join(" ")
            );
        }
    }
}

#[cfg(unix)]
#[test]
fn every_readme_command_runs() {
    let dir = scratch("readme-commands");
    link_repository_folders(&dir);
    let mut failures = Vec::new();
    for command in readme_commands() {
        let output = Command::new(env!("CARGO_BIN_EXE_armkit"))
            .args(&command.args)
            .current_dir(&dir)
            .output()
            .unwrap();
        let reason_given = command.exit == 0 || !stderr(&output).is_empty();
        if output.status.code() != Some(command.exit) || !reason_given {
            failures.push(format!(
                "armkit {}\n  exit {:?} (the README says {}): {}",
                command.args.join(" "),
                output.status.code(),
                command.exit,
                stderr(&output)
            ));
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    assert!(
        failures.is_empty(),
        "{} README commands failed:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// The README's TOML blocks run too: a scenario (`name` and a method table)
/// with `armkit run`, a DH description (`[[links]]`) with `armkit info`.
#[test]
fn every_readme_toml_block_loads_and_runs() {
    let dir = scratch("readme-toml");
    let blocks = fenced_blocks(&readme(), "toml");
    assert!(blocks.len() >= 2, "{} TOML blocks", blocks.len());
    for (index, block) in blocks.iter().enumerate() {
        let path = dir.join(format!("block{index}.toml"));
        std::fs::write(&path, block).unwrap();
        let path = path.to_string_lossy().to_string();
        let args: Vec<&str> = if block.contains("[[links]]") {
            vec!["info", "--robot-file", &path]
        } else {
            vec!["run", &path]
        };
        let output = Command::new(env!("CARGO_BIN_EXE_armkit"))
            .args(&args)
            .current_dir(&dir)
            .output()
            .unwrap();
        assert!(
            output.status.success(),
            "README TOML block {}: armkit {}: {}",
            index + 1,
            args.join(" "),
            stderr(&output)
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn shell_words_keep_quoted_values_and_drop_comments() {
    assert_eq!(
        shell_words(r#"armkit fk --q "0, 1" --json   # pose"#),
        ["armkit", "fk", "--q", "0, 1", "--json"]
    );
    assert_eq!(shell_words("a#b c"), ["a#b", "c"]);
}

/// The targets of the README's relative links and images (`](path)`, a
/// fragment or a URL excluded).
fn relative_link_targets(text: &str) -> Vec<String> {
    text.split("](")
        .skip(1)
        .filter_map(|rest| rest.split(')').next())
        .map(|target| target.split('#').next().unwrap_or("").to_string())
        .filter(|target| !target.is_empty() && !target.contains("://"))
        .collect()
}

#[test]
fn every_relative_link_and_picture_of_the_readme_exists() {
    let root = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."));
    let targets = relative_link_targets(&readme());
    assert!(
        targets.iter().filter(|t| t.ends_with(".png")).count() >= 3,
        "{targets:?}"
    );
    for target in &targets {
        assert!(
            root.join(target).exists(),
            "the README links {target}, which is not in the repository"
        );
    }
    assert_eq!(
        relative_link_targets("[a](docs/x.md) [b](#anchor) ![c](https://e.org/y.png)"),
        ["docs/x.md"]
    );
}

/// The README's capability-map picture is a committed SVG written by
/// `armkit reach --svg`, and the README shows it.
#[test]
fn the_readme_shows_the_committed_capability_map() {
    let name = "docs/images/ur5_capability.svg";
    assert!(
        readme().contains(&format!("]({name})")),
        "the README does not show {name}"
    );
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .join(name);
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.starts_with("<svg") && text.contains("capability index"));
}
