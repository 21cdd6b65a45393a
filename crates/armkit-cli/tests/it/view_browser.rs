//! `armkit view` end to end, and the 3-D view checked against armkit's FK:
//! headless Chromium opens the page from `file://` offline, the page's test
//! mode (`#armkit-test`) reads every link's world transform back from the
//! three.js scene graph through `window.armkitView` at several times, and
//! they must equal armkit's forward kinematics of the same configuration to
//! 1e-9; the robot must cover pixels of the canvas; a screenshot is taken.
//!
//! Without Chromium the browser half is skipped with a message, unless
//! `ARMKIT_REQUIRE_BROWSER=1` (set by `.ci/run` once
//! `scripts/install-browser.sh` has installed Chromium).

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

    let rows: Vec<Vec<f64>> = ROWS.iter().map(|r| r[1..].to_vec()).collect();
    let arm = ["pan", "lift", "elbow", "roll"];
    let checked_frames = check_urdf_page(&result, &urdf, "base_link", &arm, &rows);
    assert_eq!(result["samples"][0]["links"].as_array().unwrap().len(), 8);
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

/// armkit's FK of each URDF link drawn on the page: the chain from `base` to
/// that link (`ChainSelection::between`), with each of its joints at the
/// configuration's value of the same-named joint of `arm` (zero for joints
/// off the arm's chain); a link joined to its parent by a fixed joint with
/// no moving joint above is the parent's pose times the joint's origin. Each
/// sampled frame's configuration must be `rows[frame]`. Returns the frames
/// checked.
fn check_urdf_page(
    result: &serde_json::Value,
    urdf: &Path,
    base: &str,
    arm: &[&str],
    rows: &[Vec<f64>],
) -> Vec<usize> {
    let text = std::fs::read_to_string(urdf).unwrap();
    let mut checked = Vec::new();
    for sample in result["samples"].as_array().unwrap() {
        let frame = sample["frame"].as_u64().unwrap() as usize;
        checked.push(frame);
        let q = &rows[frame];
        let page_q: Vec<f64> = sample["q"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect();
        assert_eq!(
            &page_q, q,
            "frame {frame}: the page's configuration is the motion's"
        );
        for link in sample["links"].as_array().unwrap() {
            let name = link["name"].as_str().unwrap();
            let pose = link_pose(&text, base, name, arm, q);
            let what = format!("{}: frame {frame}, link `{name}`", urdf.display());
            assert_matches(&link["matrix"], &pose, &what);
        }
    }
    checked
}

/// A link's world pose by armkit's FK (see [`check_urdf_page`]).
fn link_pose(text: &str, base: &str, link: &str, arm: &[&str], q: &[f64]) -> Pose {
    if link == base {
        return Pose::identity();
    }
    match armkit::urdf::parse_str(text, "urdf", &ChainSelection::between(base, link)) {
        Ok(model) => {
            let sub_q: Vec<f64> = model
                .joints()
                .iter()
                .map(|j| arm.iter().position(|a| *a == j.name).map_or(0.0, |i| q[i]))
                .collect();
            let mut data = armkit::Data::new(&model);
            *armkit::forward_kinematics(&model, &mut data, &sub_q).unwrap()
        }
        // No moving joint above: the parent's pose times the fixed joint's
        // origin (read here with its own small parse of the joint element).
        Err(_) => {
            let (parent, origin) = fixed_parent(text, link);
            link_pose(text, base, &parent, arm, q) * origin
        }
    }
}

/// The parent link and origin of the fixed joint whose child is `link`.
fn fixed_parent(text: &str, link: &str) -> (String, Pose) {
    let child = format!("<child link=\"{link}\"");
    let at = text
        .find(&child)
        .unwrap_or_else(|| panic!("no joint has child `{link}`"));
    let start = text[..at].rfind("<joint").unwrap();
    let end = at + text[at..].find("</joint>").unwrap();
    let joint = &text[start..end];
    assert!(joint.contains("type=\"fixed\""), "{joint}");
    let attribute = |element: &str, name: &str| -> Option<String> {
        let e = &joint[joint.find(&format!("<{element} "))?..];
        let e = &e[..e.find('>')?];
        let v = &e[e.find(&format!("{name}=\""))? + name.len() + 2..];
        Some(v[..v.find('"')?].to_string())
    };
    let numbers = |s: Option<String>| -> [f64; 3] {
        let v: Vec<f64> = s
            .map(|s| s.split_whitespace().map(|x| x.parse().unwrap()).collect())
            .unwrap_or_else(|| vec![0.0; 3]);
        [v[0], v[1], v[2]]
    };
    let parent = attribute("parent", "link").unwrap();
    let origin = Pose::from_xyz_rpy(
        numbers(attribute("origin", "xyz")),
        numbers(attribute("origin", "rpy")),
    );
    (parent, origin)
}

/// example-robot-data's UR5 and Panda with their Collada meshes, where
/// `ARMKIT_EXAMPLE_ROBOT_DATA` names the `share` folder holding
/// `example-robot-data` (the peers' environment, `../shared/peers/setup.sh`);
/// skipped with a message otherwise.
#[test]
fn view_of_example_robot_data_ur5_and_panda_matches_armkit_fk_in_chromium() {
    let Ok(share) = std::env::var("ARMKIT_EXAMPLE_ROBOT_DATA") else {
        eprintln!("ARMKIT_EXAMPLE_ROBOT_DATA not set: the UR5 and Panda views are not checked");
        return;
    };
    let Some(browser) = browser_or_skip("the UR5 and Panda views") else {
        return;
    };
    let share = PathBuf::from(share);
    let robots = share.join("example-robot-data/robots");
    let ur5 = [
        "shoulder_pan_joint",
        "shoulder_lift_joint",
        "elbow_joint",
        "wrist_1_joint",
        "wrist_2_joint",
        "wrist_3_joint",
    ];
    let panda = [
        "panda_joint1",
        "panda_joint2",
        "panda_joint3",
        "panda_joint4",
        "panda_joint5",
        "panda_joint6",
        "panda_joint7",
    ];
    let cases: [(&str, &str, &str, &[&str]); 2] = [
        (
            "ur_description/urdf/ur5_robot.urdf",
            "base_link",
            "tool0",
            &ur5,
        ),
        (
            "panda_description/urdf/panda.urdf",
            "panda_link0",
            "panda_link8",
            &panda,
        ),
    ];
    let dir = temp_dir("view-erd");
    let scratch = temp_dir("view-erd-chromium");
    for (file, base, tip, arm) in cases {
        let urdf = robots.join(file);
        // Within both robots' limits: small alternating angles.
        let rows: Vec<Vec<f64>> = (0..5)
            .map(|k| {
                (0..arm.len())
                    .map(|j| 0.25 * k as f64 * if j % 2 == 0 { 1.0 } else { -0.5 })
                    .collect()
            })
            .collect();
        let header: Vec<String> = (1..=arm.len()).map(|j| format!("q{j}")).collect();
        let mut csv = format!("t,{}\n", header.join(","));
        for (k, row) in rows.iter().enumerate() {
            let cells: Vec<String> = row.iter().map(f64::to_string).collect();
            csv += &format!("{},{}\n", 0.5 * k as f64, cells.join(","));
        }
        let csv_path = dir.join("motion.csv");
        std::fs::write(&csv_path, csv).unwrap();
        let html = dir.join(format!("{tip}.html"));
        let output = Command::new(env!("CARGO_BIN_EXE_armkit"))
            .args(["view", "--base", base, "--tip", tip, "--urdf"])
            .arg(&urdf)
            .arg("--package-path")
            .arg(&share)
            .arg("--trajectory")
            .arg(&csv_path)
            .arg("--out")
            .arg(&html)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(output.status.success(), "{}: {stderr}", urdf.display());
        assert!(
            !stderr.contains("bounding primitive"),
            "{}: {stderr}",
            urdf.display()
        );
        let url = format!("file://{}#armkit-test", html.display());
        let visit = visit_url(&browser, &url, &scratch);
        assert!(visit.page_requests.is_empty(), "{:?}", visit.page_requests);
        let result = test_result(&visit.dom);
        let pixels = result["robotPixels"].as_u64().unwrap();
        assert!(pixels > 2_000, "{}: {pixels} pixels", urdf.display());
        assert_eq!(check_urdf_page(&result, &urdf, base, arm, &rows).len(), 4);
        let png = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("view-{tip}.png"));
        let url = format!("file://{}#armkit-view-only", html.display());
        screenshot(&browser, &url, &png, &scratch);
    }
    std::fs::remove_dir_all(&dir).unwrap();
    std::fs::remove_dir_all(&scratch).unwrap();
}
