//! `armkit manipulability`: singular values, singularity kind and ellipsoids.

use crate::common::*;

fn numbers(value: &serde_json::Value) -> Vec<f64> {
    serde_json::from_value(value.clone()).unwrap()
}

#[test]
fn a_puma_with_q5_zero_is_a_wrist_singularity_of_rank_five() {
    let out = armkit(&[
        "manipulability",
        "--robot",
        "puma560",
        "--q",
        "0.3,0.5,-0.4,0.2,0,0.1",
        "--json",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let v = json(&out);
    assert_eq!(v["kinds"], serde_json::json!(["wrist"]));
    assert_eq!(v["rank"], 5);
    assert_eq!(v["singular"], true);
    assert!(v["factors"]["wrist"].as_f64().unwrap().abs() < 1e-12);
    let sigma = numbers(&v["singular_values"]);
    assert!(sigma[5] < 1e-9 * sigma[0], "{sigma:?}");
}

#[test]
fn the_ellipsoids_agree_with_the_jacobian_printed_by_armkit_jacobian() {
    let q = "0.2,-0.4,1.1,0.3,0.8,-0.5";
    let out = armkit(&["manipulability", "--robot", "ur5", "--q", q, "--json"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let v = json(&out);
    assert_eq!(v["singular"], false);
    assert!(
        v["factors"].is_object(),
        "the UR family's wrist, elbow and shoulder factors"
    );
    let j: Vec<Vec<f64>> = serde_json::from_value(
        json(&armkit(&["jacobian", "--robot", "ur5", "--q", q, "--json"]))["jacobian"].clone(),
    )
    .unwrap();
    // trace(J_p J_p') = sum of the squared radii, for each three-row part.
    for (part, rows) in [
        ("translational_ellipsoid", 0..3),
        ("rotational_ellipsoid", 3..6),
    ] {
        let radii = numbers(&v[part]["radii"]);
        let trace: f64 = j[rows].iter().flatten().map(|x| x * x).sum();
        let sum: f64 = radii.iter().map(|r| r * r).sum();
        assert!(
            (trace - sum).abs() < 1e-9 * trace,
            "{part}: {trace} vs {sum}"
        );
        let volume = v[part]["volume"].as_f64().unwrap();
        assert!((volume - radii.iter().product::<f64>()).abs() < 1e-12);
    }
}

#[test]
fn a_bad_tolerance_is_an_error_naming_it() {
    let out = armkit(&[
        "manipulability",
        "--robot",
        "puma560",
        "--q",
        "0,0,0,0,0,0",
        "--tolerance",
        "0",
    ]);
    assert_eq!(out.status.code(), Some(1));
    assert!(stderr(&out).contains("tolerance"), "{}", stderr(&out));
}
