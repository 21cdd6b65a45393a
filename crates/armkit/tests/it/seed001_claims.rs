//! Seed 001's claims as the distribution study tests them: the energy
//! claim against the move's duration (crossover, moderate speed), eq 17's
//! F at each instant at identical configurations, and unit weights giving
//! the pseudo-inverse's rates.

use armkit::redundancy::TorqueModel;
use armkit::study::{
    DistributionStudy, DurationPoint, DurationSweep, FindingStatus, InstantComparison, InstantRival,
};

fn finding<'a>(findings: &'a [armkit::study::Finding], word: &str) -> &'a armkit::study::Finding {
    findings
        .iter()
        .find(|f| f.claim.contains(word))
        .unwrap_or_else(|| panic!("no finding on {word}: {findings:#?}"))
}

/// On gantry9 the baseline wins under dynamic torques at 4 s, the
/// energy-optimal distribution from 8 s on: the crossover lies between, and
/// the slow moves where inertia adds at most 5 % to F show the paper's claim.
#[test]
fn gantry9_duration_sweep_has_a_crossover_and_a_moderate_speed() {
    let model = armkit::robots::by_name("gantry9").unwrap();
    let outcome = DistributionStudy::default().compare(&model).unwrap();
    let sweep = outcome.sweep.as_ref().unwrap();
    let durations: Vec<f64> = sweep.points.iter().map(|p| p.duration).collect();
    assert_eq!(durations, [2.0, 3.0, 4.0, 6.0, 8.0, 12.0, 16.0]);
    let at = |d: f64| sweep.points.iter().find(|p| p.duration == d).unwrap();
    assert!(at(4.0).margin(TorqueModel::Dynamic) < 0.0);
    assert!(at(8.0).margin(TorqueModel::Dynamic) > 5.0);
    // Under the load's static torques the energy-optimal run wins everywhere.
    assert!(sweep
        .points
        .iter()
        .all(|p| p.margin(TorqueModel::Static) > 0.0));
    // The 4 s point is the main run's: the same figures.
    let main = outcome
        .torque_energies
        .iter()
        .find(|e| e.name == "energy-optimal")
        .unwrap();
    assert_eq!(at(4.0).optimal_dynamic, main.dynamic_energy);
    let crossover = sweep.crossover().unwrap();
    assert!(crossover > 4.0 && crossover < 8.0, "{crossover}");
    // Inertia matters less the slower the move.
    let shares: Vec<f64> = sweep
        .points
        .iter()
        .map(DurationPoint::inertia_share)
        .collect();
    assert!(shares.windows(2).all(|w| w[1] < w[0]), "{shares:?}");
    let moderate = sweep.moderate().unwrap();
    assert!(moderate.inertia_share() <= armkit::study::MODERATE_SPEED_MARGIN);
    assert!(moderate.duration > crossover);
    let findings = outcome.findings();
    assert_eq!(
        finding(&findings, "crossover duration").status,
        FindingStatus::ReproducedWithDeviation
    );
    let moderate_finding = finding(&findings, "at moderate speed (the load's torques dominate)");
    assert_eq!(moderate_finding.status, FindingStatus::Reproduced);
    assert!(moderate_finding
        .measured
        .contains(&format!("{} s", moderate.duration)));
}

/// The crossover is interpolated between the bracketing durations, the
/// moderate speed is the first duration from which on inertia stays small,
/// and a sweep without a winning end is not reproduced.
#[test]
fn duration_sweep_logic_on_given_points() {
    // Both runs' F grows by `share` from static to dynamic torques.
    let point = |duration: f64, dynamic_margin: f64, share: f64| DurationPoint {
        duration,
        optimal_static: 1.0,
        baseline_static: 1.0 / (1.0 - dynamic_margin / 100.0),
        optimal_dynamic: 1.0 + share,
        baseline_dynamic: (1.0 + share) / (1.0 - dynamic_margin / 100.0),
    };
    let sweep = DurationSweep {
        points: vec![
            point(4.0, -1.4, 0.2),
            point(8.0, 11.0, 0.03),
            point(16.0, 11.8, 0.01),
        ],
    };
    let crossover = sweep.crossover().unwrap();
    assert!(
        (crossover - (4.0 + 4.0 * 1.4 / 12.4)).abs() < 1e-9,
        "{crossover}"
    );
    assert_eq!(sweep.moderate().unwrap().duration, 8.0);
    // A fast point between slow ones: moderate speed starts after it.
    let sweep = DurationSweep {
        points: vec![
            point(4.0, 1.0, 0.01),
            point(8.0, 2.0, 0.2),
            point(16.0, 3.0, 0.01),
        ],
    };
    assert_eq!(sweep.moderate().unwrap().duration, 16.0);
    let losing = DurationSweep {
        points: vec![point(4.0, -3.0, 0.2), point(8.0, -1.0, 0.01)],
    };
    assert!(losing.crossover().is_none());
    let findings = losing.findings();
    assert_eq!(findings[0].status, FindingStatus::NotReproduced);
    assert_eq!(findings[1].status, FindingStatus::NotReproduced);
}

/// Eq 17 at the energy-optimal run's configurations and twists gives F no
/// larger than any other distribution's at the same (q, V), strictly lower
/// for most; eq 19 with unit weights gives J^+ V to rounding, while the
/// energy weights give rates far from it.
#[test]
fn eq17_is_minimal_at_each_instant_and_unit_weights_are_the_pseudo_inverse() {
    let model = armkit::robots::by_name("gantry9").unwrap();
    let outcome = DistributionStudy::default().compare(&model).unwrap();
    let instant = outcome.instant.as_ref().unwrap();
    assert!(instant.samples >= 390, "{}", instant.samples);
    assert_eq!(instant.singular_samples, 0);
    assert_eq!(instant.rivals.len(), 3);
    for rival in &instant.rivals {
        assert_eq!(rival.lower_samples, 0, "{rival:?}");
        assert!(rival.min_ratio >= 1.0 - 1e-9, "{rival:?}");
        assert!(rival.median_ratio > 1.01, "{rival:?}");
    }
    assert!(instant.unit_weight_difference <= 1e-9, "{instant:?}");
    assert!(instant.energy_rates_difference > 0.1, "{instant:?}");
    let findings = outcome.findings();
    assert_eq!(
        finding(&findings, "at each instant").status,
        FindingStatus::Reproduced
    );
    assert_eq!(
        finding(&findings, "minimum-norm solution (the pseudo-inverse's").status,
        FindingStatus::Reproduced
    );
}

/// A rival lower at some sample, or unit-weight rates off the
/// pseudo-inverse, makes the findings not reproduced.
#[test]
fn instant_findings_fail_when_the_figures_do() {
    let rival = |lower_samples| InstantRival {
        name: "minimum-norm".into(),
        lower_samples,
        min_ratio: if lower_samples > 0 { 0.9 } else { 1.0 },
        median_ratio: 1.2,
    };
    let holds = InstantComparison {
        samples: 10,
        singular_samples: 0,
        rivals: vec![rival(0)],
        unit_weight_difference: 1e-14,
        energy_rates_difference: 0.5,
    };
    assert!(holds
        .findings()
        .iter()
        .all(|f| f.status == FindingStatus::Reproduced));
    let fails = InstantComparison {
        rivals: vec![rival(3)],
        unit_weight_difference: 1e-3,
        ..holds
    };
    assert!(fails
        .findings()
        .iter()
        .all(|f| f.status == FindingStatus::NotReproduced));
}

/// The sweep's durations are an option: sorted, `Some(vec![])` for none,
/// a non-positive one refused by name.
#[test]
fn durations_option_is_checked() {
    let model = armkit::robots::by_name("gantry9").unwrap();
    let outcome = DistributionStudy {
        durations: Some(vec![8.0, 4.0]),
        ..DistributionStudy::default()
    }
    .compare(&model)
    .unwrap();
    let durations: Vec<f64> = outcome
        .sweep
        .unwrap()
        .points
        .iter()
        .map(|p| p.duration)
        .collect();
    assert_eq!(durations, [4.0, 8.0]);
    let none = DistributionStudy {
        durations: Some(Vec::new()),
        ..DistributionStudy::default()
    }
    .compare(&model)
    .unwrap();
    assert!(none.sweep.is_none());
    let error = DistributionStudy {
        durations: Some(vec![4.0, 0.0]),
        ..DistributionStudy::default()
    }
    .compare(&model)
    .unwrap_err();
    assert!(error.to_string().contains("durations"), "{error}");
}
