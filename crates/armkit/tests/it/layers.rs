//! The library's modules form layers: a module imports only modules below it
//! in [`LAYERS`], never one above (docs/DEVELOPING.md, "Layout").
//!
//! The test reads `src/**/*.rs`, takes each file's top-level module (the
//! first component of its path under `src/`), and collects the modules its
//! code names through `crate::<module>` (also inside `use crate::{a, b::c}`
//! groups, through `super::` paths that climb to the crate root, and through
//! the crate root's own re-exports such as `crate::Model`). Comments, string
//! and character literals, and everything from a file's first `#[cfg(test)]`
//! on are not code for this rule: tests may use any module.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

/// The library's top-level modules, lowest first. A module may import only
/// the modules before it.
const LAYERS: &[&str] = &[
    "error",
    "math",
    "linalg",
    "seeds",
    "model",
    "beam",
    "description",
    "urdf",
    "kinematics",
    "dynamics",
    "ik",
    "trajectory",
    "tracking",
    "redundancy",
    "space",
    "singularity",
    "reach",
    "robots",
    "mpc",
    "study",
];

fn source_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

/// Every `.rs` file under `dir`, sorted.
fn rust_files(dir: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    let mut pending = vec![dir.to_path_buf()];
    while let Some(current) = pending.pop() {
        for entry in fs::read_dir(&current).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                pending.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                files.push(path);
            }
        }
    }
    files.sort();
    files
}

/// The top-level modules of the crate: `src/foo.rs` and `src/foo/`.
fn top_level_modules(src: &Path) -> BTreeSet<String> {
    fs::read_dir(src)
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .filter_map(|path| {
            let name = path.file_name()?.to_str()?.to_string();
            if path.is_dir() {
                Some(name)
            } else {
                let stem = name.strip_suffix(".rs")?;
                (stem != "lib").then(|| stem.to_string())
            }
        })
        .collect()
}

/// The code of a file for this rule: cut at its first `#[cfg(test)]`, with
/// comments removed and string and character literals emptied (line breaks
/// kept, so that positions keep their line numbers).
fn code_of(source: &str) -> String {
    let source = match source.find("#[cfg(test)]") {
        Some(cut) => &source[..cut],
        None => source,
    };
    let chars: Vec<char> = source.chars().collect();
    let mut code = String::with_capacity(source.len());
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        let next = chars.get(i + 1).copied();
        if c == '/' && next == Some('/') {
            while i < chars.len() && chars[i] != '\n' {
                i += 1;
            }
        } else if c == '/' && next == Some('*') {
            let mut depth = 0;
            while i < chars.len() {
                if chars[i] == '/' && chars.get(i + 1) == Some(&'*') {
                    depth += 1;
                    i += 2;
                } else if chars[i] == '*' && chars.get(i + 1) == Some(&'/') {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    if chars[i] == '\n' {
                        code.push('\n');
                    }
                    i += 1;
                }
            }
        } else if c == 'r'
            && (next == Some('"') || next == Some('#'))
            && !is_ident_char(i.checked_sub(1).map(|p| chars[p]))
            && raw_string_start(&chars, i).is_some()
        {
            // r"..." or r#"..."#: no escapes, ends at `"` and as many `#`.
            let (hashes, body) = raw_string_start(&chars, i).unwrap_or((0, i));
            i = body;
            while i < chars.len() {
                if chars[i] == '"' && (0..hashes).all(|k| chars.get(i + 1 + k) == Some(&'#')) {
                    i += 1 + hashes;
                    break;
                }
                if chars[i] == '\n' {
                    code.push('\n');
                }
                i += 1;
            }
            code.push_str("\"\"");
        } else if c == '"' {
            i += 1;
            while i < chars.len() && chars[i] != '"' {
                if chars[i] == '\\' {
                    i += 1;
                }
                if chars.get(i) == Some(&'\n') {
                    code.push('\n');
                }
                i += 1;
            }
            i += 1;
            code.push_str("\"\"");
        } else if c == '\'' && next == Some('\\') {
            // An escaped character literal: '\n', '\'', '\u{..}'.
            i += 3;
            while i < chars.len() && chars[i] != '\'' {
                i += 1;
            }
            i += 1;
            code.push_str("' '");
        } else if c == '\'' && chars.get(i + 2) == Some(&'\'') {
            i += 3;
            code.push_str("' '");
        } else {
            // Code, or the quote of a lifetime.
            code.push(c);
            i += 1;
        }
    }
    code
}

/// For a raw string starting at `i` (`r`), the number of `#` and the index
/// of its first character.
fn raw_string_start(chars: &[char], i: usize) -> Option<(usize, usize)> {
    let mut j = i + 1;
    while chars.get(j) == Some(&'#') {
        j += 1;
    }
    (chars.get(j) == Some(&'"')).then_some((j - i - 1, j + 1))
}

fn is_ident_char(c: Option<char>) -> bool {
    c.is_some_and(|c| c.is_alphanumeric() || c == '_')
}

/// The identifier starting at `i`, if any.
fn ident_at(chars: &[char], i: usize) -> Option<String> {
    let ident: String = chars[i.min(chars.len())..]
        .iter()
        .take_while(|c| c.is_alphanumeric() || **c == '_')
        .collect();
    (!ident.is_empty()).then_some(ident)
}

/// The first identifier of each item of the `{ ... }` group opening at `i`
/// (nested groups skipped).
fn group_heads(chars: &[char], i: usize) -> Vec<String> {
    let mut heads = Vec::new();
    let mut depth = 0;
    let mut expect_head = true;
    let mut j = i;
    while j < chars.len() {
        let c = chars[j];
        match c {
            '{' => {
                depth += 1;
                expect_head = depth == 1;
            }
            '}' => {
                depth -= 1;
                if depth == 0 {
                    break;
                }
            }
            ',' if depth == 1 => expect_head = true,
            _ if c.is_whitespace() => {}
            _ => {
                if expect_head && depth == 1 {
                    if let Some(ident) = ident_at(chars, j) {
                        j += ident.chars().count();
                        heads.push(ident);
                        expect_head = false;
                        continue;
                    }
                }
                expect_head = false;
            }
        }
        j += 1;
    }
    heads
}

/// What `path` names at the crate root, read at `i` (just after `crate::`):
/// one identifier, or the heads of a group.
fn root_names(chars: &[char], i: usize) -> Vec<String> {
    match chars.get(i) {
        Some('{') => group_heads(chars, i),
        _ => ident_at(chars, i).into_iter().collect(),
    }
}

/// `(line, name)` of every crate-root name the code refers to: the first
/// segment after `crate::`, and after `super::` chains that reach the
/// crate root from a file at module depth `depth` (1 for `src/foo.rs` and
/// `src/foo/mod.rs`, 2 for `src/foo/bar.rs`, ...).
fn root_references(code: &str, depth: usize) -> Vec<(usize, String)> {
    let chars: Vec<char> = code.chars().collect();
    let mut references = Vec::new();
    let mut line = 1;
    let mut i = 0;
    while i < chars.len() {
        if chars[i] == '\n' {
            line += 1;
        }
        let starts_word = !is_ident_char(i.checked_sub(1).map(|p| chars[p]));
        if starts_word {
            if let Some(word) = ident_at(&chars, i) {
                let after = i + word.chars().count();
                let separator =
                    |k: usize| chars.get(k) == Some(&':') && chars.get(k + 1) == Some(&':');
                if word == "crate" && separator(after) {
                    for name in root_names(&chars, after + 2) {
                        references.push((line, name));
                    }
                } else if word == "super" && separator(after) {
                    let mut supers = 1;
                    let mut k = after + 2;
                    while ident_at(&chars, k).as_deref() == Some("super") && separator(k + 5) {
                        supers += 1;
                        k += 7;
                    }
                    if supers >= depth {
                        for name in root_names(&chars, k) {
                            references.push((line, name));
                        }
                    }
                    i = k;
                    continue;
                }
                i = after;
                continue;
            }
        }
        i += 1;
    }
    references
}

/// The module depth of a file under `src/` (see [`root_references`]).
fn module_depth(relative: &Path) -> usize {
    let components = relative.components().count();
    if relative.file_name().is_some_and(|n| n == "mod.rs") {
        components - 1
    } else {
        components
    }
}

/// The crate root's re-exports (`pub use module::{Item, ...}` in `lib.rs`):
/// item name -> the module it comes from.
fn root_reexports(src: &Path) -> BTreeMap<String, String> {
    let code = code_of(&fs::read_to_string(src.join("lib.rs")).unwrap());
    let mut items = BTreeMap::new();
    for statement in code.split(';') {
        let Some(path) = statement.trim().strip_prefix("pub use ") else {
            continue;
        };
        let Some((module, rest)) = path.split_once("::") else {
            continue;
        };
        let rest = rest.trim().trim_start_matches('{').trim_end_matches('}');
        for item in rest.split(',') {
            let item = item.split(" as ").last().unwrap_or("").trim();
            let item = item.rsplit("::").next().unwrap_or("");
            if !item.is_empty() {
                items.insert(item.to_string(), module.trim().to_string());
            }
        }
    }
    items
}

/// Every import from a module to one at its layer or above it, as
/// `file:line: ...`; and every name after `crate::` that is neither a
/// module nor a re-export of the crate root.
fn upward_imports(src: &Path) -> Vec<String> {
    let rank = |module: &str| LAYERS.iter().position(|m| *m == module);
    let reexports = root_reexports(src);
    let mut problems = Vec::new();
    for file in rust_files(src) {
        let relative = file.strip_prefix(src).unwrap().to_path_buf();
        let Some(first) = relative.components().next() else {
            continue;
        };
        let module = first
            .as_os_str()
            .to_string_lossy()
            .trim_end_matches(".rs")
            .to_string();
        if module == "lib" {
            continue;
        }
        let Some(own_rank) = rank(&module) else {
            continue; // reported by `every_library_module_has_a_layer`
        };
        let code = code_of(&fs::read_to_string(&file).unwrap());
        for (line, name) in root_references(&code, module_depth(&relative)) {
            let target = if rank(&name).is_some() {
                name.clone()
            } else if let Some(origin) = reexports.get(&name) {
                origin.clone()
            } else {
                problems.push(format!(
                    "src/{}:{line}: `crate::{name}` names neither a module of LAYERS nor a \
                     re-export of lib.rs",
                    relative.display()
                ));
                continue;
            };
            if target == module {
                continue;
            }
            let Some(target_rank) = rank(&target) else {
                continue;
            };
            if target_rank > own_rank {
                let via = if target == name {
                    String::new()
                } else {
                    format!(" (`crate::{name}` is {target}'s)")
                };
                problems.push(format!(
                    "src/{}:{line}: `{module}` imports `crate::{target}`{via}, a higher layer",
                    relative.display()
                ));
            }
        }
    }
    problems
}

#[test]
fn library_modules_import_downward_only() {
    let problems = upward_imports(&source_dir());
    assert!(
        problems.is_empty(),
        "a module imports only the modules before it in LAYERS (lowest first: {}):\n{}",
        LAYERS.join(", "),
        problems.join("\n")
    );
}

#[test]
fn every_library_module_has_a_layer() {
    let modules = top_level_modules(&source_dir());
    let listed: BTreeSet<String> = LAYERS.iter().map(|m| m.to_string()).collect();
    let missing: Vec<&String> = modules.difference(&listed).collect();
    let stale: Vec<&String> = listed.difference(&modules).collect();
    assert!(
        missing.is_empty() && stale.is_empty(),
        "LAYERS must list every module of src/ once: missing {missing:?}, not in src/ {stale:?}"
    );
    assert_eq!(listed.len(), LAYERS.len(), "LAYERS lists a module twice");
}

/// The scanner on a file that hides imports every way it handles, and on
/// text that only looks like imports.
#[test]
fn the_scanner_finds_every_form_of_import() {
    let source = r##"//! Docs naming crate::study are not code.
use crate::error::Result;
use crate::{math::Pose, model::{Model, JointKind}, kinematics};
/* block comment: crate::mpc */
fn f() -> &'static str {
    let _ = crate::dynamics::rnea;
    let _ = super::super::trajectory::Trajectory::new;
    let _ = super::sibling::item;
    let _ = 'c';
    let _ = '\'';
    let _ = r#"crate::robots in a raw string"#;
    "crate::space in a string"
}
#[cfg(test)]
mod tests {
    use crate::study::Check;
}
"##;
    let code = code_of(source);
    let names: Vec<(usize, String)> = root_references(&code, 2);
    let expected: Vec<(usize, String)> = [
        (2, "error"),
        (3, "math"),
        (3, "model"),
        (3, "kinematics"),
        (6, "dynamics"),
        (7, "trajectory"),
    ]
    .into_iter()
    .map(|(line, name)| (line, name.to_string()))
    .collect();
    assert_eq!(names, expected);
    // At depth 3, two `super::` stay inside the top-level module.
    assert!(!root_references(&code, 3)
        .iter()
        .any(|(_, name)| name == "trajectory"));
}

/// The `src/` folders of every crate of the workspace.
fn workspace_source_dirs() -> Vec<PathBuf> {
    let crates = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .canonicalize()
        .unwrap();
    let mut dirs: Vec<PathBuf> = fs::read_dir(&crates)
        .unwrap()
        .map(|entry| entry.unwrap().path().join("src"))
        .filter(|src| src.is_dir())
        .collect();
    dirs.sort();
    dirs
}

/// The line limit of a source file (docs/DEVELOPING.md, "Layout"): 400 for
/// a command of the CLI, 700 for the rest.
fn line_limit(relative: &str) -> usize {
    if relative.starts_with("armkit-cli/src/commands/") {
        400
    } else {
        700
    }
}

/// Files a reader can hold: every source file of the workspace within its
/// line limit.
#[test]
fn files_a_reader_can_hold() {
    let crates = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut problems = Vec::new();
    for src in workspace_source_dirs() {
        for file in rust_files(&src) {
            let relative = file
                .strip_prefix(crates.canonicalize().unwrap())
                .unwrap()
                .to_string_lossy()
                .replace('\\', "/");
            let lines = fs::read_to_string(&file).unwrap().lines().count();
            let limit = line_limit(&relative);
            if lines > limit {
                problems.push(format!("{relative}: {lines} lines, over {limit}"));
            }
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

/// Most production lines `ik::analytic` may hold (docs/DEVELOPING.md,
/// "Module rules"): code, doc comments and blanks, without its tests.
const ANALYTIC_IK_LINE_BUDGET: usize = 7_000;

/// The production lines of one source file: every line except those of a
/// test file (`*tests.rs`, `test_random.rs`) and of its `#[cfg(test)] mod`
/// items (inline blocks, up to the closing brace at their indentation, and
/// declarations). The file is rustfmt-formatted, so a block's brace closes
/// at the indentation it opened.
fn production_lines(path: &Path, source: &str) -> usize {
    let name = path.file_name().unwrap().to_string_lossy();
    if name.ends_with("tests.rs") || name == "test_random.rs" {
        return 0;
    }
    let lines: Vec<&str> = source.lines().collect();
    let mut count = 0;
    let mut i = 0;
    while i < lines.len() {
        if lines[i].trim() == "#[cfg(test)]" {
            let mut j = i + 1;
            while j < lines.len() && lines[j].trim_start().starts_with("#[") {
                j += 1;
            }
            let item = lines.get(j).map_or("", |l| l.trim());
            let module = ["mod ", "pub mod ", "pub(crate) mod ", "pub(super) mod "]
                .iter()
                .any(|p| item.starts_with(p));
            if module {
                if !item.ends_with(';') {
                    let indent = &lines[j][..lines[j].len() - lines[j].trim_start().len()];
                    let close = format!("{indent}}}");
                    while j < lines.len() && lines[j] != close {
                        j += 1;
                    }
                }
                i = j + 1;
                continue;
            }
        }
        count += 1;
        i += 1;
    }
    count
}

/// The analytic IK stays within its line budget (production lines, see
/// [`production_lines`]).
#[test]
fn analytic_ik_stays_within_its_line_budget() {
    let dir = source_dir().join("ik").join("analytic");
    let mut per_file: Vec<(usize, String)> = rust_files(&dir)
        .iter()
        .map(|file| {
            let source = fs::read_to_string(file).unwrap();
            let relative = file.strip_prefix(&dir).unwrap().display().to_string();
            (production_lines(file, &source), relative)
        })
        .collect();
    let total: usize = per_file.iter().map(|(n, _)| n).sum();
    per_file.sort();
    assert!(
        total < ANALYTIC_IK_LINE_BUDGET,
        "ik/analytic: {total} production lines, budget {ANALYTIC_IK_LINE_BUDGET}: {per_file:?}"
    );
    // The counter skips what it should: an inline test module and a
    // declared one.
    let sample = "fn a() {}\n#[cfg(test)]\nmod tests {\n    fn b() {\n    }\n}\n#[cfg(test)]\nmod more;\nfn c() {}\n";
    assert_eq!(production_lines(Path::new("x.rs"), sample), 2);
    assert_eq!(production_lines(Path::new("x_tests.rs"), sample), 0);
}

/// Two house rules of docs/DEVELOPING.md ("Layout") that keep a module
/// readable on its own: a module with files of its own is `foo/mod.rs`
/// (never `foo.rs` beside `foo/`), and code names what it imports (no
/// `use super::*` outside the `#[cfg(test)]` part of a file).
#[test]
fn one_submodule_convention_and_named_imports() {
    let mut problems = Vec::new();
    for src in workspace_source_dirs() {
        for file in rust_files(&src) {
            if file.with_extension("").is_dir() && file.file_name().is_some_and(|n| n != "mod.rs") {
                problems.push(format!(
                    "{}: move it to {}/mod.rs",
                    file.display(),
                    file.with_extension("").display()
                ));
            }
            let source = fs::read_to_string(&file).unwrap();
            if code_of(&source).contains("use super::*") {
                problems.push(format!(
                    "{}: `use super::*` outside #[cfg(test)]",
                    file.display()
                ));
            }
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

/// Whether a target table (`[lib]`, or one `[[bin]]`) switches its tests off.
fn tests_off(target: Option<&toml::Value>) -> bool {
    target
        .and_then(|t| t.get("test"))
        .and_then(toml::Value::as_bool)
        == Some(false)
}

/// The test binaries `cargo test --workspace` links for one crate: its
/// library's unit tests, its binaries' (where not switched off), one per
/// integration-test target under `tests/`. A crate whose library's tests are
/// off must hold no `#[cfg(test)]` code: those tests would never run.
fn test_binaries(crate_dir: &Path, problems: &mut Vec<String>) -> Vec<String> {
    let manifest: toml::Value =
        toml::from_str(&fs::read_to_string(crate_dir.join("Cargo.toml")).unwrap()).unwrap();
    let name = manifest["package"]["name"].as_str().unwrap().to_string();
    let mut binaries = Vec::new();
    let src = crate_dir.join("src");
    if src.join("lib.rs").exists() {
        if tests_off(manifest.get("lib")) {
            for file in rust_files(&src) {
                if fs::read_to_string(&file).unwrap().contains("#[cfg(test)]") {
                    problems.push(format!(
                        "{}: #[cfg(test)] in a library whose tests are off (move them to tests/)",
                        file.display()
                    ));
                }
            }
        } else {
            binaries.push(format!("{name} (lib)"));
        }
    }
    let bins = manifest.get("bin").and_then(toml::Value::as_array);
    let bin_tests_off = bins.is_some_and(|bins| bins.iter().all(|b| tests_off(Some(b))));
    if src.join("main.rs").exists() && !bin_tests_off {
        binaries.push(format!("{name} (bin)"));
    }
    if let Ok(entries) = fs::read_dir(crate_dir.join("tests")) {
        for entry in entries {
            let path = entry.unwrap().path();
            if path.extension().is_some_and(|e| e == "rs") || path.join("main.rs").exists() {
                binaries.push(format!("{name} ({})", path.display()));
            }
        }
    }
    binaries
}

/// `cargo test --workspace` links at most four test binaries (each link is
/// seconds of a 2-core machine's time; the doctests of edition 2024 merge
/// into one more), and no unit test sits where it would not run.
#[test]
fn the_workspace_links_at_most_four_test_binaries() {
    let mut problems = Vec::new();
    let binaries: Vec<String> = workspace_source_dirs()
        .iter()
        .flat_map(|src| test_binaries(src.parent().unwrap(), &mut problems))
        .collect();
    assert!(problems.is_empty(), "{}", problems.join("\n"));
    assert!(
        (3..=4).contains(&binaries.len()),
        "test binaries: {binaries:#?}"
    );
}
