//! Scenario reports: checks, tables, figures, an animation, written as CSV,
//! SVG, `summary.json` and a self-contained `report.html`.
//!
//! Every file is written atomically (a temporary file, then a rename), and
//! `report.html` is written last: an interrupted run never leaves a report
//! that looks complete.

mod animation;
pub mod html;

use std::path::{Path, PathBuf};

pub use animation::Animation;

use crate::common::CliResult;
use crate::plot::Figure;

/// One verifiable claim and how it is compared: the library's
/// ([`armkit::study`]), so that a study's checks are the report's.
pub use armkit::study::{Check, Comparison, Finding};

/// A check as `summary.json` writes it.
fn check_json(check: &Check) -> serde_json::Value {
    serde_json::json!({
        "name": check.name,
        "value": finite_or_null(check.value),
        "threshold": check.threshold,
        "comparison": check.comparison.as_str(),
        "unit": check.unit,
        "detail": check.detail,
        "pass": check.passed(),
    })
}

/// A finding as `summary.json` writes it.
fn finding_json(finding: &Finding) -> serde_json::Value {
    serde_json::json!({
        "claim": finding.claim,
        "measured": finding.measured,
        "status": finding.status.as_str(),
        "same_evidence_as": finding.same_evidence_as,
    })
}

fn finite_or_null(v: f64) -> serde_json::Value {
    if v.is_finite() {
        serde_json::json!(v)
    } else {
        serde_json::Value::Null
    }
}

/// A table of text cells with a header row.
#[derive(Clone, Debug, Default)]
pub struct Table {
    /// Caption.
    pub title: String,
    /// Column headers.
    pub header: Vec<String>,
    /// Rows of cells.
    pub rows: Vec<Vec<String>>,
}

impl Table {
    /// A table with a caption and headers.
    pub fn new(title: impl Into<String>, header: &[&str]) -> Self {
        Table {
            title: title.into(),
            header: header.iter().map(|h| h.to_string()).collect(),
            rows: Vec::new(),
        }
    }

    /// Appends a row.
    pub fn push(&mut self, row: Vec<String>) {
        self.rows.push(row);
    }

    /// The table as aligned text, for the terminal.
    pub fn to_text(&self) -> String {
        let columns = self.header.len();
        let width = |c: usize| {
            self.rows
                .iter()
                .filter_map(|r| r.get(c))
                .chain(std::iter::once(&self.header[c]))
                .map(|s| s.chars().count())
                .max()
                .unwrap_or(0)
        };
        let widths: Vec<usize> = (0..columns).map(width).collect();
        let line = |cells: &[String]| {
            cells
                .iter()
                .zip(&widths)
                // An empty cell is a dash: a blank reads as missing data.
                .map(|(c, w)| format!("{:<w$}", if c.is_empty() { "-" } else { c }))
                .collect::<Vec<_>>()
                .join("  ")
        };
        let mut out = format!("{}\n{}\n", self.title, line(&self.header));
        for row in &self.rows {
            out += &line(row);
            out.push('\n');
        }
        out
    }
}

/// What a scenario produced.
#[derive(Clone, Debug, Default)]
pub struct Report {
    /// Folder name under the output directory (letters, digits, `-`).
    pub name: String,
    /// Human title.
    pub title: String,
    /// What the scenario shows and where it comes from (seed, equations).
    pub description: String,
    /// The checks, each pass or fail: evidence and, marked
    /// [`Check::invariant`], invariants of the implementation (listed apart).
    pub checks: Vec<Check>,
    /// The papers' claims and how they fared (kept apart from the checks).
    pub findings: Vec<Finding>,
    /// Tables shown in the report and printed on the terminal.
    pub tables: Vec<Table>,
    /// Figures: (file stem, figure); each becomes `<stem>.svg` and `<stem>.csv`.
    pub figures: Vec<(String, Figure)>,
    /// Plain statements shown in the report (deviations from a paper and why).
    pub notes: Vec<String>,
    /// The robot moving along the planned motion, if any.
    pub animation: Option<Animation>,
}

/// The outcome of writing one report, for the index.
#[derive(Clone, Debug)]
pub struct ReportSummary {
    /// Folder name.
    pub name: String,
    /// Title.
    pub title: String,
    /// Number of evidence checks that passed.
    pub passed: usize,
    /// Number of evidence checks.
    pub total: usize,
    /// Number of invariants (checks true by construction) that hold.
    pub invariants_held: usize,
    /// Number of invariants.
    pub invariants: usize,
    /// The findings' counts by verdict.
    pub findings: armkit::study::FindingCounts,
    /// Path of `report.html`.
    pub html: PathBuf,
}

impl ReportSummary {
    /// True when every check passed and every invariant holds.
    pub fn all_passed(&self) -> bool {
        self.passed == self.total && self.invariants_held == self.invariants
    }
}

impl Report {
    /// A library study's report ([`armkit::study::StudyReport`]) as a
    /// scenario report: its checks and notes, one figure per series.
    pub fn from_study(
        name: impl Into<String>,
        title: impl Into<String>,
        description: impl Into<String>,
        study: armkit::study::StudyReport,
    ) -> Report {
        let figures = study
            .series
            .into_iter()
            .map(|series| {
                let mut figure =
                    Figure::new(series.title, series.x_label, series.y_label, series.x);
                for (label, values) in series.columns {
                    figure = figure.with_series(label, values);
                }
                (series.name, figure)
            })
            .collect();
        Report {
            name: name.into(),
            title: title.into(),
            description: description.into(),
            checks: study.checks,
            findings: study.findings,
            tables: Vec::new(),
            figures,
            notes: study.notes,
            animation: None,
        }
    }

    /// The checks that test a result (not the invariants).
    pub fn evidence(&self) -> impl Iterator<Item = &Check> {
        self.checks.iter().filter(|c| !c.is_invariant())
    }

    /// The invariants of the implementation (checks true by construction).
    pub fn invariants(&self) -> impl Iterator<Item = &Check> {
        self.checks.iter().filter(|c| c.is_invariant())
    }

    /// Number of evidence checks that pass.
    pub fn passed(&self) -> usize {
        self.evidence().filter(|c| c.passed()).count()
    }

    /// `summary.json`: every check with name, value, threshold and pass, the
    /// invariants apart, the findings and their counts.
    pub fn summary_json(&self) -> serde_json::Value {
        let counts = armkit::study::count_findings(&self.findings);
        serde_json::json!({
            "scenario": self.name,
            "title": self.title,
            "passed": self.passed(),
            "total": self.evidence().count(),
            "checks": self.evidence().map(check_json).collect::<Vec<_>>(),
            "invariants": self.invariants().map(check_json).collect::<Vec<_>>(),
            "findings": self.findings.iter().map(finding_json).collect::<Vec<_>>(),
            "finding_counts": {
                "reproduced": counts.reproduced,
                "reproduced_with_deviation": counts.with_deviation,
                "not_reproduced": counts.not_reproduced,
                "not_attempted": counts.not_attempted,
                "same_evidence": counts.duplicates,
            },
            "notes": self.notes,
        })
    }

    /// Writes `out_dir/<name>/`: CSV and SVG per figure, `summary.json`,
    /// then `report.html`, each atomically.
    pub fn write(&self, out_dir: &Path) -> CliResult<ReportSummary> {
        let dir = out_dir.join(&self.name);
        std::fs::create_dir_all(&dir)?;
        let mut svgs = Vec::new();
        for (stem, figure) in &self.figures {
            write_atomic(&dir.join(format!("{stem}.csv")), figure.to_csv().as_bytes())?;
            let svg = figure.to_svg(760, 420)?;
            write_atomic(&dir.join(format!("{stem}.svg")), svg.as_bytes())?;
            svgs.push((stem.clone(), figure.title.clone()));
        }
        write_atomic(
            &dir.join("summary.json"),
            serde_json::to_string_pretty(&self.summary_json())?.as_bytes(),
        )?;
        if self.animation.is_some() {
            write_viewer_asset(out_dir)?;
        }
        let html_path = dir.join("report.html");
        write_atomic(&html_path, html::report_page(self, &svgs).as_bytes())?;
        Ok(ReportSummary {
            name: self.name.clone(),
            title: self.title.clone(),
            passed: self.passed(),
            total: self.evidence().count(),
            invariants_held: self.invariants().filter(|c| c.passed()).count(),
            invariants: self.invariants().count(),
            findings: armkit::study::count_findings(&self.findings),
            html: html_path,
        })
    }

    /// The terminal summary: title, tables, checks.
    pub fn to_text(&self) -> String {
        let mut out = format!("== {} ({})\n", self.title, self.name);
        for table in &self.tables {
            out += &table.to_text();
        }
        for check in &self.checks {
            let name = if check.is_invariant() {
                format!("invariant: {}", check.name)
            } else {
                check.name.clone()
            };
            if !check.detail.is_empty() {
                out += &format!(
                    "  [{}] {}: {}\n",
                    if check.passed() { "pass" } else { "FAIL" },
                    name,
                    check.detail
                );
                continue;
            }
            out += &format!(
                "  [{}] {}: {} ({} {} {})\n",
                if check.passed() { "pass" } else { "FAIL" },
                check.name,
                format_value(check.value),
                if check.comparison == Comparison::AtMost {
                    "<="
                } else {
                    ">="
                },
                format_value(check.threshold),
                check.unit
            );
        }
        for finding in &self.findings {
            out += &format!("  {finding}\n");
        }
        for note in &self.notes {
            out += &format!("  note: {note}\n");
        }
        out
    }
}

/// A number for people: 4 significant digits, scientific when small or large.
pub fn format_value(v: f64) -> String {
    if v == 0.0 || (1e-3..1e5).contains(&v.abs()) {
        let s = format!("{v:.6}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        s.to_string()
    } else {
        format!("{v:.3e}")
    }
}

/// Writes `out_dir/index.html` linking every report with a pass/fail line.
pub fn write_index(out_dir: &Path, summaries: &[ReportSummary]) -> CliResult<PathBuf> {
    let path = out_dir.join("index.html");
    write_atomic(&path, html::index_page(summaries, out_dir).as_bytes())?;
    Ok(path)
}

/// Writes the 3-D view's shared script (three.js and armkit's viewer) and
/// three.js's licence into `out_dir`, beside the report folders, unless
/// they are there already with the same content.
fn write_viewer_asset(out_dir: &Path) -> CliResult {
    let files = [
        (armkit_view::ASSET_FILE, armkit_view::asset_script()),
        ("three.LICENSE", armkit_view::THREE_LICENSE.to_string()),
    ];
    for (name, content) in files {
        let path = out_dir.join(name);
        if std::fs::read_to_string(&path).ok().as_deref() != Some(content.as_str()) {
            write_atomic(&path, content.as_bytes())?;
        }
    }
    Ok(())
}

/// Writes `text` to `path` (a command's output file); the error names the file.
pub fn write_text(path: &Path, text: &str) -> CliResult {
    std::fs::write(path, text)
        .map_err(|e| crate::common::CliError(format!("{}: cannot write: {e}", path.display())))
}

/// Numbers joined by `, ` with `decimals` digits after the point.
pub fn join(values: &[f64], decimals: usize) -> String {
    values
        .iter()
        .map(|v| format!("{v:.decimals$}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Writes `bytes` to `path` through a temporary file in the same folder and
/// a rename, so that readers see the old file or the whole new one.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> CliResult {
    let file_name = path
        .file_name()
        .and_then(|n| n.to_str())
        .unwrap_or("output");
    let temporary = path.with_file_name(format!(".{file_name}.{}.tmp", std::process::id()));
    std::fs::write(&temporary, bytes)?;
    std::fs::rename(&temporary, path)?;
    Ok(())
}
