//! SVG line plots (plotters), shared by every command that draws.
//!
//! A [`Figure`] is a titled chart of named series against one x axis; it
//! renders to an SVG string that can be written to a file or inlined in an
//! HTML report. The same data goes to CSV through [`Figure::to_csv`], so a
//! plot never shows what its CSV does not hold.

use plotters::prelude::*;

/// One named curve: `y[i]` at `x[i]`.
#[derive(Clone, Debug)]
pub struct Series {
    /// Legend label (also the CSV column header).
    pub name: String,
    /// Ordinates.
    pub y: Vec<f64>,
}

/// A line chart: several series sharing one x axis.
#[derive(Clone, Debug)]
pub struct Figure {
    /// Title above the chart.
    pub title: String,
    /// x-axis label with units, e.g. `t (s)`.
    pub x_label: String,
    /// y-axis label with units.
    pub y_label: String,
    /// Abscissae shared by every series.
    pub x: Vec<f64>,
    /// The curves.
    pub series: Vec<Series>,
}

const PALETTE: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];

impl Figure {
    /// An empty figure.
    pub fn new(
        title: impl Into<String>,
        x_label: impl Into<String>,
        y_label: impl Into<String>,
        x: Vec<f64>,
    ) -> Self {
        Figure {
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            x,
            series: Vec::new(),
        }
    }

    /// Adds a series (same length as `x`).
    pub fn with_series(mut self, name: impl Into<String>, y: Vec<f64>) -> Self {
        self.series.push(Series {
            name: name.into(),
            y,
        });
        self
    }

    /// The CSV text: header `x_label,series...`, one row per abscissa.
    pub fn to_csv(&self) -> String {
        let mut out = std::iter::once(csv_field(&self.x_label))
            .chain(self.series.iter().map(|s| csv_field(&s.name)))
            .collect::<Vec<_>>()
            .join(",");
        out.push('\n');
        for (i, x) in self.x.iter().enumerate() {
            let row: Vec<String> = std::iter::once(format!("{x}"))
                .chain(
                    self.series
                        .iter()
                        .map(|s| s.y.get(i).map_or(String::new(), |v| format!("{v}"))),
                )
                .collect();
            out += &row.join(",");
            out.push('\n');
        }
        out
    }

    /// Renders the chart as an SVG document of `width` x `height` pixels.
    pub fn to_svg(&self, width: u32, height: u32) -> Result<String, String> {
        let mut svg = String::new();
        {
            let root = SVGBackend::with_string(&mut svg, (width, height)).into_drawing_area();
            root.fill(&WHITE).map_err(|e| e.to_string())?;
            let (x_range, y_range) = self.ranges();
            let mut chart = ChartBuilder::on(&root)
                .caption(&self.title, ("sans-serif", 22))
                .margin(10)
                .x_label_area_size(48)
                .y_label_area_size(72)
                .build_cartesian_2d(x_range, y_range)
                .map_err(|e| e.to_string())?;
            chart
                .configure_mesh()
                .x_desc(self.x_label.as_str())
                .y_desc(self.y_label.as_str())
                .light_line_style(RGBColor(235, 235, 235))
                .label_style(("sans-serif", 15))
                .axis_desc_style(("sans-serif", 17))
                .draw()
                .map_err(|e| e.to_string())?;
            for (k, series) in self.series.iter().enumerate() {
                let color = PALETTE[k % PALETTE.len()];
                let points = self
                    .x
                    .iter()
                    .copied()
                    .zip(series.y.iter().copied())
                    .filter(|(x, y)| x.is_finite() && y.is_finite());
                chart
                    .draw_series(LineSeries::new(points, color.stroke_width(2)))
                    .map_err(|e| e.to_string())?
                    .label(series.name.as_str())
                    .legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(2))
                    });
            }
            if self.has_legend() {
                chart
                    .configure_series_labels()
                    .label_font(("sans-serif", 15))
                    .background_style(WHITE.mix(0.85))
                    .border_style(RGBColor(200, 200, 200))
                    .position(SeriesLabelPosition::UpperRight)
                    .draw()
                    .map_err(|e| e.to_string())?;
            }
            root.present().map_err(|e| e.to_string())?;
        }
        Ok(svg)
    }

    fn has_legend(&self) -> bool {
        self.series.len() > 1 || self.series.first().is_some_and(|s| !s.name.is_empty())
    }

    /// The axes' ranges. With a legend, the y range has headroom above the
    /// data for it (a row of about 7 % of the plot's height per series, up
    /// to half the height), so that it does not cover the curves.
    pub fn ranges(&self) -> (std::ops::Range<f64>, std::ops::Range<f64>) {
        let finite = |v: &&f64| v.is_finite();
        let (x_min, x_max) = min_max(self.x.iter().filter(finite).copied());
        let (y_min, y_max) = min_max(
            self.series
                .iter()
                .flat_map(|s| s.y.iter())
                .filter(finite)
                .copied(),
        );
        let y = padded(y_min, y_max, 0.05);
        let y = if self.has_legend() {
            let rows = (0.07 * self.series.len() as f64).min(0.5);
            y.start..y.end + (y.end - y.start) * rows / (1.0 - rows)
        } else {
            y
        };
        (padded(x_min, x_max, 0.0), y)
    }
}

fn min_max(values: impl Iterator<Item = f64>) -> (f64, f64) {
    values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    })
}

/// A non-empty range around `[lo, hi]`, widened by `margin` of its span.
fn padded(lo: f64, hi: f64, margin: f64) -> std::ops::Range<f64> {
    if !(lo.is_finite() && hi.is_finite()) {
        return 0.0..1.0;
    }
    let span = hi - lo;
    if span <= 1e-12 * lo.abs().max(1.0) {
        let pad = 0.5 * lo.abs().max(1e-3);
        return (lo - pad)..(hi + pad);
    }
    (lo - margin * span)..(hi + margin * span)
}

fn csv_field(text: &str) -> String {
    if text.contains([',', '"', '\n']) {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_string()
    }
}
