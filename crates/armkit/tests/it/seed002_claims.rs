//! Seed 002's closed-form inverse kinematics as printed (eqs 10-18, with
//! theta1 plus theta2 as one angle), its forward-kinematics example (sec 2.1) and the
//! reading of the orientation angles (eqs 20-22), as study findings.

use armkit::ik::closed_form::{Arm4Solver, RangeFilter};
use armkit::study::{ContinuousPathStudy, FindingStatus};

/// At a generic configuration of arm4, one of the 16 sign choices of eqs
/// 11, 15, 17 and 18 reproduces the pose, the configuration itself: eq
/// 11's other elbow turns theta12 and with it the tool's heading, which the
/// roll and pitch cannot undo. The 15 others miss it by far.
#[test]
fn paper_closed_form_has_one_exact_candidate_of_sixteen() {
    let model = armkit::robots::by_name("arm4").unwrap();
    let solver = Arm4Solver::new(&model).unwrap();
    let mut data = armkit::Data::new(&model);
    let q = [0.4, -1.1, 0.7, 0.5];
    let target = *armkit::forward_kinematics(&model, &mut data, &q).unwrap();
    let candidates = solver.paper_candidates(&target).unwrap();
    assert_eq!(candidates.len(), 16);
    let mut exact = Vec::new();
    for c in &candidates {
        let pose = *armkit::forward_kinematics(&model, &mut data, c).unwrap();
        let error = (pose.translation - target.translation).norm()
            + armkit::ik::orientation_error(&target.rotation, &pose.rotation).norm();
        if error < 1e-9 {
            exact.push(c.clone());
        } else {
            assert!(error > 1e-3, "{c:?}: {error}");
        }
    }
    assert_eq!(exact.len(), 1, "{exact:?}");
    let wrapped = |a: &[f64], b: &[f64]| {
        a.iter()
            .zip(b)
            .map(|(x, y)| (x - y).sin().abs().max(1.0 - (x - y).cos()))
            .fold(0.0, f64::max)
    };
    assert!(exact.iter().any(|c| wrapped(c, &q) < 1e-9), "{exact:?}");
    // The same as armkit's solver.
    let armkit = solver
        .solve_with(&target, &q, RangeFilter::IgnoreLimits)
        .unwrap();
    assert_eq!(armkit.len(), 1);
    for s in &armkit {
        assert!(exact.iter().any(|c| wrapped(c, &s.q) < 1e-9), "{s:?}");
    }
    // The DH angles of eqs 7-18: joint 2's offset is +90 deg.
    let q_home = solver.joints_from_dh_angles([0.0, 0.0, std::f64::consts::PI, 0.0]);
    assert!((q_home[1] + std::f64::consts::FRAC_PI_2).abs() < 1e-15);
    assert_eq!(solver.link2_length(), 0.20);
}

/// The arm4 scenario's study reports the closed form and the FK example
/// as reproduced findings; the Panda (not of the structure) has neither but
/// states the orientation law's deviation.
#[test]
fn seed002_study_findings_on_arm4_and_panda() {
    let model = armkit::robots::by_name("arm4").unwrap();
    let report = ContinuousPathStudy::default()
        .outcome(&model, None)
        .unwrap()
        .report();
    let find = |word: &str| {
        report
            .findings
            .iter()
            .find(|f| f.claim.contains(word))
            .unwrap_or_else(|| panic!("no finding on {word}: {:#?}", report.findings))
    };
    let ik = find("theta1 + theta2 as one angle");
    assert_eq!(ik.status, FindingStatus::Reproduced, "{ik}");
    assert!(ik.measured.contains("1 to 1 reproduce the pose"), "{ik}");
    assert!(ik.measured.contains("200 of 200; they are exactly"), "{ik}");
    let fk = find("motor angles (0, 90, 0, -90) deg");
    assert_eq!(fk.status, FindingStatus::Reproduced, "{fk}");
    assert!(fk.measured.contains("d3 = 0.2 m"), "{fk}");
}
