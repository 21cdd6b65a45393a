//! Seed 000's claims checked as strongly as the paper states them: Table 1
//! to the printed digits, where the two-load beam bends most, and Example
//! 1's prismatic speeds.

use crate::seed000_common::{run, Example};
use armkit::beam::{
    PointLoad, SimplySupportedBeam, TwoCarriageBeam, SEED000_CARRIAGE_MASS, SEED000_GRAVITY,
    SEED000_TABLE1,
};
use armkit::mpc::PlantModel;

/// Rounded to the 4 decimals the paper prints (m).
fn printed(value: f64) -> f64 {
    (value * 1e4).round() / 1e4
}

fn gantry(gravity: f64) -> TwoCarriageBeam {
    let force = SEED000_CARRIAGE_MASS * gravity;
    TwoCarriageBeam::new(SimplySupportedBeam::seed000(), [force, force]).unwrap()
}

/// Table 1 (0.0046, 0.0056, 0.0022 m) is printed with g = 10 m/s^2 (the
/// SPEC's reading): every case rounds to the printed digits exactly. With
/// g = 9.81 cases (a) and (b) print 0.0045 and 0.0055: it does not.
#[test]
fn table1_rounds_to_the_printed_digits_with_g_10_only() {
    assert_eq!(SEED000_GRAVITY, 10.0);
    let expected = [0.0046, 0.0056, 0.0022];
    for (case, paper) in SEED000_TABLE1.iter().zip(expected) {
        assert_eq!(case.paper, paper);
        let [wa, wb] = gantry(10.0).deflections(case.positions).unwrap();
        assert_eq!(printed(wa), paper, "{}: {wa}", case.label);
        assert_eq!(printed(wb), paper, "{}: {wb}", case.label);
    }
    let with_981: Vec<f64> = SEED000_TABLE1
        .iter()
        .map(|case| printed(gantry(9.81).deflections(case.positions).unwrap()[0]))
        .collect();
    assert_eq!(with_981, [0.0045, 0.0055, 0.0022]);
}

/// The paper's Fig 5 text puts the largest deflection under the loads; for
/// two symmetric loads it is at mid-span: 0.005289 m against 0.004574 m
/// under the loads at 3.3 m from each end (g = 10), and likewise in the
/// other two cases of Table 1.
#[test]
fn two_symmetric_loads_bend_the_beam_most_at_mid_span() {
    let g = gantry(SEED000_GRAVITY);
    let beam = g.beam;
    for case in SEED000_TABLE1 {
        let loads = case.positions.map(|x| PointLoad::new(x, g.forces[0]));
        let mid = beam.deflection(beam.length() / 2.0, &loads).unwrap();
        let under = beam.deflection(case.positions[0], &loads).unwrap();
        assert!(mid > under, "{}: {mid} vs {under}", case.label);
        // Mid-span is the largest over the whole span (1 mm grid).
        for k in 0..=10_000 {
            let x = beam.length() * k as f64 / 10_000.0;
            assert!(beam.deflection(x, &loads).unwrap() <= mid + 1e-15, "{x}");
        }
        if case.positions == [3.3, 6.7] {
            assert!((mid - 0.005289).abs() < 5e-7, "{mid}");
            assert!((under - 0.004574).abs() < 5e-7, "{under}");
        }
    }
}

/// Example 1 (Fig 7): all three prismatic joints reach their 0.6 m/s limit
/// (within 1e-9 m/s) and none exceeds it, in the closed-loop run.
#[test]
fn example1_every_prismatic_joint_reaches_0_6_m_per_s() {
    let r = run(Example::LargeMove, PlantModel::Exact, 2000);
    assert!(r.converged_at.is_some());
    assert_eq!(r.prismatic, [0, 1, 2]);
    for &j in &r.prismatic {
        let peak = r.peak_speed(j);
        assert!((peak - 0.6).abs() <= 1e-9, "d{}: {peak}", j + 1);
    }
}

/// The demo's Table 1 checks: each case rounds to the printed digits (with
/// g = 10 all pass; with 9.81, which the former 4 % band let through,
/// cases a and b fail), the largest deflection lies at mid-span, and the
/// findings say so with the figures.
#[test]
fn the_beam_study_checks_the_printed_digits_and_reports_fig5_as_not_reproduced() {
    use armkit::study::{BeamTableStudy, FindingStatus, TABLE1_TOLERANCE};
    let report = BeamTableStudy::default().run().unwrap();
    assert_eq!(report.checks.len(), 4);
    assert!(report.all_passed(), "{:?}", report.checks);
    assert!(report.checks[0]
        .name
        .contains("rounds to the printed digits"));
    assert!((report.checks[0].value - 2.62e-5).abs() < 1e-7);
    assert_eq!(report.checks[0].threshold, 0.5e-4);
    let statuses: Vec<FindingStatus> = report.findings.iter().map(|f| f.status).collect();
    assert_eq!(
        statuses,
        [
            FindingStatus::Reproduced,
            FindingStatus::NotAttempted,
            FindingStatus::NotReproduced
        ]
    );
    let fig5 = &report.findings[2].measured;
    assert!(
        fig5.contains("0.005289") && fig5.contains("0.004574"),
        "{fig5}"
    );
    assert!(report.findings[0]
        .measured
        .contains("0.0045 / 0.0055 / 0.0022"));
    assert!(report.findings[1].measured.contains("-3.6 %"));

    let g981 = BeamTableStudy {
        gravity: 9.81,
        ..BeamTableStudy::default()
    };
    let rows = g981.rows().unwrap();
    assert!(rows
        .iter()
        .all(|r| r.relative_error().abs() < TABLE1_TOLERANCE));
    let report = g981.run().unwrap();
    let failed: Vec<&str> = report
        .checks
        .iter()
        .filter(|c| !c.passed())
        .map(|c| c.name.as_str())
        .collect();
    assert_eq!(failed.len(), 2, "{failed:?}");
    assert!(failed[0].contains("a=3.3") && failed[1].contains("a=4"));
    assert_eq!(report.findings[0].status, FindingStatus::NotReproduced);
}

/// The demo's Example 1 check needs every prismatic joint at 0.6 m/s: a run
/// with one joint held to 0.54 m/s fails it (the former "at least one"
/// passed), and the Fig 7d finding turns to not reproduced.
#[test]
fn example1_check_fails_when_one_prismatic_joint_stays_below_the_limit() {
    use armkit::study::FindingStatus;
    use armkit::study::Seed000Example;
    let example = Seed000Example::LargeMove;
    let run = example.run().unwrap();
    let name = "every prismatic velocity reaches 0.6 m/s without exceeding it";
    let check = |run| {
        example
            .checks(run)
            .into_iter()
            .find(|c| c.name == name)
            .unwrap()
    };
    let fig7d = |run| {
        example
            .findings(run)
            .unwrap()
            .into_iter()
            .find(|f| f.claim.contains("Fig 7d"))
            .unwrap()
            .status
    };
    assert!(check(&run).passed);
    assert_eq!(fig7d(&run), FindingStatus::ReproducedWithDeviation);
    let mut slower = run.clone();
    for s in &mut slower.samples {
        s.velocity[2] *= 0.9;
    }
    let c = check(&slower);
    assert!(!c.passed, "{}", c.detail);
    assert!(c.detail.contains("0.5400"), "{}", c.detail);
    assert_eq!(fig7d(&slower), FindingStatus::NotReproduced);
}
