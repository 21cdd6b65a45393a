//! A lookup table over the sphere that finds the approach directions
//! nearest a unit vector by scanning a few candidates instead of all.
//!
//! The sphere is cut into equal-area bins (uniform in `z`, uniform in
//! azimuth). A bin lists every direction within `rho + r4` of its centre,
//! `rho` the bin's angular radius and `r4` a bound on the angle from any
//! point to its fourth nearest direction: by the triangle inequality the
//! four nearest directions of every point in the bin are listed.

/// Bins along `z` and along the azimuth.
const Z_BINS: usize = 24;
const PHI_BINS: usize = 48;

/// Candidate lists per bin (compressed rows).
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct DirectionIndex {
    offsets: Vec<u32>,
    members: Vec<u32>,
}

fn angle(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    (a[0] * b[0] + a[1] * b[1] + a[2] * b[2])
        .clamp(-1.0, 1.0)
        .acos()
}

fn point(z: f64, phi: f64) -> [f64; 3] {
    let r = (1.0 - z * z).max(0.0).sqrt();
    [r * phi.cos(), r * phi.sin(), z]
}

/// The bin of unit vector `v`.
#[inline]
fn bin_of(v: [f64; 3]) -> usize {
    let zi = (((v[2] + 1.0) * 0.5 * Z_BINS as f64) as usize).min(Z_BINS - 1);
    let phi = v[1].atan2(v[0]) + std::f64::consts::PI;
    let pi = ((phi / std::f64::consts::TAU * PHI_BINS as f64) as usize).min(PHI_BINS - 1);
    zi * PHI_BINS + pi
}

impl DirectionIndex {
    /// The index of `directions` (unit vectors); empty (a full scan) for
    /// fewer than 32 directions, where a scan is as fast.
    pub(crate) fn new(directions: &[[f64; 3]]) -> DirectionIndex {
        if directions.len() < 32 {
            return DirectionIndex::default();
        }
        // r4: the largest angle from a dense sample of the sphere to its
        // fourth nearest direction, with a margin for the points between.
        let probes = super::layout::fibonacci_directions(40 * directions.len());
        let mut r4 = 0.0f64;
        for p in &probes {
            // The four largest cosines, largest first.
            let mut best = [f64::NEG_INFINITY; 4];
            for d in directions {
                let c = p[0] * d[0] + p[1] * d[1] + p[2] * d[2];
                if c > best[3] {
                    best[3] = c;
                    best.sort_by(|a, b| b.total_cmp(a));
                }
            }
            r4 = r4.max(best[3].clamp(-1.0, 1.0).acos());
        }
        r4 = r4 * 1.25 + 0.02;
        let (tau, dz) = (std::f64::consts::TAU, 2.0 / Z_BINS as f64);
        let dphi = tau / PHI_BINS as f64;
        let mut offsets = vec![0u32];
        let mut members = Vec::new();
        for zi in 0..Z_BINS {
            for pi in 0..PHI_BINS {
                let (z0, phi0) = (
                    -1.0 + zi as f64 * dz,
                    -std::f64::consts::PI + pi as f64 * dphi,
                );
                let centre = point(z0 + 0.5 * dz, phi0 + 0.5 * dphi);
                // The bin's angular radius: its corners and edge midpoints.
                let mut rho = 0.0f64;
                for a in 0..=2 {
                    for b in 0..=2 {
                        let q = point(z0 + 0.5 * a as f64 * dz, phi0 + 0.5 * b as f64 * dphi);
                        rho = rho.max(angle(&centre, &q));
                    }
                }
                let reach = rho * 1.1 + r4;
                for (i, d) in directions.iter().enumerate() {
                    if angle(&centre, d) <= reach {
                        members.push(i as u32);
                    }
                }
                offsets.push(members.len() as u32);
            }
        }
        DirectionIndex { offsets, members }
    }

    /// The four directions nearest unit `v` (index, cosine), nearest first;
    /// missing entries have cosine -infinity. Allocates nothing.
    #[inline]
    pub(crate) fn nearest4(&self, directions: &[[f64; 3]], v: [f64; 3]) -> [(usize, f64); 4] {
        let mut top = [(0usize, f64::NEG_INFINITY); 4];
        let mut consider = |i: usize| {
            let d = &directions[i];
            let dot = v[0] * d[0] + v[1] * d[1] + v[2] * d[2];
            if dot > top[3].1 {
                let mut j = 3;
                while j > 0 && dot > top[j - 1].1 {
                    top[j] = top[j - 1];
                    j -= 1;
                }
                top[j] = (i, dot);
            }
        };
        if self.offsets.is_empty() || !v.iter().all(|c| c.is_finite()) {
            (0..directions.len()).for_each(&mut consider);
        } else {
            let b = bin_of(v);
            let (from, to) = (self.offsets[b] as usize, self.offsets[b + 1] as usize);
            self.members[from..to]
                .iter()
                .for_each(|&i| consider(i as usize));
        }
        top
    }
}
