//! The merged map and its queries.

use super::nearest::nearest_sites;
use super::{ChunkResult, MapLayout};
use crate::error::{Error, Result};
use crate::math::Pose;

/// Units of the stored boundary distance per cell edge: 64, the crossing
/// of 6 bisection steps ([`ReachMap::boundary`]).
pub const BOUNDARY_UNITS: i8 = 64;

/// A reachability map: per (cell, orientation) bin reachable or not, its
/// IK solution count and its signed distance to the boundary, per cell the
/// capability index and best manipulability (see the module docs for
/// frames and units).
///
/// Arrays are flat in the layout's C order: per cell `(nx, ny, nz)`, per bin
/// `(nx, ny, nz, orientations)`.
#[derive(Clone, Debug, PartialEq)]
pub struct ReachMap {
    layout: MapLayout,
    reachable: Vec<u8>,
    solutions: Vec<u8>,
    capability: Vec<f64>,
    manipulability: Vec<f64>,
    /// Per bin, the signed distance to the boundary (see `boundary()`).
    boundary: Vec<i8>,
    /// Per cell, the nearest cell with capability > 0 (`u32::MAX`: none).
    nearest: Vec<u32>,
    calls: u64,
}

/// A zeroed vector of `len` entries, or an error naming the size when the
/// memory cannot be had (never an allocation abort).
fn zeroed<T: Clone + Default>(what: &str, len: usize) -> Result<Vec<T>> {
    let mut v = Vec::new();
    v.try_reserve_exact(len).map_err(|_| {
        Error::invalid_argument(
            what,
            format!(
                "cannot allocate {len} entries of {} bytes for the map",
                std::mem::size_of::<T>()
            ),
        )
    })?;
    v.resize(len, T::default());
    Ok(v)
}

fn mismatch(what: &str, expected: usize, got: usize) -> Error {
    Error::invalid_argument(
        "chunks",
        format!("a chunk's `{what}` holds {got} values where its range needs {expected}"),
    )
}

impl ReachMap {
    /// An empty map of `layout` (every bin unreachable), to merge into.
    fn empty(layout: MapLayout) -> Result<ReachMap> {
        let (cells, bins) = (layout.cell_count(), layout.bin_count());
        Ok(ReachMap {
            reachable: zeroed("reachable", bins)?,
            solutions: zeroed("solutions", bins)?,
            capability: Vec::new(),
            manipulability: zeroed("manipulability", cells)?,
            boundary: Vec::new(),
            nearest: Vec::new(),
            calls: 0,
            layout,
        })
    }

    /// Adds one chunk's bins (order-independent: chunks of the IK builder
    /// cover disjoint cells, the sampling builder's hits are a union with
    /// the best manipulability kept).
    fn merge(&mut self, chunk: &ChunkResult) -> Result<()> {
        let orientations = self.layout.orientation_count();
        let cells = chunk.cells.clone();
        self.layout.check_cells("chunks", &cells)?;
        let bins = cells.len() * orientations;
        if chunk.reachable.len() != bins {
            return Err(mismatch("reachable", bins, chunk.reachable.len()));
        }
        if chunk.solutions.len() != bins {
            return Err(mismatch("solutions", bins, chunk.solutions.len()));
        }
        if chunk.manipulability.len() != cells.len() {
            return Err(mismatch(
                "manipulability",
                cells.len(),
                chunk.manipulability.len(),
            ));
        }
        if chunk.hit_manipulability.len() != chunk.hits.len() {
            return Err(mismatch(
                "hit_manipulability",
                chunk.hits.len(),
                chunk.hit_manipulability.len(),
            ));
        }
        let first = cells.start * orientations;
        for (i, (&r, &s)) in chunk.reachable.iter().zip(&chunk.solutions).enumerate() {
            self.reachable[first + i] |= (r != 0) as u8;
            self.solutions[first + i] = self.solutions[first + i].max(s);
        }
        for (i, &m) in chunk.manipulability.iter().enumerate() {
            let cell = &mut self.manipulability[cells.start + i];
            *cell = cell.max(m);
        }
        for (&bin, &m) in chunk.hits.iter().zip(&chunk.hit_manipulability) {
            let bin = usize::try_from(bin)
                .ok()
                .filter(|&b| b < self.reachable.len())
                .ok_or_else(|| {
                    Error::invalid_argument(
                        "chunks",
                        format!(
                            "a hit bin {bin} is beyond the layout's {} bins",
                            self.reachable.len()
                        ),
                    )
                })?;
            self.reachable[bin] = 1;
            let cell = &mut self.manipulability[bin / orientations];
            *cell = cell.max(m);
        }
        self.calls += chunk.calls;
        Ok(())
    }

    /// The capability index and the nearest-reachable table, once merged.
    fn finish(mut self) -> Result<ReachMap> {
        let orientations = self.layout.orientation_count();
        let mut capability = zeroed::<f64>("capability", self.layout.cell_count())?;
        for (c, bins) in capability
            .iter_mut()
            .zip(self.reachable.chunks_exact(orientations))
        {
            let hit: usize = bins.iter().map(|&b| b as usize).sum();
            *c = hit as f64 / orientations as f64;
        }
        self.nearest = nearest_sites(self.layout.dims(), &capability)?;
        self.capability = capability;
        let mut boundary = zeroed::<i8>("boundary", self.reachable.len())?;
        for (d, &b) in boundary.iter_mut().zip(&self.reachable) {
            *d = if b != 0 {
                BOUNDARY_UNITS
            } else {
                -BOUNDARY_UNITS
            };
        }
        self.boundary = boundary;
        Ok(self)
    }

    /// The map with `boundary` (as [`ReachMap::boundary`] returns it: one
    /// value per bin, positive exactly where the bin is reachable, at most
    /// [`BOUNDARY_UNITS`] in magnitude) in place of its own: a refined map
    /// read back, or [`super::refine`]'s result. Errors name the first bin
    /// that does not fit.
    pub fn with_boundary(mut self, boundary: Vec<i8>) -> Result<ReachMap> {
        if boundary.len() != self.reachable.len() {
            return Err(Error::invalid_argument(
                "boundary",
                format!(
                    "holds {} values where the map has {} bins",
                    boundary.len(),
                    self.reachable.len()
                ),
            ));
        }
        let bad = boundary.iter().zip(&self.reachable).position(|(&d, &b)| {
            (d > 0) != (b != 0) || d == 0 || d.unsigned_abs() > BOUNDARY_UNITS as u8
        });
        if let Some(bin) = bad {
            return Err(Error::invalid_argument(
                "boundary",
                format!(
                    "bin {bin} holds {} for a bin that is {}: a value is 1 to {BOUNDARY_UNITS} where the bin is reachable, -1 to -{BOUNDARY_UNITS} where not",
                    boundary[bin],
                    if self.reachable[bin] != 0 { "reachable" } else { "unreachable" }
                ),
            ));
        }
        self.boundary = boundary;
        Ok(self)
    }

    /// Adds `calls` IK solves (the refinement's) to the build's count.
    pub(crate) fn add_calls(&mut self, calls: u64) {
        self.calls += calls;
    }

    /// Merges chunk results (in any order) into a map; bins no chunk covers
    /// stay unreachable. Errors: a chunk whose arrays do not fit the layout,
    /// or a map too large for memory (named, never an allocation abort).
    pub fn from_chunks(
        layout: MapLayout,
        chunks: impl IntoIterator<Item = ChunkResult>,
    ) -> Result<ReachMap> {
        let mut map = ReachMap::empty(layout)?;
        for chunk in chunks {
            map.merge(&chunk)?;
        }
        map.finish()
    }

    /// Merges results as they arrive (the local build's streaming merge).
    pub(crate) fn from_results(
        layout: MapLayout,
        chunks: impl IntoIterator<Item = Result<ChunkResult>>,
    ) -> Result<ReachMap> {
        let mut map = ReachMap::empty(layout)?;
        for chunk in chunks {
            map.merge(&chunk?)?;
        }
        map.finish()
    }

    /// The map's layout.
    pub fn layout(&self) -> &MapLayout {
        &self.layout
    }

    /// Per bin (`cell * orientations + k`): 1 reachable, 0 not.
    pub fn reachable(&self) -> &[u8] {
        &self.reachable
    }

    /// Per bin: distinct IK solutions within the limits (0 for maps built
    /// by sampling; 1 per reachable bin on the automatic solver's route).
    pub fn solutions(&self) -> &[u8] {
        &self.solutions
    }

    /// Per cell: the capability index, the reachable fraction of its
    /// orientations, in [0, 1].
    pub fn capability(&self) -> &[f64] {
        &self.capability
    }

    /// Per cell: the best manipulability over its reachable bins (0 where none).
    pub fn manipulability(&self) -> &[f64] {
        &self.manipulability
    }

    /// Per bin: the signed distance from the bin's cell centre to the
    /// boundary of the bin's orientation, in units of 1/[`BOUNDARY_UNITS`]
    /// of the resolution, positive where the bin is reachable: along each
    /// axis the nearer crossing `d_a` on the edges to the two neighbours
    /// (found by [`super::refine`]; none: no term), combined as the
    /// distance to the plane through them, `1 / sqrt(sum 1 / d_a^2)`, at
    /// most one cell. A map without refinement holds +-[`BOUNDARY_UNITS`]
    /// (one cell: the boundary halfway between disagreeing centres, as the
    /// interpolation of the bits puts it).
    pub fn boundary(&self) -> &[i8] {
        &self.boundary
    }

    /// IK solves (or samples) the build took, the refinement's included.
    pub fn calls(&self) -> u64 {
        self.calls
    }

    /// Number of cells with capability > 0.
    pub fn reachable_cells(&self) -> usize {
        self.capability.iter().filter(|&&c| c > 0.0).count()
    }

    /// Number of reachable bins.
    pub fn reachable_bins(&self) -> usize {
        self.reachable.iter().filter(|&&b| b != 0).count()
    }

    /// Volume of the cells with capability > 0, m^3.
    pub fn reachable_volume(&self) -> f64 {
        self.reachable_cells() as f64 * self.layout.cell_volume()
    }

    /// The fraction of `reference`'s reachable bins this map also has
    /// reachable (a sampled map's coverage against an IK map of the same
    /// layout); 1 when `reference` has none. Errors: different layouts.
    pub fn coverage_of(&self, reference: &ReachMap) -> Result<f64> {
        if self.reachable.len() != reference.reachable.len()
            || self.layout.dims() != reference.layout.dims()
        {
            return Err(Error::invalid_argument(
                "reference",
                "maps of different layouts cannot be compared bin by bin",
            ));
        }
        let (mut both, mut total) = (0usize, 0usize);
        for (&a, &b) in self.reachable.iter().zip(&reference.reachable) {
            total += (b != 0) as usize;
            both += (a != 0 && b != 0) as usize;
        }
        Ok(if total == 0 {
            1.0
        } else {
            both as f64 / total as f64
        })
    }

    /// True when `pose` (world frame, m) is reachable by the map: the
    /// interpolation of the bins' signed boundary distances
    /// ([`ReachMap::boundary`]) over the three orientations around its
    /// rotation ([`MapLayout::orientations_around`]; a position-only map's
    /// one) and, trilinearly, the 8 cell centres around its position (cells
    /// beyond the box count as one cell outside) is at least 0. Without
    /// refinement this is the interpolation of the reachable bits at least
    /// 1/2: a boundary piecewise linear between the centres, not the
    /// cells' staircase. With it, near the boundary the interpolated
    /// distance is zero where the bisection put the crossing (exactly for
    /// a locally planar boundary). Allocates nothing.
    #[inline]
    pub fn query(&self, pose: &Pose) -> bool {
        let p = pose.translation;
        let (origin, dims, r) = (
            self.layout.origin(),
            self.layout.dims(),
            self.layout.resolution(),
        );
        let mut base = [0i64; 3];
        let mut frac = [0.0f64; 3];
        for (axis, (b, fr)) in base.iter_mut().zip(&mut frac).enumerate() {
            // Coordinates in cell units from cell 0's centre.
            let t = (p[axis] - origin[axis]) / r - 0.5;
            if !(t > -1.0 && t < dims[axis] as f64) {
                return false;
            }
            let f = t.floor();
            *b = f as i64;
            *fr = t - f;
        }
        let orientations = self.layout.orientation_count();
        let around = if self.layout.position_only() {
            [(0, 1.0), (0, 0.0), (0, 0.0)]
        } else {
            self.layout.orientations_around(&pose.rotation)
        };
        let mut sum = 0.0;
        for corner in 0..8 {
            let mut weight = 1.0;
            let mut cell = 0usize;
            let mut inside = true;
            for axis in 0..3 {
                let up = (corner >> (2 - axis)) & 1 == 1;
                let i = base[axis] + up as i64;
                weight *= if up { frac[axis] } else { 1.0 - frac[axis] };
                inside &= i >= 0 && i < dims[axis] as i64;
                cell = cell * dims[axis] + i.max(0) as usize;
            }
            if inside {
                let bins = &self.boundary[cell * orientations..(cell + 1) * orientations];
                for &(k, w) in &around {
                    sum += weight * w * f64::from(bins[k]);
                }
            } else {
                sum -= weight * f64::from(BOUNDARY_UNITS);
            }
        }
        sum >= 0.0
    }

    /// True when the bin of `pose` (its position's cell, the orientation
    /// nearest its rotation) is reachable: the map's raw bit, without
    /// interpolation. Allocates nothing.
    #[inline]
    pub fn bin_reachable(&self, pose: &Pose) -> bool {
        let p = pose.translation;
        match self.layout.cell_of([p.x, p.y, p.z]) {
            Some(cell) => {
                let k = self.layout.orientation_of(&pose.rotation);
                self.reachable[cell * self.layout.orientation_count() + k] != 0
            }
            None => false,
        }
    }

    /// The capability index of the cell containing `position` (world frame,
    /// m); 0 outside the box.
    #[inline]
    pub fn capability_at(&self, position: [f64; 3]) -> f64 {
        self.layout
            .cell_of(position)
            .map_or(0.0, |cell| self.capability[cell])
    }

    /// The reachable cell (capability > 0) whose centre is nearest the
    /// centre of `position`'s cell (world frame, m; a position outside the
    /// box is clamped into it first); `None` when no cell is reachable or
    /// the position is not finite. A table lookup (exact Euclidean distance
    /// transform at merge time).
    #[inline]
    pub fn nearest_reachable_cell(&self, position: [f64; 3]) -> Option<usize> {
        let (origin, dims, r) = (
            self.layout.origin(),
            self.layout.dims(),
            self.layout.resolution(),
        );
        let mut cell = 0usize;
        for ((&p, &o), &n) in position.iter().zip(&origin).zip(&dims) {
            let t = ((p - o) / r).floor();
            if t.is_nan() {
                return None;
            }
            let i = t.clamp(0.0, (n - 1) as f64) as usize;
            cell = cell * n + i;
        }
        match self.nearest[cell] {
            u32::MAX => None,
            n => Some(n as usize),
        }
    }
}
