//! The HTML pages: one report per scenario and the index. CSS is inline;
//! figures are the report folder's own SVG files (an `<img>` each, not a
//! second copy inline), scripts the shared file beside the folders: the
//! pages open offline.

use std::path::Path;

use super::{format_value, Comparison, Report, ReportSummary};

const STYLE: &str = "body{font-family:-apple-system,Segoe UI,Helvetica,Arial,sans-serif;max-width:1100px;margin:24px auto;padding:0 16px;color:#222}
h1{font-size:1.6em;margin-bottom:0.2em}h2{font-size:1.2em;margin-top:1.6em;border-bottom:1px solid #ddd}
table{border-collapse:collapse;margin:8px 0}td,th{border:1px solid #ccc;padding:4px 8px;text-align:left;font-size:0.92em}
th{background:#f3f3f6}.pass{color:#1a7f37;font-weight:bold}.fail{color:#c62828;font-weight:bold}
.figures{display:flex;flex-wrap:wrap;gap:12px}.figure{border:1px solid #eee;padding:4px}
.figure svg,.figure img{max-width:100%;height:auto}.caption{color:#666;font-size:0.9em}.note{background:#fff8e1;padding:6px 10px;border-left:4px solid #f0b400}
footer{margin-top:2.4em;border-top:1px solid #ddd;color:#555;font-size:0.88em}footer li{margin:2px 0}
.reproduced{background:#d7f5dd}.reproduced-with-deviation{background:#fff1c2}.not-reproduced{background:#fbd5d5}.not-attempted{background:#e6e6ea}";

/// Escapes text for HTML.
pub fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

fn verdict(passed: bool) -> &'static str {
    if passed {
        "<span class=\"pass\">pass</span>"
    } else {
        "<span class=\"fail\">FAIL</span>"
    }
}

/// The seed papers, one line each: authors, title (the paper's, then its
/// English sense), and what it claims.
const SEED_PAPERS: &[(&str, &str)] = &[
    (
        "Seed 000",
        "Wang, Li, Xi, 采用预测控制的龙门架式冗余自由度机械臂轨迹规划算法 (MPC trajectory planning of a redundant gantry manipulator): a horizon MPC with joint priorities moves a 9-DOF gantry arm, whose beam bends under it, to a target within its joint position and velocity limits.",
    ),
    (
        "Seed 001",
        "Zhao, Huang, 自由度大于六的机器人速度控制的能量优化分配 (energy-optimal distribution of the velocity inputs of robots with more than six DOF): a closed form shares the joint rates of a redundant arm so that the joint power is least, below locking the extra joints.",
    ),
    (
        "Seed 002",
        "Hao, Chen, Deng, 4-DOF多功能机器人运动控制算法的研究 (motion control of a 4-DOF multi-function robot): closed-form IK and a continuous Cartesian path of polynomial segments, split adaptively until the path error is within a tolerance.",
    ),
    (
        "Seed 004",
        "Zhao, She, Huang, Huang (singularity avoidance of a space manipulator with a controlled base attitude): inside a detected singular region, IK at every k-th pose and a C2 spline keep the joint rates bounded with a small tracking error.",
    ),
];

/// Year, month, day of a count of days since 1970-01-01 (proleptic
/// Gregorian; H. Hinnant's `civil_from_days`).
pub fn civil_from_days(days: i64) -> (i64, u32, u32) {
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097);
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = (doy - (153 * mp + 2) / 5 + 1) as u32;
    let month = if mp < 10 { mp + 3 } else { mp - 9 } as u32;
    (yoe + era * 400 + i64::from(month <= 2), month, day)
}

/// The time of writing, UTC, to the minute.
fn now_utc() -> String {
    let seconds = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs() as i64);
    let (year, month, day) = civil_from_days(seconds.div_euclid(86_400));
    let minutes = seconds.rem_euclid(86_400) / 60;
    format!(
        "{year:04}-{month:02}-{day:02} {:02}:{:02} UTC",
        minutes / 60,
        minutes % 60
    )
}

/// Every page's footer: the armkit version, the date, and the seed papers.
fn footer() -> String {
    let mut out = format!(
        "<footer><p>armkit {} &middot; written {}</p>\n<p>The papers armkit implements and checks (the seeds):</p>\n<ul>\n",
        env!("CARGO_PKG_VERSION"),
        now_utc()
    );
    for (seed, line) in SEED_PAPERS {
        out += &format!("<li><b>{seed}</b>: {}</li>\n", escape(line));
    }
    out + "</ul></footer>"
}

/// A whole report page: `title`, the body's HTML, and the footer (armkit's
/// version, the date in UTC, a line on each seed paper).
pub fn page(title: &str, body: &str) -> String {
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>{}</title><style>{STYLE}\n{}</style></head>\n<body>\n<p class=\"caption\">armkit {} &middot; {}</p>\n{body}\n{}\n</body></html>\n",
        escape(title),
        armkit_view::STYLE,
        env!("CARGO_PKG_VERSION"),
        now_utc(),
        footer()
    )
}

/// The report page of one scenario; `figures` are `(file stem, title)` of
/// the SVG files written beside it.
pub fn report_page(report: &Report, figures: &[(String, String)]) -> String {
    let mut body = format!(
        "<p><a href=\"../index.html\">all scenarios</a></p>\n<h1>{}</h1>\n<p>{}</p>\n<p>Checks: {} of {} pass.</p>\n",
        escape(&report.title),
        escape(&report.description),
        report.passed(),
        report.evidence().count()
    );
    body += "<h2>Checks</h2>\n";
    body += &checks_table(report.evidence());
    let invariants: Vec<&super::Check> = report.invariants().collect();
    if !invariants.is_empty() {
        body += "<h2>Invariants of the implementation</h2>\n<p>True by construction: kept as tests of the code, never evidence for a paper's claim.</p>\n";
        body += &checks_table(invariants.into_iter());
    }
    body += &findings_table(&report.findings);
    for note in &report.notes {
        body += &format!("<p class=\"note\">{}</p>\n", escape(note));
    }
    if let Some(animation) = &report.animation {
        body += "<h2>Motion</h2>\n";
        // The 3-D view, with the stick figure's last frame as its fallback
        // image where the browser has no WebGL; the scripts are the one shared file that
        // `Report::write` puts beside the report folders.
        match animation.scene() {
            Some(Ok(scene)) => {
                body += &armkit_view::viewer_block(
                    &scene,
                    "motion",
                    Some(&animation.to_still_svg_html()),
                );
                body += &armkit_view::Scripts::Shared(format!("../{}", armkit_view::ASSET_FILE))
                    .to_html();
            }
            _ => body += &animation.to_svg_html(),
        }
    }
    for table in &report.tables {
        body += &format!("<h2>{}</h2>\n<table><tr>", escape(&table.title));
        for h in &table.header {
            body += &format!("<th>{}</th>", escape(h));
        }
        body += "</tr>\n";
        for row in &table.rows {
            body += "<tr>";
            for cell in row {
                // An empty cell is a dash: a blank reads as missing data.
                if cell.is_empty() {
                    body += "<td>&ndash;</td>";
                } else {
                    body += &format!("<td>{}</td>", escape(cell));
                }
            }
            body += "</tr>\n";
        }
        body += "</table>\n";
    }
    if !figures.is_empty() {
        body += "<h2>Figures</h2>\n<div class=\"figures\">\n";
        for (stem, title) in figures {
            body += &format!(
                "<div class=\"figure\"><img src=\"{stem}.svg\" alt=\"{}\"><p class=\"caption\">data: <a href=\"{stem}.csv\">{stem}.csv</a></p></div>\n",
                escape(title)
            );
        }
        body += "</div>\n";
    }
    body += "<p class=\"caption\">Every check is also in <a href=\"summary.json\">summary.json</a>.</p>\n";
    page(&report.title, &body)
}

/// The checks' table: name, value, threshold, unit, result.
fn checks_table<'a>(checks: impl Iterator<Item = &'a super::Check>) -> String {
    let mut body = "<table><tr><th>check</th><th>value</th><th>threshold</th><th>unit</th><th>result</th></tr>\n".to_string();
    for check in checks {
        let op = if check.comparison == Comparison::AtMost {
            "&le;"
        } else {
            "&ge;"
        };
        let (value, threshold) = if check.detail.is_empty() {
            (
                format_value(check.value),
                format!("{op} {}", format_value(check.threshold)),
            )
        } else {
            (escape(&check.detail), "holds".to_string())
        };
        body += &format!(
            "<tr><td>{}</td><td>{value}</td><td>{threshold}</td><td>{}</td><td>{}</td></tr>\n",
            escape(&check.name),
            // Dimensionless values and yes/no checks have no unit: a dash,
            // not an empty cell.
            if check.unit.is_empty() {
                "&ndash;".to_string()
            } else {
                escape(&check.unit)
            },
            verdict(check.passed())
        );
    }
    body + "</table>\n"
}

/// The papers' claims and how they fared, apart from the checks.
fn findings_table(findings: &[super::Finding]) -> String {
    if findings.is_empty() {
        return String::new();
    }
    let mut html = "<h2>The paper's claims</h2>\n<table><tr><th>claim</th><th>measured here</th><th>verdict</th></tr>\n".to_string();
    for finding in findings {
        let same = finding
            .same_evidence_as
            .as_ref()
            .map_or(String::new(), |at| {
                format!(" (same evidence as {}; not counted)", escape(at))
            });
        html += &format!(
            "<tr><td>{}</td><td>{}</td><td class=\"{}\">{}{same}</td></tr>\n",
            escape(&finding.claim),
            escape(&finding.measured),
            status_class(finding.status),
            escape(finding.status.as_str())
        );
    }
    html + "</table>\n"
}

/// The CSS class colouring a verdict.
fn status_class(status: armkit::study::FindingStatus) -> &'static str {
    use armkit::study::FindingStatus;
    match status {
        FindingStatus::Reproduced => "reproduced",
        FindingStatus::ReproducedWithDeviation => "reproduced-with-deviation",
        FindingStatus::NotReproduced => "not-reproduced",
        FindingStatus::NotAttempted => "not-attempted",
    }
}

/// The index page: one line per scenario with its pass/fail count.
pub fn index_page(summaries: &[ReportSummary], out_dir: &Path) -> String {
    let all = summaries.iter().all(ReportSummary::all_passed);
    let mut body = format!(
        "<h1>armkit demo</h1>\n<p>{} scenarios; {}.</p>\n<table><tr><th>scenario</th><th>checks</th><th>result</th><th>invariants</th><th>reproduced</th><th>with deviation</th><th>not reproduced</th><th>not attempted</th><th>same evidence (not counted)</th></tr>\n",
        summaries.len(),
        if all { "every check passes" } else { "some checks fail: see the reports" }
    );
    for s in summaries {
        let link = s
            .html
            .strip_prefix(out_dir)
            .unwrap_or(&s.html)
            .to_string_lossy()
            .replace('\\', "/");
        body += &format!(
            "<tr><td><a href=\"{}\">{}</a></td><td>{} of {} pass</td><td>{}</td><td>{} of {} hold</td>\
             <td class=\"reproduced\">{}</td><td class=\"reproduced-with-deviation\">{}</td>\
             <td class=\"not-reproduced\">{}</td><td class=\"not-attempted\">{}</td><td>{}</td></tr>\n",
            escape(&link),
            escape(&s.title),
            s.passed,
            s.total,
            verdict(s.all_passed()),
            s.invariants_held,
            s.invariants,
            s.findings.reproduced,
            s.findings.with_deviation,
            s.findings.not_reproduced,
            s.findings.not_attempted,
            s.findings.duplicates
        );
    }
    body += "</table>\n";
    page("armkit demo", &body)
}
