//! The figures: SVG text, legend headroom, CSV, degenerate data.

use armkit_cli::plot::Figure;

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

#[test]
fn the_legend_gets_headroom_above_the_curves() {
    let x = vec![0.0, 1.0];
    let one = Figure::new("t", "x", "y", x.clone()).with_series("", vec![0.0, 1.0]);
    let four = (0..4).fold(Figure::new("t", "x", "y", x), |f, k| {
        f.with_series(format!("q{k}"), vec![0.0, 1.0])
    });
    let (_, plain) = one.ranges();
    let (_, legend) = four.ranges();
    assert!((plain.end - 1.05).abs() < 1e-12, "{plain:?}");
    // The top 28 % of the plot (4 rows of 7 %) lies above the data.
    let band = (legend.end - 1.05) / (legend.end - legend.start);
    assert!((band - 0.28).abs() < 1e-12, "{legend:?}");
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
