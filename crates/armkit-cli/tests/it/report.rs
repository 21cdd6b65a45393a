//! Report pages: the footer's date and version, every file a report writes,
//! and checks that never pass on NaN.

use armkit_cli::plot::Figure;
use armkit_cli::report::html::{civil_from_days, page};
use armkit_cli::report::{write_index, Animation, Check, Finding, Report, Table};

#[test]
fn civil_dates_from_day_counts() {
    assert_eq!(civil_from_days(0), (1970, 1, 1));
    assert_eq!(civil_from_days(11_016), (2000, 2, 29));
    assert_eq!(civil_from_days(20_791), (2026, 12, 4));
    assert_eq!(civil_from_days(-1), (1969, 12, 31));
}

#[test]
fn every_page_names_the_version_the_date_and_each_seed() {
    let html = page("t", "<p>body</p>");
    assert!(html.contains(&format!("armkit {}", env!("CARGO_PKG_VERSION"))));
    assert!(html.contains(" UTC</p>"), "{html}");
    for seed in ["Seed 000", "Seed 001", "Seed 002", "Seed 004"] {
        assert!(html.contains(&format!("<b>{seed}</b>")), "{seed}");
    }
}

fn sample_report() -> Report {
    let x = vec![0.0, 1.0, 2.0];
    Report {
        name: "sample".into(),
        title: "A sample".into(),
        description: "Shows <everything> & more".into(),
        checks: vec![
            Check::at_most("error", 1e-7, 1e-6, "m"),
            Check::at_least("speed", 0.5, 0.6, "m/s"),
        ],
        tables: vec![Table {
            title: "T".into(),
            header: vec!["a".into()],
            rows: vec![vec!["1".into()]],
        }],
        figures: vec![(
            "curve".into(),
            Figure::new("Curve", "t (s)", "y", x.clone()).with_series("y", x),
        )],
        findings: vec![Finding::new(
            "seed 999: the sky is green",
            "blue",
            armkit::study::FindingStatus::NotReproduced,
        )],
        notes: vec!["a note".into()],
        animation: Some(Animation::new(
            vec![0.0, 1.0],
            vec![
                vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]],
                vec![[0.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
            ],
        )),
    }
}

#[test]
fn write_produces_every_file_and_a_summary_with_pass_and_fail() {
    let dir = std::env::temp_dir().join(format!("armkit-report-test-{}", std::process::id()));
    let summary = sample_report().write(&dir).unwrap();
    assert_eq!((summary.passed, summary.total), (1, 2));
    for file in ["curve.csv", "curve.svg", "summary.json", "report.html"] {
        assert!(dir.join("sample").join(file).exists(), "{file}");
    }
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("sample/summary.json")).unwrap())
            .unwrap();
    assert_eq!(json["checks"][0]["pass"], true);
    assert_eq!(json["checks"][1]["pass"], false);
    assert_eq!(json["findings"][0]["status"], "not reproduced");
    let html = std::fs::read_to_string(dir.join("sample/report.html")).unwrap();
    assert!(html.contains("Shows &lt;everything&gt; &amp; more"));
    assert!(html.contains("id=\"animation\""));
    // The figure is the folder's SVG file, referenced once, not a second copy inline.
    assert!(html.contains("<img src=\"curve.svg\" alt=\""), "{html}");
    let figures = &html[html.find("<h2>Figures</h2>").unwrap()..];
    let figures = &figures[..figures.find("Every check is also").unwrap()];
    assert!(!figures.contains("<svg"), "{figures}");
    assert!(
        !html.contains("src=\"http") && !html.contains("href=\"http"),
        "external resource"
    );
    let index = write_index(&dir, &[summary]).unwrap();
    let index_html = std::fs::read_to_string(index).unwrap();
    assert!(index_html.contains("sample/report.html") && index_html.contains("1 of 2"));
    assert!(
        index_html.contains("class=\"not-reproduced\">1<"),
        "findings counts in the index"
    );
    assert!(html.contains("not reproduced") && html.contains("the sky is green"));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn nan_never_passes() {
    assert!(!Check::at_most("x", f64::NAN, 1.0, "").passed());
    assert!(!Check::at_least("x", f64::NAN, 1.0, "").passed());
}
