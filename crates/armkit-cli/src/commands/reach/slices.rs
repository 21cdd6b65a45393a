//! The capability index's slices as one SVG: the horizontal (x-y) and the
//! vertical (x-z) plane through the grid's middle cell, cells coloured by
//! the index (white 0, dark blue 1).

use armkit::reach::ReachMap;
use plotters::prelude::*;

use crate::common::{CliError, CliResult};

/// The SVG text of the two slices of `map`'s capability index.
pub fn capability_svg(map: &ReachMap, robot: &str) -> CliResult<String> {
    let layout = map.layout();
    let [nx, ny, nz] = layout.dims();
    let (origin, r) = (layout.origin(), layout.resolution());
    let capability = map.capability();
    let index = |x: usize, y: usize, z: usize| (x * ny + y) * nz + z;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (1000, 520)).into_drawing_area();
        let fail = |e: &dyn std::fmt::Display| CliError(format!("SVG: {e}"));
        root.fill(&WHITE).map_err(|e| fail(&e))?;
        let panels = root.split_evenly((1, 2));
        let slices: [(&str, usize, usize, usize); 2] =
            [("x-y plane", 1, ny, nz / 2), ("x-z plane", 2, nz, ny / 2)];
        for (panel, (name, axis, n2, fixed)) in panels.iter().zip(slices) {
            let (lo2, label2) = if axis == 1 {
                (origin[1], "y (m)")
            } else {
                (origin[2], "z (m)")
            };
            let x_range = origin[0]..origin[0] + nx as f64 * r;
            let y_range = lo2..lo2 + n2 as f64 * r;
            let mut chart = ChartBuilder::on(panel)
                .caption(
                    format!("{robot}: capability index, {name}"),
                    ("sans-serif", 18),
                )
                .margin(10)
                .x_label_area_size(35)
                .y_label_area_size(45)
                .build_cartesian_2d(x_range, y_range)
                .map_err(|e| fail(&e))?;
            chart
                .configure_mesh()
                .x_desc("x (m)")
                .y_desc(label2)
                .disable_mesh()
                .draw()
                .map_err(|e| fail(&e))?;
            let cells = (0..nx).flat_map(|i| (0..n2).map(move |j| (i, j)));
            chart
                .draw_series(cells.filter_map(|(i, j)| {
                    let c = if axis == 1 {
                        capability[index(i, j, fixed)]
                    } else {
                        capability[index(i, fixed, j)]
                    };
                    (c > 0.0).then(|| {
                        let shade = (255.0 * (1.0 - c)) as u8;
                        let x0 = origin[0] + i as f64 * r;
                        let y0 = lo2 + j as f64 * r;
                        Rectangle::new(
                            [(x0, y0), (x0 + r, y0 + r)],
                            RGBColor(shade, shade, 255).filled(),
                        )
                    })
                }))
                .map_err(|e| fail(&e))?;
        }
        root.present().map_err(|e| fail(&e))?;
    }
    Ok(svg)
}
