//! The map's grid: cubic position cells over the reach bound's box times a
//! set of tool orientations (Fibonacci approach directions times rolls).
//!
//! Frames and units: positions in the world frame (the frame of the model's
//! base transform), metres; orientations as rotation matrices of the tool
//! frame in the world frame. Cell `i` is `(ix, iy, iz)` in C order,
//! `i = (ix * ny + iy) * nz + iz` (x slowest), so a flat per-cell array
//! reshapes to NumPy's `(nx, ny, nz)`; a per-(cell, orientation) array is
//! `(nx, ny, nz, orientations)`. Orientation `k = direction * rolls + roll`.

use std::ops::Range;

use super::bound::ReachBox;
use super::directions::DirectionIndex;
use super::{MapSpec, MapTarget};
use crate::error::{Error, Result};
use crate::math::{Matrix3, Rotation3, Vector3};
use crate::model::Model;

/// Largest number of (cell, orientation) bins a map may have: each bin holds
/// two bytes, so this keeps a map under about 2 GiB and every index in `u32`.
pub const MAX_BINS: u64 = 1 << 30;

/// The grid of a reachability map: where its cells are and which tool
/// orientations each cell is tested with.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "io", derive(serde::Serialize, serde::Deserialize))]
pub struct MapLayout {
    spec: MapSpec,
    /// World-frame position of the grid's lower corner (cell 0's corner), m.
    origin: [f64; 3],
    /// Cells along x, y, z.
    dims: [usize; 3],
    /// Unit approach directions (the tool z axis), world frame.
    directions: Vec<[f64; 3]>,
    /// Per direction, the unit x axis of its zero-roll tool frame.
    reference_x: Vec<[f64; 3]>,
    /// Candidate directions per region of the sphere (rebuilt, not
    /// serialized: a layout read back scans every direction, same answers).
    #[cfg_attr(feature = "io", serde(skip))]
    index: DirectionIndex,
}

/// The `count` points of the Fibonacci lattice on the unit sphere: point `i`
/// at height `z = 1 - (2 i + 1) / count` and azimuth `i` times the golden
/// angle `pi (3 - sqrt 5)` (near-uniform: every point's Voronoi cell has
/// about the area `4 pi / count`).
pub fn fibonacci_directions(count: usize) -> Vec<[f64; 3]> {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    (0..count)
        .map(|i| {
            let z = 1.0 - (2.0 * i as f64 + 1.0) / count as f64;
            let r = (1.0 - z * z).max(0.0).sqrt();
            let (s, c) = (golden * i as f64).sin_cos();
            [r * c, r * s, z]
        })
        .collect()
}

/// The x axis of the zero-roll frame about unit `z`: world x projected
/// perpendicular to `z` (world y when `z` is within about 25 degrees of x).
fn reference_x_axis(z: &Vector3<f64>) -> Vector3<f64> {
    let e = if z.x.abs() < 0.9 {
        Vector3::x()
    } else {
        Vector3::y()
    };
    (e - z * z.dot(&e)).normalize()
}

impl MapLayout {
    /// The layout of `spec` for `model`: the box of [`ReachBox`] (the
    /// reach ball's cube for an arm on a fixed base, the rails' travel
    /// grown by the arm's reach for an arm on prismatic axes),
    /// `ceil(side / resolution)` cells along each axis, centred on it.
    ///
    /// Errors: a resolution that is not finite and > 0, zero directions or
    /// rolls, a model without a finite reach bound, or a grid of more than
    /// [`MAX_BINS`] (cell, orientation) bins (the message names the size).
    pub fn new(model: &Model, spec: &MapSpec) -> Result<MapLayout> {
        spec.validate()?;
        let bound = ReachBox::of_model(model)?;
        let (lower, upper) = (bound.lower(), bound.upper());
        let sides: [f64; 3] =
            std::array::from_fn(|a| ((upper[a] - lower[a]) / spec.resolution).ceil().max(1.0));
        let cells = sides[0] * sides[1] * sides[2];
        if !cells.is_finite() || cells * spec.orientation_count() as f64 > MAX_BINS as f64 {
            return Err(Error::invalid_argument(
                "resolution",
                format!(
                    "a grid of {} x {} x {} = {cells:e} cells times {} orientations exceeds the limit of {MAX_BINS} bins (box {:.3} x {:.3} x {:.3} m at {} m resolution): choose a coarser resolution or fewer orientations",
                    sides[0],
                    sides[1],
                    sides[2],
                    spec.orientation_count(),
                    upper[0] - lower[0],
                    upper[1] - lower[1],
                    upper[2] - lower[2],
                    spec.resolution
                ),
            ));
        }
        let dims = sides.map(|s| s as usize);
        // Centred on the box: the grid overhangs it by at most one cell.
        let origin: [f64; 3] = std::array::from_fn(|a| {
            0.5 * (lower[a] + upper[a]) - 0.5 * dims[a] as f64 * spec.resolution
        });
        let directions = fibonacci_directions(spec.approach_directions);
        let reference_x = directions
            .iter()
            .map(|d| {
                let x = reference_x_axis(&Vector3::from(*d));
                [x.x, x.y, x.z]
            })
            .collect();
        Ok(MapLayout {
            spec: spec.clone(),
            origin,
            dims,
            index: DirectionIndex::new(&directions),
            directions,
            reference_x,
        })
    }

    /// The spec the layout was made from.
    pub fn spec(&self) -> &MapSpec {
        &self.spec
    }

    /// Edge of a cubic cell, m.
    pub fn resolution(&self) -> f64 {
        self.spec.resolution
    }

    /// World-frame position of the grid's lower corner, m.
    pub fn origin(&self) -> [f64; 3] {
        self.origin
    }

    /// Cells along x, y and z.
    pub fn dims(&self) -> [usize; 3] {
        self.dims
    }

    /// Number of position cells (`nx ny nz`).
    pub fn cell_count(&self) -> usize {
        self.dims[0] * self.dims[1] * self.dims[2]
    }

    /// Number of orientations per cell (directions times rolls).
    pub fn orientation_count(&self) -> usize {
        self.spec.orientation_count()
    }

    /// Number of (cell, orientation) bins.
    pub fn bin_count(&self) -> usize {
        self.cell_count() * self.orientation_count()
    }

    /// Volume of one cell, m^3.
    pub fn cell_volume(&self) -> f64 {
        self.spec.resolution.powi(3)
    }

    /// The unit approach directions (tool z axes), world frame.
    pub fn directions(&self) -> &[[f64; 3]] {
        &self.directions
    }

    /// Checks that `cells` is a range within the layout's cells; the error
    /// names `what` (the argument) and the range.
    pub fn check_cells(&self, what: &str, cells: &Range<usize>) -> Result<()> {
        if cells.end > self.cell_count() || cells.start > cells.end {
            return Err(Error::invalid_argument(
                what,
                format!(
                    "cells {cells:?} are not within the layout's 0..{}",
                    self.cell_count()
                ),
            ));
        }
        Ok(())
    }

    /// True for a position-only map ([`MapTarget::Position`]).
    #[inline]
    pub fn position_only(&self) -> bool {
        self.spec.target == MapTarget::Position
    }

    /// `(ix, iy, iz)` of cell `i` (`i < cell_count()`).
    pub fn cell_coordinates(&self, i: usize) -> [usize; 3] {
        let [_, ny, nz] = self.dims;
        [i / (ny * nz), (i / nz) % ny, i % nz]
    }

    /// World-frame centre of cell `i`, m.
    pub fn cell_center(&self, i: usize) -> [f64; 3] {
        let c = self.cell_coordinates(i);
        let r = self.spec.resolution;
        [
            self.origin[0] + (c[0] as f64 + 0.5) * r,
            self.origin[1] + (c[1] as f64 + 0.5) * r,
            self.origin[2] + (c[2] as f64 + 0.5) * r,
        ]
    }

    /// The cell containing world-frame `position` (m), `None` outside the
    /// box or for a non-finite position.
    #[inline]
    pub fn cell_of(&self, position: [f64; 3]) -> Option<usize> {
        let r = self.spec.resolution;
        let mut index = 0usize;
        for ((&p, &o), &n) in position.iter().zip(&self.origin).zip(&self.dims) {
            let t = ((p - o) / r).floor();
            // NaN fails both comparisons and is rejected too.
            if !(t >= 0.0 && t < n as f64) {
                return None;
            }
            index = index * n + t as usize;
        }
        Some(index)
    }

    /// Tool orientation `k` in the world frame: z along direction
    /// `k / rolls`, x turned by `2 pi (k % rolls) / rolls` about z from the
    /// direction's reference x axis.
    pub fn orientation(&self, k: usize) -> Rotation3<f64> {
        let rolls = self.spec.rolls;
        let (d, r) = (k / rolls, k % rolls);
        let z = Vector3::from(self.directions[d]);
        let x0 = Vector3::from(self.reference_x[d]);
        let y0 = z.cross(&x0);
        let angle = std::f64::consts::TAU * r as f64 / rolls as f64;
        let (s, c) = angle.sin_cos();
        let x = x0 * c + y0 * s;
        let y = z.cross(&x);
        Rotation3::from_matrix_unchecked(Matrix3::from_columns(&[x, y, z]))
    }

    /// The orientation index nearest `rotation` (tool frame in the world
    /// frame): the approach direction nearest its z axis, then the roll
    /// sample nearest its x axis's angle about that direction. Allocates
    /// nothing.
    #[inline]
    pub fn orientation_of(&self, rotation: &Matrix3<f64>) -> usize {
        let z = rotation.column(2);
        let best = self.index.nearest4(&self.directions, [z[0], z[1], z[2]])[0].0;
        best * self.spec.rolls + self.roll_of(best, rotation)
    }

    /// The roll sample (0..rolls) nearest the angle of `rotation`'s x axis
    /// about direction `d`, from the direction's reference x axis.
    #[inline]
    fn roll_of(&self, d: usize, rotation: &Matrix3<f64>) -> usize {
        let rolls = self.spec.rolls;
        if rolls == 1 {
            return 0;
        }
        let z = Vector3::from(self.directions[d]);
        let x0 = Vector3::from(self.reference_x[d]);
        let y0 = z.cross(&x0);
        let x = rotation.column(0);
        let angle = x.dot(&y0).atan2(x.dot(&x0));
        let step = std::f64::consts::TAU / rolls as f64;
        let r = (angle / step).round().rem_euclid(rolls as f64) as usize;
        r.min(rolls - 1)
    }

    /// The three orientations around `rotation` with interpolation weights
    /// summing to 1: the three approach directions nearest its z axis, each
    /// weighted by how much nearer (in cosine) it is than the fourth
    /// nearest (so a weight falls to 0 as its direction leaves the three),
    /// each at its nearest roll. Allocates nothing.
    #[inline]
    pub fn orientations_around(&self, rotation: &Matrix3<f64>) -> [(usize, f64); 3] {
        let z = rotation.column(2);
        // The four largest cosines, largest first.
        let top = self.index.nearest4(&self.directions, [z[0], z[1], z[2]]);
        let floor = if top[3].1.is_finite() { top[3].1 } else { -1.0 };
        let mut weights = [0.0; 3];
        for (w, t) in weights.iter_mut().zip(&top) {
            *w = if t.1.is_finite() {
                (t.1 - floor).max(0.0)
            } else {
                0.0
            };
        }
        let total: f64 = weights.iter().sum();
        if total <= 0.0 {
            weights = [1.0, 0.0, 0.0];
        } else {
            weights.iter_mut().for_each(|w| *w /= total);
        }
        let rolls = self.spec.rolls;
        std::array::from_fn(|i| {
            let d = top[i].0.min(self.directions.len() - 1);
            (d * rolls + self.roll_of(d, rotation), weights[i])
        })
    }
}
