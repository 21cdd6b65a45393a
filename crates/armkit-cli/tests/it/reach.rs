//! `armkit reach`: the summary, the .npz (a zip of .npy arrays, checked
//! byte by byte against the format), the SVG, and bad input.

use crate::common::*;

/// The entries of a stored zip: (name, data), read from the local headers
/// and checked against the central directory's count.
fn zip_entries(bytes: &[u8]) -> Vec<(String, Vec<u8>)> {
    let u16_at = |i: usize| u16::from_le_bytes([bytes[i], bytes[i + 1]]) as usize;
    let u32_at = |i: usize| u32::from_le_bytes(bytes[i..i + 4].try_into().unwrap()) as usize;
    let mut entries = Vec::new();
    let mut at = 0;
    while u32_at(at) == 0x0403_4b50 {
        assert_eq!(u16_at(at + 8), 0, "stored, not compressed");
        let size = u32_at(at + 18);
        assert_eq!(size, u32_at(at + 22));
        let name_len = u16_at(at + 26);
        let name = String::from_utf8(bytes[at + 30..at + 30 + name_len].to_vec()).unwrap();
        let start = at + 30 + name_len + u16_at(at + 28);
        entries.push((name, bytes[start..start + size].to_vec()));
        at = start + size;
    }
    let end = bytes.len() - 22;
    assert_eq!(u32_at(end), 0x0605_4b50);
    assert_eq!(u16_at(end + 10), entries.len());
    assert_eq!(
        u32_at(end + 16),
        at,
        "the central directory follows the files"
    );
    entries
}

/// A `.npy` file's header text and data.
fn npy(data: &[u8]) -> (String, Vec<u8>) {
    assert_eq!(&data[..8], b"\x93NUMPY\x01\x00");
    let len = u16::from_le_bytes([data[8], data[9]]) as usize;
    assert_eq!((10 + len) % 64, 0, "header padded to 64 bytes");
    let header = String::from_utf8(data[10..10 + len].to_vec()).unwrap();
    (header, data[10 + len..].to_vec())
}

#[test]
fn a_coarse_ur5_map_is_summarized_and_written_as_npz_and_svg() {
    let dir = std::env::temp_dir().join(format!("armkit-reach-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("map.npz");
    let svg = dir.join("map.svg");
    let run = armkit(&[
        "reach",
        "--robot",
        "ur5",
        "--resolution",
        "0.25",
        "--orientations",
        "20",
        "--out",
        out.to_str().unwrap(),
        "--svg",
        svg.to_str().unwrap(),
        "--json",
    ]);
    assert!(run.status.success(), "{}", stderr(&run));
    let v = json(&run);
    let dims: Vec<usize> = serde_json::from_value(v["dims"].clone()).unwrap();
    let cells = dims.iter().product::<usize>();
    assert_eq!(v["cells"], cells);
    assert_eq!(v["orientations"], 20);
    let reachable = v["reachable_cells"].as_u64().unwrap() as usize;
    assert!(reachable > 0 && reachable < cells, "{v}");
    let volume = v["reachable_volume"].as_f64().unwrap();
    assert!((volume - reachable as f64 * 0.25f64.powi(3)).abs() < 1e-9);
    assert!(v["ik_calls"].as_u64().unwrap() > 0);

    let entries = zip_entries(&std::fs::read(&out).unwrap());
    let names: Vec<&str> = entries.iter().map(|e| e.0.as_str()).collect();
    for name in [
        "reachable.npy",
        "capability.npy",
        "origin.npy",
        "orientations.npy",
    ] {
        assert!(names.contains(&name), "{names:?}");
    }
    let (header, data) = npy(&entries.iter().find(|e| e.0 == "reachable.npy").unwrap().1);
    let shape = format!("({}, {}, {}, 20)", dims[0], dims[1], dims[2]);
    assert!(
        header.contains("'descr': '|u1'") && header.contains(&shape),
        "{header}"
    );
    assert_eq!(data.len(), cells * 20);
    let bins = data.iter().filter(|&&b| b == 1).count();
    assert_eq!(bins as u64, v["reachable_bins"].as_u64().unwrap());
    let (header, data) = npy(&entries.iter().find(|e| e.0 == "capability.npy").unwrap().1);
    assert!(header.contains("'descr': '<f8'"), "{header}");
    let capability: Vec<f64> = data
        .chunks_exact(8)
        .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
        .collect();
    assert_eq!(capability.iter().filter(|&&c| c > 0.0).count(), reachable);
    // The refined boundary: a signed distance per bin, positive exactly
    // on the reachable bins, some nearer the boundary than one cell.
    let (header, boundary) = npy(&entries.iter().find(|e| e.0 == "boundary.npy").unwrap().1);
    assert!(
        header.contains("'descr': '|i1'") && header.contains(&shape),
        "{header}"
    );
    let reachable_bits = &npy(&entries.iter().find(|e| e.0 == "reachable.npy").unwrap().1).1;
    assert!(boundary
        .iter()
        .zip(reachable_bits)
        .all(|(&d, &r)| ((d as i8) > 0) == (r == 1) && (d as i8).unsigned_abs() <= 64));
    assert!(boundary.iter().any(|&d| (d as i8).unsigned_abs() < 64));
    assert_eq!(v["boundary"]["bisection"]["steps"], 6);
    let (header, spec) = npy(&entries.iter().find(|e| e.0 == "spec.npy").unwrap().1);
    let text: String = spec
        .chunks_exact(4)
        .map(|c| char::from_u32(u32::from_le_bytes(c.try_into().unwrap())).unwrap())
        .collect();
    assert!(
        header.contains(&format!("'descr': '<U{}'", text.len())),
        "{header}"
    );
    let spec: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(spec["target"], "pose");
    assert_eq!(spec["approach_directions"], 20);
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.starts_with("<svg") && text.contains("capability index"));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn arm4s_map_is_position_only_and_orientations_are_refused_saying_why() {
    let run = armkit(&["reach", "--robot", "arm4", "--resolution", "0.1", "--json"]);
    assert!(run.status.success(), "{}", stderr(&run));
    let v = json(&run);
    assert_eq!(v["target"], "position");
    assert_eq!(v["orientations"], 1);
    let reachable = v["reachable_cells"].as_u64().unwrap();
    assert!(reachable > 20, "{v}");
    assert_eq!(v["reachable_bins"], reachable);
    assert_eq!(v["mean_capability"], 1.0);
    let run = armkit(&["reach", "--robot", "arm4", "--orientations", "50"]);
    assert!(!run.status.success());
    let e = stderr(&run);
    assert!(
        e.contains("--orientations 50: `arm4` has 4 joints, fewer than the six a tool pose needs")
            && e.contains("position-only"),
        "{e}"
    );
}

#[test]
fn forward_sampling_reports_its_coverage_of_the_ik_map() {
    let run = armkit(&[
        "reach",
        "--robot",
        "ur5",
        "--resolution",
        "0.3",
        "--orientations",
        "10",
        "--builder",
        "fk-samples",
        "--samples",
        "20000",
        "--coverage",
        "--json",
    ]);
    assert!(run.status.success(), "{}", stderr(&run));
    let v = json(&run);
    assert_eq!(v["fk_samples"], 20000);
    let coverage = v["coverage"].as_f64().unwrap();
    assert!(coverage > 0.2 && coverage <= 1.0, "{v}");
}

#[test]
fn bad_resolutions_and_orientations_are_named() {
    for (flag, value, expect) in [
        ("--resolution", "0", "resolution"),
        ("--resolution", "nan", "resolution"),
        ("--orientations", "0", "zero orientations"),
        ("--resolution", "0.0001", "cells times 200 orientations"),
    ] {
        let run = armkit(&["reach", "--robot", "ur5", flag, value]);
        assert!(!run.status.success());
        assert!(
            stderr(&run).contains(expect),
            "{flag} {value}: {}",
            stderr(&run)
        );
    }
}

/// The task of `tool_poses` moved by the base `(x, y)` as JSON: the first
/// pose as `[x, y, z, qw, qx, qy, qz]`, the others as 4 x 4 rows.
fn task_json(x: f64, y: f64, far: bool) -> String {
    use armkit::math::{UnitQuaternion, Vector3};
    let model = armkit::robots::by_name("ur5").unwrap();
    let mut data = armkit::kinematics::Data::new(&model);
    let items: Vec<serde_json::Value> = [
        [0.3, -1.2, 1.4, -1.7, -1.5, 0.2],
        [0.6, -1.0, 1.2, -1.6, -1.5, 0.0],
        [0.0, -1.4, 1.6, -1.8, -1.4, 0.5],
    ]
    .iter()
    .enumerate()
    .map(|(i, q)| {
        let mut t = *armkit::kinematics::forward_kinematics(&model, &mut data, q).unwrap();
        t.translation += Vector3::new(x, y, 0.0);
        if far && i == 1 {
            t.translation.x += 4.0;
        }
        if i == 0 {
            let u = UnitQuaternion::from_matrix(&t.rotation);
            let p = t.translation;
            serde_json::json!([p.x, p.y, p.z, u.w, u.i, u.j, u.k])
        } else {
            let rows: Vec<Vec<f64>> = (0..4)
                .map(|r| {
                    (0..4)
                        .map(|c| match (r, c) {
                            (3, 3) => 1.0,
                            (3, _) => 0.0,
                            (_, 3) => t.translation[r],
                            _ => t.rotation[(r, c)],
                        })
                        .collect()
                })
                .collect();
            serde_json::json!(rows)
        }
    })
    .collect();
    serde_json::Value::Array(items).to_string()
}

#[test]
fn base_placements_find_the_known_base_and_name_an_impossible_task() {
    let dir = std::env::temp_dir().join(format!("armkit-reach-base-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let task = dir.join("task.json");
    let grid = [
        "reach",
        "--robot",
        "ur5",
        "--resolution",
        "0.1",
        "--orientations",
        "50",
        "--floor-x",
        "-0.5",
        "1.0",
        "--floor-y",
        "-1.0",
        "0.5",
        "--floor-step",
        "0.1",
        "--json",
        "--base-placements",
        task.to_str().unwrap(),
    ];
    std::fs::write(&task, task_json(0.5, -0.3, false)).unwrap();
    let run = armkit(&grid);
    assert!(run.status.success(), "{}", stderr(&run));
    let v = json(&run);
    let found = v["base_placements"].as_array().unwrap();
    assert!(
        !found.is_empty() && found.len() < 16 * 16,
        "{}",
        found.len()
    );
    assert!(
        found
            .iter()
            .any(|p| (p["x"].as_f64().unwrap() - 0.5).abs() < 1e-9
                && (p["y"].as_f64().unwrap() + 0.3).abs() < 1e-9),
        "{v}"
    );
    std::fs::write(&task, task_json(0.5, -0.3, true)).unwrap();
    let run = armkit(&grid);
    assert!(!run.status.success());
    assert!(
        stderr(&run).contains("no base placement reaches all 3 task poses"),
        "{}",
        stderr(&run)
    );
    std::fs::write(&task, "[[1, 2, 3]]").unwrap();
    let run = armkit(&grid);
    assert!(
        stderr(&run).contains("task pose 0 is neither"),
        "{}",
        stderr(&run)
    );
    std::fs::remove_dir_all(&dir).ok();
}
