//! `armkit run SCENARIO.toml` and `armkit demo`: scenarios to reports.

use std::path::{Path, PathBuf};

use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};

use crate::common::{CliError, CliResult, Outcome};
use crate::report::{write_index, ReportSummary};
use crate::scenario::{self, Scenario};

/// The scenarios shipped in the repository's `scenarios/` folder, built into
/// the binary so that `armkit demo` runs anywhere.
pub const SHIPPED: &[(&str, &str)] = &[
    (
        "seed000-beam.toml",
        include_str!("../../../../scenarios/seed000-beam.toml"),
    ),
    (
        "seed000-mpc-ex1.toml",
        include_str!("../../../../scenarios/seed000-mpc-ex1.toml"),
    ),
    (
        "seed000-mpc-ex1-rigid-model.toml",
        include_str!("../../../../scenarios/seed000-mpc-ex1-rigid-model.toml"),
    ),
    (
        "seed000-mpc-ex1-link-error.toml",
        include_str!("../../../../scenarios/seed000-mpc-ex1-link-error.toml"),
    ),
    (
        "seed000-mpc-ex2-paper-weights.toml",
        include_str!("../../../../scenarios/seed000-mpc-ex2-paper-weights.toml"),
    ),
    (
        "seed000-mpc-ex2.toml",
        include_str!("../../../../scenarios/seed000-mpc-ex2.toml"),
    ),
    (
        "seed000-mpc-ex2-strict.toml",
        include_str!("../../../../scenarios/seed000-mpc-ex2-strict.toml"),
    ),
    (
        "seed000-mpc-ex2-precision.toml",
        include_str!("../../../../scenarios/seed000-mpc-ex2-precision.toml"),
    ),
    (
        "seed000-mpc-ex3-undamped.toml",
        include_str!("../../../../scenarios/seed000-mpc-ex3-undamped.toml"),
    ),
    (
        "seed000-mpc-ex3.toml",
        include_str!("../../../../scenarios/seed000-mpc-ex3.toml"),
    ),
    (
        "seed000-mpc-ex3-precision.toml",
        include_str!("../../../../scenarios/seed000-mpc-ex3-precision.toml"),
    ),
    (
        "seed001-energy.toml",
        include_str!("../../../../scenarios/seed001-energy.toml"),
    ),
    (
        "seed002-arm4.toml",
        include_str!("../../../../scenarios/seed002-arm4.toml"),
    ),
    (
        "seed002-panda.toml",
        include_str!("../../../../scenarios/seed002-panda.toml"),
    ),
    (
        "seed004-singularity.toml",
        include_str!("../../../../scenarios/seed004-singularity.toml"),
    ),
    (
        "seed004-space.toml",
        include_str!("../../../../scenarios/seed004-space.toml"),
    ),
];

/// Runs one scenario file and writes its report.
#[derive(Args, Debug)]
pub struct RunArgs {
    /// The scenario file (TOML).
    pub scenario: PathBuf,
    /// Output directory; the report goes to OUT/<scenario name>/.
    #[arg(long, default_value = "out")]
    pub out: PathBuf,
}

/// Runs every shipped scenario and writes out/index.html.
#[derive(Args, Debug)]
pub struct DemoArgs {
    /// Output directory.
    #[arg(long, default_value = "out")]
    pub out: PathBuf,
    /// Run the scenario files of this folder instead of the shipped ones.
    #[arg(long, value_name = "DIR")]
    pub scenarios: Option<PathBuf>,
    /// Print every scenario's tables, checks, claims and notes as it runs
    /// (by default one line per scenario; the reports hold the rest).
    #[arg(long)]
    pub verbose: bool,
}

/// How much of a scenario's report goes to the terminal.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Detail {
    /// Tables, checks, claims and notes, then the report's path.
    Full,
    /// Nothing: the caller prints a summary line.
    None,
}

/// Runs `armkit run`.
pub fn run(args: &RunArgs) -> CliResult<Outcome> {
    let scenario = scenario::load(&args.scenario)?;
    let summary = run_scenario(&scenario, &args.out, Detail::Full)?;
    Ok(outcome(&[summary]))
}

fn run_scenario(scenario: &Scenario, out: &Path, detail: Detail) -> CliResult<ReportSummary> {
    let report = scenario.run()?;
    if detail == Detail::Full {
        print!("{}", report.to_text());
    }
    let summary = report.write(out)?;
    if detail == Detail::Full {
        println!("  report: {}", summary.html.display());
    }
    Ok(summary)
}

fn outcome(summaries: &[ReportSummary]) -> Outcome {
    if summaries.iter().all(ReportSummary::all_passed) {
        Outcome::Success
    } else {
        Outcome::NotConverged
    }
}

/// Runs `armkit demo`.
pub fn demo(args: &DemoArgs) -> CliResult<Outcome> {
    let scenarios = match &args.scenarios {
        Some(dir) => load_folder(dir)?,
        None => SHIPPED
            .iter()
            .map(|(name, text)| {
                scenario::parse(text, &format!("scenarios/{name}"), Path::new("scenarios"))
            })
            .collect::<CliResult<Vec<_>>>()?,
    };
    let started = std::time::Instant::now();
    let progress = ProgressBar::new(scenarios.len() as u64);
    progress.set_style(
        ProgressStyle::with_template("{bar:30} {pos}/{len} {msg}")
            .map_err(|e| CliError(format!("progress bar: {e}")))?,
    );
    let detail = if args.verbose {
        Detail::Full
    } else {
        Detail::None
    };
    let mut summaries = Vec::new();
    for scenario in &scenarios {
        progress.set_message(scenario.name.clone());
        let summary = progress.suspend(|| run_scenario(scenario, &args.out, detail))?;
        summaries.push(summary);
        progress.inc(1);
    }
    progress.finish_and_clear();
    let index = write_index(&args.out, &summaries)?;
    println!(
        "{}{} scenarios in {:.1} s (checks pass / total; the papers' claims: reproduced, with a \
         deviation, not reproduced, not attempted):",
        if args.verbose { "\n" } else { "" },
        summaries.len(),
        started.elapsed().as_secs_f64()
    );
    for s in &summaries {
        let c = s.findings;
        let mut findings = if c.independent() + c.duplicates == 0 {
            String::new()
        } else {
            format!(
                "; claims {} / {} / {} / {}",
                c.reproduced, c.with_deviation, c.not_reproduced, c.not_attempted
            )
        };
        if c.duplicates > 0 {
            findings += &format!(" (+{} restating)", c.duplicates);
        }
        let invariants = if s.invariants == 0 {
            String::new()
        } else {
            format!("; invariants {}/{}", s.invariants_held, s.invariants)
        };
        let failed = if s.all_passed() {
            String::new()
        } else {
            format!("; see {}", s.html.display())
        };
        println!(
            "  [{}] {:<width$} checks {}/{}{invariants}{findings}{failed}",
            if s.all_passed() { "pass" } else { "FAIL" },
            s.name,
            s.passed,
            s.total,
            width = summaries.iter().map(|s| s.name.len()).max().unwrap_or(0)
        );
    }
    println!("open {}", index.display());
    if !args.verbose {
        println!(
            "(each scenario's tables, checks and notes: its report, or armkit demo --verbose)"
        );
    }
    Ok(outcome(&summaries))
}

fn load_folder(dir: &Path) -> CliResult<Vec<Scenario>> {
    let mut paths: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(|e| CliError(format!("{}: cannot read the folder: {e}", dir.display())))?
        .filter_map(|entry| entry.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    paths.sort();
    if paths.is_empty() {
        return Err(CliError(format!(
            "{}: no .toml scenario files",
            dir.display()
        )));
    }
    paths.iter().map(|p| scenario::load(p)).collect()
}
