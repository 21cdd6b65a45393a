//! End to end: `armkit demo` writes the reports, and headless Chromium opens
//! the index and a report offline: the plots and the animation are there,
//! the animation's script runs, and the page asks the network for nothing.
//!
//! Chromium (Debian's `chromium`) is needed for the browser half. Without it
//! the test only checks the files, unless `ARMKIT_REQUIRE_BROWSER=1` makes its
//! absence a failure (`scripts/browser-test.sh`, which `.ci/run` calls after
//! the README's test command, installs Chromium and runs this test so).

use std::path::{Path, PathBuf};
use std::process::Command;

pub fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("armkit-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

pub fn chromium() -> Option<PathBuf> {
    [
        "/usr/bin/chromium",
        "/usr/bin/chromium-browser",
        "/usr/bin/google-chrome",
    ]
    .iter()
    .map(PathBuf::from)
    .find(|p| p.exists())
}

/// What Chromium saw on one page: the DOM after scripts ran, and the URLs the
/// page itself requested (Chromium's own background requests excluded).
pub struct PageVisit {
    pub dom: String,
    pub page_requests: Vec<String>,
}

fn visit(browser: &Path, page: &Path, scratch: &Path) -> PageVisit {
    visit_url(browser, &format!("file://{}", page.display()), scratch)
}

/// The browser's flags: headless, offline (no background networking), and
/// WebGL through SwiftShader (software; the machine has no GPU).
pub const CHROMIUM_FLAGS: [&str; 9] = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--enable-unsafe-swiftshader",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
];

/// Opens `url` (a `file://` URL, with a fragment if any), lets its scripts
/// run for 2 s of virtual time, and returns the DOM and the page's requests.
pub fn visit_url(browser: &Path, url: &str, scratch: &Path) -> PageVisit {
    let net_log = scratch.join("netlog.json");
    let output = Command::new(browser)
        .args(CHROMIUM_FLAGS)
        .arg("--virtual-time-budget=2000")
        .arg(format!(
            "--user-data-dir={}",
            scratch.join("profile").display()
        ))
        .arg(format!("--log-net-log={}", net_log.display()))
        .arg("--dump-dom")
        .arg(url)
        .output()
        .unwrap();
    assert!(output.status.success(), "chromium failed on {url}");
    let log: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&net_log).unwrap()).unwrap();
    let start_job = log["constants"]["logEventTypes"]["URL_REQUEST_START_JOB"].clone();
    let page_requests = log["events"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|e| e["type"] == start_job)
        .filter(|e| e["params"]["initiator"] != "not an origin")
        .filter_map(|e| e["params"]["url"].as_str())
        .filter(|url| !url.starts_with("file:"))
        .map(str::to_string)
        .collect();
    PageVisit {
        dom: String::from_utf8_lossy(&output.stdout).to_string(),
        page_requests,
    }
}

#[test]
fn demo_reports_open_offline_with_plots_and_animation() {
    let out = temp_dir("demo");
    let run = Command::new(env!("CARGO_BIN_EXE_armkit"))
        .args(["demo", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "demo failed: {}",
        String::from_utf8_lossy(&run.stderr)
    );
    let index = out.join("index.html");
    let report = out.join("seed000-mpc-ex1/report.html");
    for path in [&index, &report] {
        assert!(path.exists(), "{} missing", path.display());
    }
    // Every shipped scenario's checks pass (a figure the papers' numbers do
    // not support is a note in its report, not a failing check).
    for entry in std::fs::read_dir(&out).unwrap() {
        let summary = entry.unwrap().path().join("summary.json");
        if summary.exists() {
            let json: serde_json::Value =
                serde_json::from_str(&std::fs::read_to_string(&summary).unwrap()).unwrap();
            assert_eq!(json["passed"], json["total"], "{}", summary.display());
            // Invariants are listed apart from the checks, and hold too.
            for invariant in json["invariants"].as_array().unwrap() {
                assert_eq!(
                    invariant["pass"],
                    true,
                    "{}: {invariant}",
                    summary.display()
                );
            }
            // No finding is both counted and marked as restating evidence.
            let counts = &json["finding_counts"];
            let counted: u64 = [
                "reproduced",
                "reproduced_with_deviation",
                "not_reproduced",
                "not_attempted",
                "same_evidence",
            ]
            .iter()
            .map(|k| counts[k].as_u64().unwrap())
            .sum();
            assert_eq!(
                counted as usize,
                json["findings"].as_array().unwrap().len(),
                "{}",
                summary.display()
            );
        }
    }

    let Some(browser) = chromium() else {
        assert!(
            std::env::var("ARMKIT_REQUIRE_BROWSER").is_err(),
            "ARMKIT_REQUIRE_BROWSER is set but Chromium is not installed (apt-get install chromium)"
        );
        eprintln!("Chromium not found: browser checks skipped");
        return;
    };
    let scratch = temp_dir("chromium");

    // The detector must see a request when a page makes one.
    let control = scratch.join("control.html");
    std::fs::write(
        &control,
        "<html><body><img src=\"http://armkit-control.invalid/x.png\"></body></html>",
    )
    .unwrap();
    let seen = visit(&browser, &control, &scratch);
    assert!(
        seen.page_requests
            .iter()
            .any(|u| u.contains("armkit-control.invalid")),
        "the network-request detector saw nothing on the control page: {:?}",
        seen.page_requests
    );

    let index_visit = visit(&browser, &index, &scratch);
    assert!(
        index_visit.page_requests.is_empty(),
        "{:?}",
        index_visit.page_requests
    );
    assert!(index_visit.dom.contains("seed000-mpc-ex1/report.html"));

    let report_visit = visit(&browser, &report, &scratch);
    assert!(
        report_visit.page_requests.is_empty(),
        "{:?}",
        report_visit.page_requests
    );
    let dom = &report_visit.dom;
    assert!(dom.matches("<svg").count() >= 6, "plots missing");
    assert!(dom.contains("id=\"animation\""), "animation missing");
    // The script ran: the stick figure has points and joint markers.
    let robot = dom.split("id=\"robot\"").nth(1).unwrap_or("");
    let points = robot
        .split("points=\"")
        .nth(1)
        .unwrap_or("")
        .split('"')
        .next()
        .unwrap_or("");
    assert!(
        points.split(' ').count() >= 5,
        "animation did not draw: {points:?}"
    );
    assert!(dom.contains("<circle"), "joint markers missing");
    std::fs::remove_dir_all(&out).unwrap();
    std::fs::remove_dir_all(&scratch).unwrap();
}
