//! Boundary refinement: the crossings are where IK changes its answer, a
//! distributed refinement gives the local one's map, the refined query
//! agrees with IK more often, and bad boundaries are errors.

use super::reach::{truth_solver, whole_map};
use armkit::math::{Pose, Vector3};
use armkit::reach::{
    self, apply_refinement, refine_chunk, Boundary, Builder, Crossing, MapSpec, ReachMap,
    Refinement, BOUNDARY_UNITS,
};
use armkit::Model;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn ur5() -> Model {
    armkit::robots::by_name("ur5").unwrap()
}

fn cells_spec(resolution: f64, orientations: usize) -> MapSpec {
    MapSpec {
        boundary: Boundary::Cells,
        ..MapSpec::with_orientations(resolution, orientations, Builder::InverseKinematics)
    }
}

/// The map with the cells' boundary (+-one cell from the bits).
fn unrefined(map: &ReachMap) -> ReachMap {
    let bits = map
        .reachable()
        .iter()
        .map(|&b| {
            if b != 0 {
                BOUNDARY_UNITS
            } else {
                -BOUNDARY_UNITS
            }
        })
        .collect();
    map.clone().with_boundary(bits).unwrap()
}

#[test]
fn crossings_lie_where_ik_changes_its_answer() {
    let model = ur5();
    let spec = MapSpec::with_orientations(0.2, 12, Builder::InverseKinematics);
    let cells = reach::build(&model, &cells_spec(0.2, 12), 2, &mut |_, _| {}).unwrap();
    // The cells' map under the refining spec: rebuild its layout's spec.
    let layout = armkit::reach::MapLayout::new(&model, &spec).unwrap();
    let map = whole_map(&model, &layout);
    assert_eq!(map.reachable(), cells.reachable());
    let part = refine_chunk(&model, &map, 0..layout.cell_count()).unwrap();
    assert!(part.crossings.len() > 100, "{}", part.crossings.len());
    assert_eq!(part.calls, 6 * part.crossings.len() as u64);
    let mut solver = truth_solver(&model);
    let start = model.neutral_configuration();
    let o = layout.orientation_count();
    let (mut right, mut total) = (0, 0);
    for c in part.crossings.iter().step_by(7) {
        let (cell, k) = (c.bin as usize / o, c.bin as usize % o);
        let inside = map.reachable()[c.bin as usize] != 0;
        let centre = Vector3::from(layout.cell_center(cell));
        let mut at = |f: f64| {
            let mut t = centre;
            t[c.axis as usize] += f * layout.resolution();
            let pose = Pose {
                rotation: layout.orientation(k).into_inner(),
                translation: t,
            };
            solver.solve(&pose, &start).unwrap().report.converged()
        };
        let step = 1.0 / 64.0;
        let a = f64::from(c.at);
        assert!(a > 0.0 && a < 1.0);
        right += (at(a - step) == inside && at(a + step) != inside) as usize;
        total += 1;
    }
    eprintln!("{right} of {total} crossings bracketed by IK");
    assert!(right as f64 >= 0.9 * total as f64, "{right} of {total}");
}

#[test]
fn a_distributed_refinement_is_the_local_one() {
    let model = ur5();
    let spec = MapSpec::with_orientations(0.2, 12, Builder::InverseKinematics);
    let layout = reach::MapLayout::new(&model, &spec).unwrap();
    let parts: Vec<_> = reach::chunks(&layout, &spec, 300)
        .iter()
        .map(|c| reach::build_chunk(&model, &layout, c).unwrap())
        .collect();
    let merged = ReachMap::from_chunks(layout.clone(), parts).unwrap();
    let n = layout.cell_count();
    let mut pieces: Vec<Refinement> = (0..n)
        .step_by(97)
        .map(|s| refine_chunk(&model, &merged, s..(s + 97).min(n)).unwrap())
        .collect();
    pieces.reverse();
    let distributed = apply_refinement(merged.clone(), pieces).unwrap();
    let local = reach::refine(&model, merged.clone(), 2, &mut |_, _| {}).unwrap();
    assert_eq!(distributed, local);
    assert!(local.calls() > merged.calls());
    // Signs kept, magnitudes within one cell, some below it.
    let b = local.boundary();
    assert!(b
        .iter()
        .zip(local.reachable())
        .all(|(&d, &r)| (d > 0) == (r != 0) && d.unsigned_abs() <= 64 && d != 0));
    assert!(b.iter().any(|d| d.unsigned_abs() < 32));
    // Reading the boundary back gives the same map (but the refinement's
    // calls, which a file does not carry apart).
    let read = merged.with_boundary(b.to_vec()).unwrap();
    assert_eq!(read.boundary(), local.boundary());
    assert_eq!(read.reachable(), local.reachable());
}

#[test]
fn the_refined_query_agrees_with_ik_more_often() {
    let model = ur5();
    let spec = MapSpec::for_model(&model, 0.1, 50, Builder::InverseKinematics);
    let refined = reach::build(&model, &spec, 2, &mut |_, _| {}).unwrap();
    let cells = unrefined(&refined);
    let mut solver = truth_solver(&model);
    let start = model.neutral_configuration();
    let layout = refined.layout();
    let mut rng = ChaCha8Rng::seed_from_u64(77);
    let (mut near, mut before, mut after) = (0, 0, 0);
    // Poses near the boundary: where the two maps disagree or where the
    // cells' map is on the fence, drawn until 400 such are seen.
    let mut tries = 0;
    while near < 400 && tries < 200_000 {
        tries += 1;
        let p = Vector3::from_fn(|i, _| {
            layout.origin()[i] + rng.gen_range(0.0..layout.dims()[i] as f64 * layout.resolution())
        });
        let r = Pose::rot_z(rng.gen_range(-3.1..3.1)) * Pose::rot_y(rng.gen_range(-1.5..1.5));
        let pose = Pose {
            rotation: r.rotation,
            translation: p,
        };
        let (a, b) = (cells.query(&pose), refined.query(&pose));
        if a == b {
            continue;
        }
        near += 1;
        let is = solver.solve(&pose, &start).unwrap().report.converged();
        before += (a == is) as usize;
        after += (b == is) as usize;
    }
    eprintln!("{near} poses where the maps differ: cells right at {before}, refined at {after}");
    assert!(near >= 100, "{near}");
    assert!(after as f64 > 1.5 * before as f64, "{after} vs {before}");
}

#[test]
fn bad_boundaries_and_crossings_are_errors_naming_them() {
    let model = ur5();
    let map = reach::build(&model, &cells_spec(0.3, 4), 1, &mut |_, _| {}).unwrap();
    let e = map
        .clone()
        .with_boundary(vec![1; 3])
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("boundary") && e.contains("holds 3 values"),
        "{e}"
    );
    let mut flipped = map.boundary().to_vec();
    let bin = map.reachable().iter().position(|&b| b != 0).unwrap();
    flipped[bin] = -5;
    let e = map.clone().with_boundary(flipped).unwrap_err().to_string();
    assert!(
        e.contains(&format!("bin {bin} holds -5 for a bin that is reachable")),
        "{e}"
    );
    let bins = map.reachable().len() as u64;
    let e = apply_refinement(
        map.clone(),
        [Refinement {
            cells: 0..1,
            crossings: vec![Crossing {
                bin: bins - 1,
                axis: 0,
                at: 0.5,
            }],
            calls: 1,
        }],
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("is not on an edge"), "{e}");
    // A map of the cells' boundary is not refined.
    let same = reach::refine(&model, map.clone(), 1, &mut |_, _| {}).unwrap();
    assert_eq!(same, map);
    let e = MapSpec {
        boundary: Boundary::Bisection { steps: 7 },
        ..cells_spec(0.3, 4)
    }
    .validate()
    .unwrap_err()
    .to_string();
    assert!(e.contains("bisection steps must be 1 to 6"), "{e}");
}
