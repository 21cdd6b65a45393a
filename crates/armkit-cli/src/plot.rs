//! SVG line plots (plotters), shared by every command that draws.
//!
//! A [`Figure`] is a titled chart of named series against one x axis; it
//! renders to an SVG string that can be written to a file or inlined in an
//! HTML report. The same data goes to CSV through [`Figure::to_csv`], so a
//! plot never shows a curve its CSV does not hold (the dashed limit lines
//! are the robot's joint limits, which `armkit info` lists). The legend
//! sits below the chart, never over the curves; a curve keeps at most four
//! points per two pixel columns (first, lowest, highest, last), which draws
//! the same picture with far fewer coordinates.

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
    /// Horizontal limit lines `(series name, y)`: dashed, in the colour of
    /// the series of that name (grey when there is none).
    pub limits: Vec<(String, f64)>,
}

/// Font sizes of the title, tick labels, axis labels and legend (plotters
/// writes them into the SVG at 0.8 of these, in px).
const FONT_TITLE: u32 = 28;
const FONT_TICKS: u32 = 19;
const FONT_AXES: u32 = 21;
const FONT_LEGEND: u32 = 19;
/// The opacity that marks a limit line in plotters' output, replaced by a
/// dash pattern.
const DASH_MARK: f64 = 0.997;
/// Height of a legend row, px.
const LEGEND_ROW: u32 = 26;
/// Width of the y labels' area, px (the plot is the rest, less margins).
const Y_LABEL_AREA: u32 = 84;

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
            limits: Vec::new(),
        }
    }

    /// Adds a limit line at `y` for the series named `series` (a finite
    /// value; an infinite limit draws nothing). The same line twice is kept once.
    pub fn with_limit(mut self, series: impl Into<String>, y: f64) -> Self {
        let series = series.into();
        if y.is_finite() && !self.limits.iter().any(|(s, v)| *s == series && *v == y) {
            self.limits.push((series, y));
        }
        self
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

    /// Renders the chart as an SVG document `width` pixels wide: the chart
    /// `height` pixels high, the legend's rows below it.
    pub fn to_svg(&self, width: u32, height: u32) -> Result<String, String> {
        let entries = self.legend_entries();
        let (per_row, entry_width) = legend_layout(&entries, width);
        let rows = entries.len().div_ceil(per_row) as u32;
        let legend_height = if rows == 0 { 0 } else { rows * LEGEND_ROW + 8 };
        let mut svg = String::new();
        {
            let root = SVGBackend::with_string(&mut svg, (width, height + legend_height))
                .into_drawing_area();
            root.fill(&WHITE).map_err(|e| e.to_string())?;
            let (upper, lower) = root.split_vertically(height);
            let (x_range, y_range) = self.ranges();
            let mut chart = ChartBuilder::on(&upper)
                .caption(&self.title, ("sans-serif", FONT_TITLE))
                .margin(10)
                .x_label_area_size(56)
                .y_label_area_size(Y_LABEL_AREA)
                .build_cartesian_2d(x_range.clone(), y_range)
                .map_err(|e| e.to_string())?;
            chart
                .configure_mesh()
                .x_desc(self.x_label.as_str())
                .y_desc(self.y_label.as_str())
                .light_line_style(RGBColor(235, 235, 235))
                .max_light_lines(2)
                .label_style(("sans-serif", FONT_TICKS))
                .axis_desc_style(("sans-serif", FONT_AXES))
                .draw()
                .map_err(|e| e.to_string())?;
            let columns = (width.saturating_sub(Y_LABEL_AREA + 20) / 2).max(1) as usize;
            for (k, series) in self.series.iter().enumerate() {
                let points = thinned(&self.x, &series.y, columns);
                chart
                    .draw_series(LineSeries::new(
                        points,
                        PALETTE[k % PALETTE.len()].stroke_width(2),
                    ))
                    .map_err(|e| e.to_string())?;
            }
            for (name, y) in &self.limits {
                // One line each, marked by its opacity and dashed below
                // (plotters would draw a dashed line as one element per dash).
                let line = [(x_range.start, *y), (x_range.end, *y)];
                let style = self.limit_color(name).mix(DASH_MARK).stroke_width(2);
                chart
                    .draw_series(LineSeries::new(line, style))
                    .map_err(|e| e.to_string())?;
            }
            for (i, (label, color, dashed)) in entries.iter().enumerate() {
                let x = 10 + (i % per_row) as i32 * entry_width as i32;
                let y = 8 + (i / per_row) as i32 * LEGEND_ROW as i32 + LEGEND_ROW as i32 / 2;
                let style = color.stroke_width(3);
                let marks: Vec<(i32, i32)> = if *dashed {
                    vec![(x, y), (x + 10, y)]
                } else {
                    vec![(x, y), (x + 26, y)]
                };
                lower
                    .draw(&PathElement::new(marks, style))
                    .map_err(|e| e.to_string())?;
                if *dashed {
                    lower
                        .draw(&PathElement::new(vec![(x + 16, y), (x + 26, y)], style))
                        .map_err(|e| e.to_string())?;
                }
                lower
                    .draw(&Text::new(
                        label.clone(),
                        (x + 34, y - FONT_LEGEND as i32 / 2 - 1),
                        ("sans-serif", FONT_LEGEND),
                    ))
                    .map_err(|e| e.to_string())?;
            }
            root.present().map_err(|e| e.to_string())?;
        }
        Ok(svg.replace(
            &format!("opacity=\"{DASH_MARK}\""),
            "opacity=\"1\" stroke-dasharray=\"10 6\"",
        ))
    }

    /// The colour of the limit line of series `name`.
    fn limit_color(&self, name: &str) -> RGBColor {
        self.series
            .iter()
            .position(|s| s.name == name)
            .map_or(RGBColor(90, 90, 90), |k| PALETTE[k % PALETTE.len()])
    }

    /// The legend's entries: (label, colour, dashed). The curves, and one
    /// entry for the limit lines.
    fn legend_entries(&self) -> Vec<(String, RGBColor, bool)> {
        let mut entries: Vec<(String, RGBColor, bool)> = if self.has_legend() {
            self.series
                .iter()
                .enumerate()
                .map(|(k, s)| (s.name.clone(), PALETTE[k % PALETTE.len()], false))
                .collect()
        } else {
            Vec::new()
        };
        if !self.limits.is_empty() {
            entries.push(("limits (dashed)".to_string(), RGBColor(90, 90, 90), true));
        }
        entries
    }

    fn has_legend(&self) -> bool {
        self.series.len() > 1 || self.series.first().is_some_and(|s| !s.name.is_empty())
    }

    /// The axes' ranges: the data's and the limit lines', the y range
    /// padded by 5 % (the legend is below the chart: no headroom for it).
    pub fn ranges(&self) -> (std::ops::Range<f64>, std::ops::Range<f64>) {
        let finite = |v: &&f64| v.is_finite();
        let (x_min, x_max) = min_max(self.x.iter().filter(finite).copied());
        let (y_min, y_max) = min_max(
            self.series
                .iter()
                .flat_map(|s| s.y.iter())
                .chain(self.limits.iter().map(|(_, y)| y))
                .filter(finite)
                .copied(),
        );
        (padded(x_min, x_max, 0.0), padded(y_min, y_max, 0.05))
    }
}

/// Legend entries per row and each entry's width (px), from the longest label.
fn legend_layout(entries: &[(String, RGBColor, bool)], width: u32) -> (usize, u32) {
    let longest = entries
        .iter()
        .map(|(l, _, _)| l.chars().count())
        .max()
        .unwrap_or(0) as u32;
    let usable = width.saturating_sub(20).max(1);
    // About half an em per character at the size plotters writes (0.8).
    let entry = (longest * FONT_LEGEND * 9 / 20 + 52).min(usable);
    (((usable / entry) as usize).max(1), entry)
}

/// The finite points of a curve, at most four per pixel column of `columns`
/// over the x range (first, lowest, highest and last, in their order), so
/// that the drawn line is the same with far fewer coordinates.
pub fn thinned(x: &[f64], y: &[f64], columns: usize) -> Vec<(f64, f64)> {
    let points: Vec<(f64, f64)> = x
        .iter()
        .copied()
        .zip(y.iter().copied())
        .filter(|(x, y)| x.is_finite() && y.is_finite())
        .collect();
    if points.len() <= 4 * columns {
        return points;
    }
    let (lo, hi) = min_max(points.iter().map(|p| p.0));
    let column =
        |x: f64| (((x - lo) / (hi - lo)) * columns as f64).min(columns as f64 - 1.0) as usize;
    let mut out = Vec::with_capacity(4 * columns);
    let mut start = 0;
    while start < points.len() {
        let c = column(points[start].0);
        let mut end = start + 1;
        while end < points.len() && column(points[end].0) == c {
            end += 1;
        }
        let bucket = &points[start..end];
        let by_y = |a: &&(f64, f64), b: &&(f64, f64)| a.1.total_cmp(&b.1);
        let low = bucket
            .iter()
            .enumerate()
            .min_by(|a, b| by_y(&a.1, &b.1))
            .map_or(0, |p| p.0);
        let high = bucket
            .iter()
            .enumerate()
            .max_by(|a, b| by_y(&a.1, &b.1))
            .map_or(0, |p| p.0);
        let mut keep = vec![0, low, high, bucket.len() - 1];
        keep.sort_unstable();
        keep.dedup();
        out.extend(keep.into_iter().map(|i| bucket[i]));
        start = end;
    }
    out
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
