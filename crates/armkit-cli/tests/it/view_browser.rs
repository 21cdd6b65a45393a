//! `armkit view` end to end, and the 3-D view checked against armkit's FK:
//! headless Chromium opens the page from `file://` offline, the page's test
//! mode (`#armkit-test`) reads every link's world transform back from the
//! three.js scene graph through `window.armkitView` at several times, and
//! they must equal armkit's forward kinematics of the same configuration to
//! 1e-9; the robot must cover pixels of the canvas; a screenshot is taken.
//!
//! Without Chromium the browser half is skipped with a message, unless
//! `ARMKIT_REQUIRE_BROWSER=1` (`scripts/browser-test.sh`, run by `.ci/run`).

use std::path::{Path, PathBuf};
use std::process::Command;

use armkit::math::Pose;
use armkit::urdf::ChainSelection;

use crate::demo_browser::{chromium, temp_dir, visit_url, CHROMIUM_FLAGS};

/// Tolerance of the page's transforms against armkit's FK: the page holds
/// 12 significant digits (crates/armkit-view/src/scene.rs).
pub const TRANSFORM_TOLERANCE: f64 = 1e-9;

fn fixture() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/data/urdf/meshbot/meshbot.urdf")
}

/// Chromium, or `None` after saying why the browser half is skipped.
pub fn browser_or_skip(what: &str) -> Option<PathBuf> {
    let browser = chromium();
    if browser.is_none() {
        assert!(
            std::env::var("ARMKIT_REQUIRE_BROWSER").is_err(),
            "ARMKIT_REQUIRE_BROWSER is set but Chromium is not installed (apt-get install chromium)"
        );
        eprintln!("Chromium not found: {what} skipped");
    }
    browser
}

/// What the page's test mode wrote into `<pre id="armkit-test-result">`.
pub fn test_result(dom: &str) -> serde_json::Value {
    let start = dom
        .rfind("<pre id=\"armkit-test-result\">")
        .unwrap_or_else(|| {
            panic!(
                "no test result in the page: {}",
                &dom[dom.len().saturating_sub(2000)..]
            )
        });
    let text = &dom[start + "<pre id=\"armkit-test-result\">".len()..];
    let text = &text[..text.find("</pre>").unwrap()];
    let text = text
        .replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&amp;", "&");
    serde_json::from_str(&text).unwrap()
}

/// Asserts that a column-major 4x4 matrix from the page equals `pose`.
pub fn assert_matches(matrix: &serde_json::Value, pose: &Pose, what: &str) {
    let m: Vec<f64> = matrix
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert_eq!(m.len(), 16, "{what}");
    let expected = pose.to_matrix4();
    for row in 0..4 {
        for col in 0..4 {
            let got = m[col * 4 + row];
            let want = expected[(row, col)];
            assert!(
                (got - want).abs() <= TRANSFORM_TOLERANCE,
                "{what}: element ({row},{col}) is {got} on the page, {want} by armkit's FK"
            );
        }
    }
}

/// Takes a screenshot of `url` into `png`; asserts a real image was written.
pub fn screenshot(browser: &Path, url: &str, png: &Path, scratch: &Path) {
    let output = Command::new(browser)
        .args(CHROMIUM_FLAGS)
        .arg("--virtual-time-budget=2000")
        .arg("--window-size=1000,800")
        .arg(format!(
            "--user-data-dir={}",
            scratch.join("profile").display()
        ))
        .arg(format!("--screenshot={}", png.display()))
        .arg(url)
        .output()
        .unwrap();
    assert!(output.status.success(), "screenshot of {url} failed");
    let bytes = std::fs::read(png).unwrap();
    assert!(
        bytes.starts_with(b"\x89PNG") && bytes.len() > 10_000,
        "{}: {} bytes",
        png.display(),
        bytes.len()
    );
}

/// Rows of the trajectory the test draws: t, pan, lift, elbow, roll.
const ROWS: [[f64; 5]; 6] = [
    [0.0, 0.0, 0.0, 0.0, 0.0],
    [0.4, 0.3, -0.4, 0.6, 0.2],
    [0.8, 0.7, -0.9, 1.3, 0.9],
    [1.2, 1.1, -0.6, 1.7, -0.4],
    [1.6, -0.5, 0.4, -1.2, 2.1],
    [2.0, -1.3, 1.1, -2.2, -2.6],
];

#[test]
fn view_of_a_urdf_with_meshes_matches_armkit_fk_in_chromium() {
    let dir = temp_dir("view-urdf");
    let csv = dir.join("motion.csv");
    let mut text = "t,q1,q2,q3,q4\n".to_string();
    for row in ROWS {
        text += &row.map(|v| v.to_string()).join(",");
        text.push('\n');
    }
    std::fs::write(&csv, text).unwrap();
    let html = dir.join("meshbot.html");
    let urdf = fixture();
    let output = Command::new(env!("CARGO_BIN_EXE_armkit"))
        .args(["view", "--tip", "tool", "--urdf"])
        .arg(&urdf)
        .arg("--package-path")
        .arg(urdf.parent().unwrap().parent().unwrap())
        .arg("--trajectory")
        .arg(&csv)
        .arg("--out")
        .arg(&html)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{stderr}");
    // The broken mesh is named, and drawn as its collision box.
    assert!(
        stderr.contains("broken.stl") && stderr.contains("bounding primitive"),
        "{stderr}"
    );
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(stdout.contains("8 links, 6 frames, 4 meshes"), "{stdout}");
    let page = std::fs::read_to_string(&html).unwrap();
    assert!(
        !page.contains("src=\"http") && !page.contains("import "),
        "offline classic scripts"
    );

    let Some(browser) = browser_or_skip("the 3-D view's browser checks") else {
        return;
    };
    let scratch = temp_dir("view-chromium");
    let url = format!("file://{}#armkit-test", html.display());
    let visit = visit_url(&browser, &url, &scratch);
    assert!(visit.page_requests.is_empty(), "{:?}", visit.page_requests);
    let result = test_result(&visit.dom);
    let pixels = result["robotPixels"].as_u64().unwrap();
    assert!(pixels > 2_000, "the robot covers {pixels} pixels");

    // armkit's FK of each link: the chain from the base link to it, with
    // the configuration's value of each joint it shares with the arm, the
    // finger's joint (off the arm's chain) at zero.
    let urdf_text = std::fs::read_to_string(&urdf).unwrap();
    let arm = ["pan", "lift", "elbow", "roll"];
    let samples = result["samples"].as_array().unwrap();
    assert_eq!(samples.len(), 4);
    let mut checked_frames = Vec::new();
    for sample in samples {
        let frame = sample["frame"].as_u64().unwrap() as usize;
        checked_frames.push(frame);
        let q: Vec<f64> = ROWS[frame][1..].to_vec();
        let page_q: Vec<f64> = sample["q"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect();
        assert_eq!(
            page_q, q,
            "frame {frame}: the page's configuration is the CSV's row"
        );
        let links = sample["links"].as_array().unwrap();
        assert_eq!(links.len(), 8);
        for link in links {
            let name = link["name"].as_str().unwrap();
            let pose = if name == "base_link" {
                Pose::identity()
            } else {
                match armkit::urdf::parse_str(
                    &urdf_text,
                    "meshbot",
                    &ChainSelection::between("base_link", name),
                ) {
                    Ok(model) => {
                        let sub_q: Vec<f64> = model
                            .joints()
                            .iter()
                            .map(|j| arm.iter().position(|a| *a == j.name).map_or(0.0, |i| q[i]))
                            .collect();
                        let mut data = armkit::Data::new(&model);
                        *armkit::forward_kinematics(&model, &mut data, &sub_q).unwrap()
                    }
                    // `camera` hangs from `upper_arm` by a fixed joint.
                    Err(_) => {
                        assert_eq!(name, "camera");
                        let model = armkit::urdf::parse_str(
                            &urdf_text,
                            "meshbot",
                            &ChainSelection::between("base_link", "upper_arm"),
                        )
                        .unwrap();
                        let mut data = armkit::Data::new(&model);
                        let upper =
                            *armkit::forward_kinematics(&model, &mut data, &q[..2]).unwrap();
                        upper * Pose::from_xyz_rpy([0.05, 0.0, 0.2], [0.0, 0.0, 1.57])
                    }
                }
            };
            assert_matches(
                &link["matrix"],
                &pose,
                &format!("frame {frame}, link `{name}`"),
            );
        }
    }
    assert_eq!(
        checked_frames,
        vec![0, 2, 4, 5],
        "several times along the motion"
    );
    let png = Path::new(env!("CARGO_TARGET_TMPDIR")).join("view-meshbot.png");
    screenshot(
        &browser,
        &format!("file://{}", html.display()),
        &png,
        &scratch,
    );
    std::fs::remove_dir_all(&dir).unwrap();
    std::fs::remove_dir_all(&scratch).unwrap();
}

#[test]
fn view_errors_name_the_option() {
    let dir = temp_dir("view-errors");
    let csv = dir.join("bad.csv");
    std::fs::write(&csv, "t,q1,q2\n0,0,0\n").unwrap();
    let run = |args: &[&str]| {
        let output = Command::new(env!("CARGO_BIN_EXE_armkit"))
            .args(args)
            .output()
            .unwrap();
        assert!(!output.status.success());
        String::from_utf8_lossy(&output.stderr).to_string()
    };
    let csv = csv.to_str().unwrap();
    let err = run(&["view", "--robot", "puma560", "--trajectory", csv]);
    assert!(
        err.contains("--trajectory") && err.contains("`q3`"),
        "{err}"
    );
    let err = run(&["view", "--robot", "puma560", "--q", "0,0"]);
    assert!(err.contains("6"), "{err}");
    std::fs::remove_dir_all(&dir).unwrap();
}
