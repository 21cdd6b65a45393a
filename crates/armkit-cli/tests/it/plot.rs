//! The figures: SVG text, legend headroom, CSV, degenerate data.

use armkit_cli::plot::{thinned, Figure};

#[test]
fn svg_has_the_title_labels_and_one_path_per_series() {
    let x: Vec<f64> = (0..50).map(|i| i as f64 * 0.1).collect();
    let figure = Figure::new("Joint rates", "t (s)", "rate (rad/s)", x.clone())
        .with_series("q1", x.iter().map(|t| t.sin()).collect())
        .with_series("q2", x.iter().map(|t| t.cos()).collect());
    let svg = figure.to_svg(640, 400).unwrap();
    assert!(svg.starts_with("<svg"), "{}", &svg[..40]);
    for text in ["Joint rates", "t (s)", "rate (rad/s)", "q1", "q2"] {
        assert!(svg.contains(text), "missing {text}");
    }
    assert!(svg.matches("<polyline").count() >= 2);
}

/// The height of an SVG document (its `height` attribute), px.
fn svg_height(svg: &str) -> u32 {
    let rest = svg.split("height=\"").nth(1).unwrap();
    rest.split('"').next().unwrap().parse().unwrap()
}

#[test]
fn the_legend_sits_below_the_chart_not_over_the_curves() {
    let x = vec![0.0, 1.0];
    let one = Figure::new("t", "x", "y", x.clone()).with_series("", vec![0.0, 1.0]);
    let four = (0..4).fold(Figure::new("t", "x", "y", x.clone()), |f, k| {
        f.with_series(format!("q{k}"), vec![0.0, 1.0])
    });
    // No headroom in the data's range: the same 5 % padding either way.
    let (_, plain) = one.ranges();
    let (_, legend) = four.ranges();
    assert!((plain.end - 1.05).abs() < 1e-12, "{plain:?}");
    assert_eq!(plain, legend);
    // The legend's rows are added below the chart's 400 px.
    assert_eq!(svg_height(&one.to_svg(640, 400).unwrap()), 400);
    let svg = four.to_svg(640, 400).unwrap();
    assert!(svg_height(&svg) > 400, "{}", svg_height(&svg));
    // Twenty long labels need more rows than four short ones.
    let many = (0..20).fold(Figure::new("t", "x", "y", x), |f, k| {
        f.with_series(format!("a rather long label {k}"), vec![0.0, 1.0])
    });
    assert!(svg_height(&many.to_svg(640, 400).unwrap()) > svg_height(&svg) + 100);
}

#[test]
fn limit_lines_are_dashed_lines_in_range() {
    let x: Vec<f64> = (0..20).map(f64::from).collect();
    let figure = Figure::new("rates", "t (s)", "rad/s", x.clone())
        .with_series("joint 1", x.iter().map(|t| 0.1 * t).collect())
        .with_limit("joint 1", 3.0)
        .with_limit("joint 1", -3.0)
        .with_limit("joint 1", 3.0)
        .with_limit("joint 1", f64::INFINITY);
    // Each finite limit once; the range reaches them.
    assert_eq!(figure.limits.len(), 2);
    let (_, y) = figure.ranges();
    assert!(y.start < -3.0 && y.end > 3.0, "{y:?}");
    let svg = figure.to_svg(640, 400).unwrap();
    assert!(svg.contains("limits (dashed)"));
    // One element per line, dashed by the SVG (the legend's mark is two strokes).
    assert_eq!(svg.matches("stroke-dasharray=\"10 6\"").count(), 2, "{svg}");
    assert!(!svg.contains("opacity=\"0.997\""));
    // The CSV holds the curve (the limits are the robot's).
    assert!(figure.to_csv().starts_with("t (s),joint 1\n0,0\n"));
}

#[test]
fn a_dense_curve_keeps_its_extremes_with_at_most_four_points_per_column() {
    let x: Vec<f64> = (0..10_000).map(|i| f64::from(i) * 1e-3).collect();
    let y: Vec<f64> = x.iter().map(|t| (40.0 * t).sin()).collect();
    let thin = thinned(&x, &y, 100);
    assert!(thin.len() <= 400, "{}", thin.len());
    assert!(thin.len() >= 200, "{}", thin.len());
    // The ends and the extremes are kept exactly, in order.
    assert_eq!(thin[0], (x[0], y[0]));
    assert_eq!(*thin.last().unwrap(), (x[9999], y[9999]));
    let top = thin.iter().map(|p| p.1).fold(f64::MIN, f64::max);
    let bottom = thin.iter().map(|p| p.1).fold(f64::MAX, f64::min);
    assert_eq!(top, y.iter().copied().fold(f64::MIN, f64::max));
    assert_eq!(bottom, y.iter().copied().fold(f64::MAX, f64::min));
    assert!(thin.windows(2).all(|w| w[0].0 <= w[1].0));
    // A short curve is left as it is.
    assert_eq!(thinned(&x[..50], &y[..50], 100).len(), 50);
}

#[test]
fn csv_has_a_header_and_a_row_per_sample() {
    let figure = Figure::new("t", "t (s)", "y", vec![0.0, 1.0]).with_series("a,b", vec![1.0, 2.0]);
    assert_eq!(figure.to_csv(), "t (s),\"a,b\"\n0,1\n1,2\n");
}

#[test]
fn flat_and_empty_data_still_render() {
    let flat = Figure::new("flat", "x", "y", vec![0.0, 1.0]).with_series("c", vec![2.0, 2.0]);
    assert!(flat.to_svg(300, 200).is_ok());
    let empty = Figure::new("empty", "x", "y", vec![]);
    assert!(empty.to_svg(300, 200).is_ok());
}
