//! The nearest reachable cell of every cell: an exact Euclidean distance
//! transform of the grid (Felzenszwalb and Huttenlocher, "Distance
//! transforms of sampled functions", 2012: one pass of the lower envelope
//! of parabolas per axis), carrying the nearest site's index.

use crate::error::{Error, Result};

/// The lower envelope of the parabolas `(q - p)^2 + f[p]` over the finite
/// `f[p]`: `d[q]` its value, `site_out[q] = site_in[argmin]`.
fn transform_line(
    f: &[f64],
    site_in: &[u32],
    d: &mut [f64],
    site_out: &mut [u32],
    v: &mut Vec<usize>,
    z: &mut Vec<f64>,
) {
    v.clear();
    z.clear();
    for q in 0..f.len() {
        if !f[q].is_finite() {
            continue;
        }
        let qf = q as f64;
        while let Some(&p) = v.last() {
            let pf = p as f64;
            // Where parabola q overtakes parabola p.
            let s = ((f[q] + qf * qf) - (f[p] + pf * pf)) / (2.0 * (qf - pf));
            if z.last().is_some_and(|&zl| s <= zl) {
                v.pop();
                z.pop();
            } else {
                v.push(q);
                z.push(s);
                break;
            }
        }
        if v.is_empty() {
            v.push(q);
            z.push(f64::NEG_INFINITY);
        }
    }
    let mut k = 0;
    for (q, (dq, sq)) in d.iter_mut().zip(site_out.iter_mut()).enumerate() {
        if v.is_empty() {
            *dq = f64::INFINITY;
            *sq = u32::MAX;
            continue;
        }
        while k + 1 < v.len() && z[k + 1] < q as f64 {
            k += 1;
        }
        let p = v[k];
        let delta = q as f64 - p as f64;
        *dq = delta * delta + f[p];
        *sq = site_in[p];
    }
}

/// For each cell of a `dims` grid (C order), the index of the nearest cell
/// (by centre distance) whose `weight` is > 0, `u32::MAX` when none is.
pub(crate) fn nearest_sites(dims: [usize; 3], weight: &[f64]) -> Result<Vec<u32>> {
    let n = weight.len();
    let mut dist = Vec::new();
    let mut site = Vec::new();
    if dist.try_reserve_exact(n).is_err() || site.try_reserve_exact(n).is_err() {
        return Err(Error::invalid_argument(
            "resolution",
            format!("cannot allocate the nearest-cell table of {n} cells"),
        ));
    }
    for (i, &w) in weight.iter().enumerate() {
        let reachable = w > 0.0;
        dist.push(if reachable { 0.0 } else { f64::INFINITY });
        site.push(if reachable { i as u32 } else { u32::MAX });
    }
    let longest = dims.iter().copied().max().unwrap_or(0);
    let (mut f, mut s_in) = (vec![0.0; longest], vec![0u32; longest]);
    let (mut d, mut s_out) = (vec![0.0; longest], vec![0u32; longest]);
    let (mut v, mut z) = (Vec::with_capacity(longest), Vec::with_capacity(longest));
    let strides = [dims[1] * dims[2], dims[2], 1];
    for axis in (0..3).rev() {
        let (len, stride) = (dims[axis], strides[axis]);
        // Every line along `axis`: the cells whose coordinate on it is 0.
        for start in 0..n {
            if (start / stride) % len != 0 {
                continue;
            }
            for (i, (fi, si)) in f.iter_mut().zip(s_in.iter_mut()).take(len).enumerate() {
                *fi = dist[start + i * stride];
                *si = site[start + i * stride];
            }
            transform_line(
                &f[..len],
                &s_in[..len],
                &mut d[..len],
                &mut s_out[..len],
                &mut v,
                &mut z,
            );
            for (i, (&di, &si)) in d.iter().zip(&s_out).take(len).enumerate() {
                dist[start + i * stride] = di;
                site[start + i * stride] = si;
            }
        }
    }
    Ok(site)
}
