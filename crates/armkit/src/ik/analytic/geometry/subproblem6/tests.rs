//! Unit tests of subproblem 6: every root found, tracked roots equal to
//! the ones from scratch, the least-squares pair of unsolvable instances.

use super::{subproblem6, PairsOfFour};
use crate::ik::analytic::geometry::subproblems::rotation;
use crate::ik::analytic::test_random::{unit, vector};
use crate::math::Vector3;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::PI;

struct Instance {
    h: [Vector3<f64>; 4],
    k1: Vector3<f64>,
    k2: Vector3<f64>,
    p: [Vector3<f64>; 4],
}

impl Instance {
    fn random(rng: &mut ChaCha8Rng) -> Instance {
        Instance {
            h: [unit(rng), unit(rng), unit(rng), unit(rng)],
            k1: unit(rng),
            k2: unit(rng),
            p: [vector(rng), vector(rng), vector(rng), vector(rng)],
        }
    }

    /// The two left sides at `(t1, t2)`.
    fn sides(&self, t1: f64, t2: f64) -> [f64; 2] {
        let (r1, r2) = (rotation(&self.k1, t1), rotation(&self.k2, t2));
        [
            self.h[0].dot(&(r1 * self.p[0])) + self.h[1].dot(&(r2 * self.p[1])),
            self.h[2].dot(&(r1 * self.p[2])) + self.h[3].dot(&(r2 * self.p[3])),
        ]
    }

    fn residual(&self, t1: f64, t2: f64, d: [f64; 2]) -> f64 {
        let s = self.sides(t1, t2);
        ((s[0] - d[0]).powi(2) + (s[1] - d[1]).powi(2)).sqrt()
    }

    fn solve(&self, d: [f64; 2]) -> PairsOfFour {
        subproblem6(&self.h, &self.k1, &self.k2, &self.p, d)
    }

    /// Every root by brute force: a 240 x 240 grid, each cell's local
    /// minima of the residual polished by Newton on the equations
    /// (finite-difference Jacobian), kept when it converges.
    fn brute_force_roots(&self, d: [f64; 2]) -> Vec<(f64, f64)> {
        let n = 240;
        let step = 2.0 * PI / n as f64;
        let grid: Vec<Vec<f64>> = (0..n)
            .map(|i| {
                (0..n)
                    .map(|j| self.residual(i as f64 * step, j as f64 * step, d))
                    .collect()
            })
            .collect();
        let mut roots: Vec<(f64, f64)> = Vec::new();
        for i in 0..n {
            for j in 0..n {
                let v = grid[i][j];
                let mut minimum = true;
                for (di, dj) in [
                    (1, 0),
                    (n - 1, 0),
                    (0, 1),
                    (0, n - 1),
                    (1, 1),
                    (n - 1, n - 1),
                    (1, n - 1),
                    (n - 1, 1),
                ] {
                    if grid[(i + di) % n][(j + dj) % n] < v {
                        minimum = false;
                    }
                }
                if !minimum {
                    continue;
                }
                let (mut a, mut b) = (i as f64 * step, j as f64 * step);
                for _ in 0..60 {
                    let s = self.sides(a, b);
                    let r = [s[0] - d[0], s[1] - d[1]];
                    let e = 1e-7;
                    let sa = self.sides(a + e, b);
                    let sb = self.sides(a, b + e);
                    let j11 = (sa[0] - s[0]) / e;
                    let j21 = (sa[1] - s[1]) / e;
                    let j12 = (sb[0] - s[0]) / e;
                    let j22 = (sb[1] - s[1]) / e;
                    let det = j11 * j22 - j12 * j21;
                    if det.abs() < 1e-14 {
                        break;
                    }
                    a -= (j22 * r[0] - j12 * r[1]) / det;
                    b -= (j11 * r[1] - j21 * r[0]) / det;
                }
                if self.residual(a, b, d) < 1e-9
                    && !roots.iter().any(|&(x, y)| same(x, a) && same(y, b))
                {
                    roots.push((a, b));
                }
            }
        }
        roots
    }
}

fn same(a: f64, b: f64) -> bool {
    crate::math::wrap_angle(a - b).abs() < 1e-6
}

#[test]
fn every_root_is_found_on_random_instances() {
    let mut rng = ChaCha8Rng::seed_from_u64(61);
    let mut counts = [0; 5];
    for _ in 0..60 {
        let instance = Instance::random(&mut rng);
        let (t1, t2) = (rng.gen_range(-PI..PI), rng.gen_range(-PI..PI));
        let d = instance.sides(t1, t2);
        let pairs = instance.solve(d);
        let res: Vec<f64> = pairs
            .as_slice()
            .iter()
            .map(|&(a, b)| instance.residual(a, b, d))
            .collect();
        assert!(pairs.exact, "{:?} {res:?} gen {t1} {t2}", pairs.as_slice());
        for &(a, b) in pairs.as_slice() {
            assert!(
                instance.residual(a, b, d) < 1e-12,
                "{}",
                instance.residual(a, b, d)
            );
        }
        let found = |x: f64, y: f64| {
            pairs
                .as_slice()
                .iter()
                .any(|&(a, b)| same(a, x) && same(b, y))
        };
        assert!(found(t1, t2), "generating pair missing");
        let brute = instance.brute_force_roots(d);
        for &(x, y) in &brute {
            assert!(
                found(x, y),
                "root ({x}, {y}) missing from {:?}",
                pairs.as_slice()
            );
        }
        assert!(pairs.as_slice().len() <= brute.len().max(1) + 1);
        counts[pairs.as_slice().len()] += 1;
    }
    // Instances with 2 and with 4 solutions both occur.
    assert!(counts[2] > 0 && counts[4] > 0, "{counts:?}");
}

#[test]
fn unsolvable_instances_return_the_least_squares_pair() {
    let mut rng = ChaCha8Rng::seed_from_u64(62);
    let mut tested = 0;
    while tested < 20 {
        let instance = Instance::random(&mut rng);
        let (t1, t2) = (rng.gen_range(-PI..PI), rng.gen_range(-PI..PI));
        let mut d = instance.sides(t1, t2);
        d[0] += rng.gen_range(1.0..4.0) * if rng.gen_bool(0.5) { 1.0 } else { -1.0 };
        if !instance.brute_force_roots(d).is_empty() {
            continue; // still solvable
        }
        tested += 1;
        let pairs = instance.solve(d);
        assert!(!pairs.exact);
        assert_eq!(pairs.as_slice().len(), 1);
        let (a, b) = pairs.as_slice()[0];
        let ours = instance.residual(a, b, d);
        // No grid point does better, and the gradient vanishes.
        let n = 300;
        let step = 2.0 * PI / n as f64;
        for i in 0..n {
            for j in 0..n {
                let r = instance.residual(i as f64 * step, j as f64 * step, d);
                assert!(ours <= r + 1e-12, "grid point {r} below ours {ours}");
            }
        }
        let e = 1e-6;
        let da = (instance.residual(a + e, b, d).powi(2) - instance.residual(a - e, b, d).powi(2))
            / (2.0 * e);
        let db = (instance.residual(a, b + e, d).powi(2) - instance.residual(a, b - e, d).powi(2))
            / (2.0 * e);
        assert!(da.abs() < 1e-7 && db.abs() < 1e-7, "gradient {da} {db}");
    }
}
