//! End to end: `armkit demo` writes the reports, and headless Chromium opens
//! the index and a report offline: the plots and the animation are there,
//! the animation's script runs, and the page asks the network for nothing.
//!
//! Chromium (Debian's `chromium`) is needed for the browser half. Without it
//! the test only checks the files, unless `ARMKIT_REQUIRE_BROWSER=1` makes its
//! absence a failure (`.ci/run` installs Chromium with
//! `scripts/install-browser.sh` and sets it).

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
    // The terminal gets a line per scenario, the index's path and a hint:
    // the details are in the reports (`--verbose` prints them).
    let stdout = String::from_utf8_lossy(&run.stdout);
    let scenarios = stdout
        .lines()
        .filter(|l| l.starts_with("  [pass] "))
        .count();
    // One line per scenario file the demo runs (`scenarios/*.toml`).
    let files = std::fs::read_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenarios"))
        .unwrap()
        .filter(|e| {
            e.as_ref()
                .is_ok_and(|e| e.path().extension().is_some_and(|x| x == "toml"))
        })
        .count();
    assert_eq!(scenarios, files, "{stdout}");
    assert!(
        stdout.lines().count() <= 20,
        "{} lines:\n{stdout}",
        stdout.lines().count()
    );
    assert!(
        stdout.contains(&format!("open {}", out.join("index.html").display())),
        "{stdout}"
    );
    // The README's claims table is the claims script's output on this run,
    // line for line (counts, verdicts and invariants in step with the
    // summaries).
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");
    let table = Command::new("python3")
        .arg(format!("{root}/scripts/claims-table.py"))
        .arg(&out)
        .output()
        .expect("python3 runs scripts/claims-table.py");
    assert!(table.status.success(), "{table:?}");
    let table = String::from_utf8(table.stdout).unwrap();
    let readme = std::fs::read_to_string(format!("{root}/README.md")).unwrap();
    let stale: Vec<&str> = table
        .lines()
        .filter(|line| !readme.lines().any(|r| r == *line))
        .collect();
    assert!(
        stale.is_empty() && readme.contains(table.trim()),
        "README.md's claims table is out of step with the demo (rerun \
         scripts/claims-table.py out and paste it); lines not in README.md:\n{}",
        stale.join("\n")
    );
    let index = out.join("index.html");
    let report = out.join("seed000-mpc-ex1/report.html");
    for path in [&index, &report] {
        assert!(path.exists(), "{} missing", path.display());
    }
    let page = std::fs::read_to_string(&report).unwrap();
    assert!(page.contains(&format!("armkit {}", env!("CARGO_PKG_VERSION"))));
    assert!(
        page.contains("<b>Seed 004</b>") && page.contains(" UTC"),
        "no footer"
    );
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
    // The figures are the report folder's SVG files, each referenced by an
    // image (not inlined a second time), each file there.
    let images: Vec<&str> = dom
        .split("<img src=\"")
        .skip(1)
        .filter_map(|rest| rest.split('"').next())
        .filter(|src| src.ends_with(".svg"))
        .collect();
    let svg_files = std::fs::read_dir(report.parent().unwrap())
        .unwrap()
        .filter(|e| {
            e.as_ref()
                .unwrap()
                .path()
                .extension()
                .is_some_and(|x| x == "svg")
        })
        .count();
    assert!(
        images.len() >= 5 && images.len() == svg_files,
        "plots missing: {images:?} of {svg_files} files"
    );
    for src in &images {
        assert!(report.with_file_name(src).is_file(), "{src} missing");
    }
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
    check_3d_views(&browser, &out, &scratch);
    std::fs::remove_dir_all(&out).unwrap();
    std::fs::remove_dir_all(&scratch).unwrap();
}

/// Every report's 3-D view, in its test mode: offline, the robot drawn, and
/// each link's world transform at four times equal to armkit's FK of the
/// page's configuration (relative to the arm's base link, which moves on the
/// space robot's reports and sits at the model's base pose on the others),
/// to 1e-9; the demo's folder stays under 20 MB; two screenshots.
fn check_3d_views(browser: &Path, out: &Path, scratch: &Path) {
    use crate::view_browser::{assert_matches, screenshot, test_result};
    let size: u64 = walk(out).iter().map(|p| p.metadata().unwrap().len()).sum();
    assert!(size < 20_000_000, "the demo's out/ is {size} bytes");
    let reports: Vec<PathBuf> = std::fs::read_dir(out)
        .unwrap()
        .map(|entry| entry.unwrap().path().join("report.html"))
        .filter(|report| {
            report.exists()
                && std::fs::read_to_string(report)
                    .unwrap()
                    .contains("class=\"armkit-view\"")
        })
        .collect();
    let views = reports.len();
    let mut slowest: f64 = 0.0;
    for (report, visit) in visit_in_parallel(browser, &reports, "#armkit-test", scratch) {
        assert!(
            visit.page_requests.is_empty(),
            "{}: {:?}",
            report.display(),
            visit.page_requests
        );
        let result = test_result(&visit.dom);
        let pixels = result["robotPixels"].as_u64().unwrap();
        assert!(
            pixels > 300,
            "{}: the robot covers {pixels} pixels",
            report.display()
        );
        slowest = slowest.max(result["firstRenderMs"].as_f64().unwrap());
        let scene_title = result["title"].as_str().unwrap().to_string();
        let model = armkit::robots::by_name(&scene_title).unwrap();
        let mut data = armkit::Data::new(&model);
        for sample in result["samples"].as_array().unwrap() {
            let q: Vec<f64> = sample["q"]
                .as_array()
                .unwrap()
                .iter()
                .map(|v| v.as_f64().unwrap())
                .collect();
            let end = *armkit::forward_kinematics(&model, &mut data, &q).unwrap();
            let mut expected = vec![*model.base()];
            expected.extend_from_slice(data.joint_frames());
            expected.push(end);
            let links = sample["links"].as_array().unwrap();
            assert_eq!(links.len(), expected.len(), "{}", report.display());
            // The page's base link: the arm's world frame in the scene.
            let page_base = matrix_pose(&links[0]["matrix"]);
            let world = page_base * model.base().inverse();
            if !scene_title.starts_with("space6r") {
                assert_matches(
                    &links[0]["matrix"],
                    model.base(),
                    &format!("{}: base", report.display()),
                );
            }
            for (link, pose) in links.iter().zip(&expected) {
                let what = format!(
                    "{}, t = {}, link `{}`",
                    report.display(),
                    sample["t"],
                    link["name"]
                );
                assert_matches(&link["matrix"], &(world * *pose), &what);
            }
        }
    }
    assert!(views >= 10, "only {views} reports have a 3-D view");
    eprintln!("3-D views: {views} reports checked; slowest first render {slowest:.0} ms; out/ {size} bytes");
    let shots = Path::new(env!("CARGO_TARGET_TMPDIR"));
    for name in ["seed000-beam", "seed004-singularity"] {
        let url = format!(
            "file://{}#armkit-view-only",
            out.join(name).join("report.html").display()
        );
        screenshot(browser, &url, &shots.join(format!("{name}.png")), scratch);
    }
}

/// Each page visited with `fragment` (as [`visit_url`]), two browsers at a
/// time (each with its own profile folder below `scratch`): a page takes
/// seconds of the browser's CPU, and the machine has two cores.
fn visit_in_parallel(
    browser: &Path,
    pages: &[PathBuf],
    fragment: &str,
    scratch: &Path,
) -> Vec<(PathBuf, PageVisit)> {
    let half = pages.len().div_ceil(2);
    std::thread::scope(|scope| {
        let workers: Vec<_> = pages
            .chunks(half.max(1))
            .enumerate()
            .map(|(worker, chunk)| {
                let own = scratch.join(format!("browser-{worker}"));
                scope.spawn(move || {
                    std::fs::create_dir_all(&own).unwrap();
                    chunk
                        .iter()
                        .map(|page| {
                            let url = format!("file://{}{fragment}", page.display());
                            (page.clone(), visit_url(browser, &url, &own))
                        })
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        workers
            .into_iter()
            .flat_map(|worker| worker.join().unwrap())
            .collect()
    })
}

/// A column-major 4x4 matrix from the page as a pose.
fn matrix_pose(matrix: &serde_json::Value) -> armkit::math::Pose {
    let m: Vec<f64> = matrix
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let m4 = nalgebra::Matrix4::from_column_slice(&m);
    armkit::math::Pose::from_matrix4(&m4).unwrap()
}

/// Every file below `dir`.
fn walk(dir: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            files.extend(walk(&path));
        } else {
            files.push(path);
        }
    }
    files
}
