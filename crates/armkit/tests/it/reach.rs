//! Reachability maps: the chunked build equals the whole build, the map
//! agrees with IK at random poses, bad input is an error.

use armkit::ik::{AutoSolver, IkOptions};
use armkit::math::{Matrix3, Pose, Rotation3, Vector3};
use armkit::model::DhLink;
use armkit::reach::{self, build_chunk, Builder, MapLayout, MapSpec, ReachMap};
use armkit::Model;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn robot(name: &str) -> Model {
    armkit::robots::by_name(name).unwrap()
}

/// A rotation drawn uniformly on SO(3): the unit quaternion of a point drawn
/// uniformly in the 4-ball (by rejection), as a matrix.
fn random_rotation(rng: &mut ChaCha8Rng) -> Matrix3<f64> {
    loop {
        let v: [f64; 4] = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
        let n2: f64 = v.iter().map(|x| x * x).sum();
        if n2 > 0.01 && n2 <= 1.0 {
            let n = n2.sqrt();
            let [w, x, y, z] = v.map(|c| c / n);
            return Matrix3::new(
                1.0 - 2.0 * (y * y + z * z),
                2.0 * (x * y - w * z),
                2.0 * (x * z + w * y),
                2.0 * (x * y + w * z),
                1.0 - 2.0 * (x * x + z * z),
                2.0 * (y * z - w * x),
                2.0 * (x * z - w * y),
                2.0 * (y * z + w * x),
                1.0 - 2.0 * (x * x + y * y),
            );
        }
    }
}

/// Ground truth: the automatic IK solver (analytic where the class allows,
/// numeric with 50 seeded restarts otherwise) at the exact pose.
fn truth(solver: &mut AutoSolver, start: &[f64], pose: &Pose) -> bool {
    solver.solve(pose, start).unwrap().report.converged()
}

/// The ground truth's solver: 50 seeded restarts, no time budget.
pub(super) fn truth_solver(model: &Model) -> AutoSolver {
    let options = IkOptions {
        max_restarts: 50,
        time_budget: None,
        ..IkOptions::default()
    };
    AutoSolver::new(model, options).unwrap()
}

/// The map of `layout` built as one chunk of every cell.
pub(super) fn whole_map(model: &Model, layout: &MapLayout) -> ReachMap {
    let everything = reach::Chunk {
        cells: 0..layout.cell_count(),
        samples: 0..0,
    };
    let chunk = build_chunk(model, layout, &everything).unwrap();
    ReachMap::from_chunks(layout.clone(), [chunk]).unwrap()
}

/// Random poses in the box of `maps[0]` (the maps share a layout's box):
/// per map (agreement, false positives) as fractions of the interpolated
/// query, and (the last pair) of `maps[0]`'s raw bins; one ground truth.
fn accuracy_of(model: &Model, maps: &[&ReachMap], poses: usize, seed: u64) -> Vec<(f64, f64)> {
    let mut solver = truth_solver(model);
    let start = model.neutral_configuration();
    let layout = maps[0].layout();
    let (origin, dims, r) = (layout.origin(), layout.dims(), layout.resolution());
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut counts = vec![(0usize, 0usize); maps.len() + 1];
    for _ in 0..poses {
        let p = Vector3::from_fn(|i, _| origin[i] + rng.gen_range(0.0..dims[i] as f64 * r));
        let pose = Pose {
            rotation: random_rotation(&mut rng),
            translation: p,
        };
        let is = truth(&mut solver, &start, &pose);
        let said = maps
            .iter()
            .map(|m| m.query(&pose))
            .chain([maps[0].bin_reachable(&pose)]);
        for (count, said) in counts.iter_mut().zip(said) {
            count.0 += (said == is) as usize;
            count.1 += (said && !is) as usize;
        }
    }
    let n = poses as f64;
    counts
        .iter()
        .map(|&(a, f)| (a as f64 / n, f as f64 / n))
        .collect()
}

/// [`accuracy_of`] one map: (agreement, false positives, raw agreement,
/// raw false positives).
fn accuracy(model: &Model, map: &ReachMap, poses: usize, seed: u64) -> (f64, f64, f64, f64) {
    let a = accuracy_of(model, &[map], poses, seed);
    (a[0].0, a[0].1, a[1].0, a[1].1)
}

fn ik_spec(resolution: f64, orientations: usize) -> MapSpec {
    MapSpec::with_orientations(resolution, orientations, Builder::InverseKinematics)
}

fn model_spec(model: &Model, resolution: f64, orientations: usize) -> MapSpec {
    MapSpec::for_model(model, resolution, orientations, Builder::InverseKinematics)
}

/// The request in environment `variable`, `"robot resolution orientations
/// poses"`: (the text, the model, its spec, the poses); None when unset.
fn requested(variable: &str) -> Option<(String, Model, MapSpec, usize)> {
    let request = std::env::var(variable).ok()?;
    let words: Vec<&str> = request.split_whitespace().collect();
    let model = robot(words[0]);
    let spec = model_spec(&model, words[1].parse().unwrap(), words[2].parse().unwrap());
    let poses = words[3].parse().unwrap();
    Some((request, model, spec, poses))
}

/// The full accuracy figure: `ARMKIT_REACH_FULL="robot resolution
/// orientations poses"` (e.g. `ur5 0.05 200 100000`) builds the map with
/// the cells' boundary, times it, refines it, times that, and prints both
/// maps' agreement with IK and false positives on the same random poses.
#[test]
fn full_accuracy_figure_on_request() {
    let Some((request, model, spec, poses)) = requested("ARMKIT_REACH_FULL") else {
        return;
    };
    // The build's chunks come first in its progress, the refinement's next.
    let layout = MapLayout::new(&model, &spec).unwrap();
    let first = reach::chunks(&layout, &spec, reach::LOCAL_CHUNK_WORK).len();
    let began = std::time::Instant::now();
    let mut merged = None;
    let refined = reach::build(&model, &spec, 2, &mut |done, _| {
        if done == first && merged.is_none() {
            merged = Some(began.elapsed().as_secs_f64());
        }
    })
    .unwrap();
    let total = began.elapsed().as_secs_f64();
    let seconds = merged.unwrap_or(total);
    let refine_seconds = total - seconds;
    let cells_boundary = refined
        .reachable()
        .iter()
        .map(|&b| if b != 0 { 64 } else { -64 })
        .collect();
    let map = refined.clone().with_boundary(cells_boundary).unwrap();
    let a = accuracy_of(&model, &[&map, &refined], poses, 2026);
    eprintln!(
        "{request}: {} x {} orientations, build {seconds:.1} s, refinement {refine_seconds:.1} s ({:.0} IK/s overall), {} reachable cells, {} IK calls in all; before refinement: agreement {:.5}, false positives {:.5}; after: agreement {:.5}, false positives {:.5}; raw bins: agreement {:.5}, false positives {:.5}",
        spec.approach_directions,
        spec.rolls,
        refined.calls() as f64 / total,
        map.reachable_cells(),
        refined.calls(),
        a[0].0,
        a[0].1,
        a[1].0,
        a[1].1,
        a[2].0,
        a[2].1
    );
}

#[test]
fn arms_whose_roll_changes_nothing_get_directions_only() {
    let ur5 = robot("ur5");
    assert!(reach::roll_free(&ur5) && reach::one_roll_suffices(&ur5));
    let spec = model_spec(&ur5, 0.05, 200);
    assert_eq!((spec.approach_directions, spec.rolls), (200, 1));
    // The Panda's last joint turns 332 degrees: not free, but its other six
    // joints make up the rest (measured below).
    let panda = robot("panda");
    assert!(!reach::roll_free(&panda) && reach::one_roll_suffices(&panda));
    let spec = model_spec(&panda, 0.05, 200);
    assert_eq!((spec.approach_directions, spec.rolls), (200, 1));
    // The same arm with a last joint of 172 degrees keeps the rolls.
    let (convention, links) = panda.dh_table().unwrap();
    let mut links = links.to_vec();
    links[6] = links[6].with_limits(-1.5, 1.5);
    let narrow = Model::from_dh_with_transforms(
        "panda-narrow-wrist",
        convention,
        &links,
        *panda.base(),
        *panda.tool(),
    )
    .unwrap();
    assert!(!reach::one_roll_suffices(&narrow));
    let spec = model_spec(&narrow, 0.05, 200);
    assert_eq!((spec.approach_directions, spec.rolls), (25, 8));
    // A 6-joint arm needs the whole turn: the UR5 with its last joint cut
    // to 300 degrees keeps the rolls.
    let half = reach::REDUNDANT_ROLL_RANGE / 2.0;
    let last = ur5.dh_table().unwrap().1[5].with_limits(-half, half);
    let cut = ur5_variant(Some(last), Pose::identity());
    assert!(!reach::roll_free(&cut) && !reach::one_roll_suffices(&cut));
}

/// The UR5 with its last link replaced by `last` and its tool placement
/// followed by `tool_change` (flange frame).
fn ur5_variant(last: Option<DhLink>, tool_change: Pose) -> Model {
    let ur5 = robot("ur5");
    let (convention, links) = ur5.dh_table().unwrap();
    let mut links = links.to_vec();
    if let Some(last) = last {
        links[5] = last;
    }
    let tool = *ur5.tool() * tool_change;
    Model::from_dh_with_transforms("ur5-variant", convention, &links, *ur5.base(), tool).unwrap()
}

#[test]
fn roll_freedom_needs_a_whole_turn_about_the_tool_axis_through_its_origin() {
    let ur5 = robot("ur5");
    let last = ur5.dh_table().unwrap().1[5];
    let pi = std::f64::consts::PI;
    // Exactly one turn is enough; a micro-radian less is not.
    let turn = |lower: f64, upper: f64| Some(last.with_limits(lower, upper));
    assert!(reach::roll_free(&ur5_variant(
        turn(-pi, pi),
        Pose::identity()
    )));
    assert!(!reach::roll_free(&ur5_variant(
        turn(-pi, pi - 1e-6),
        Pose::identity()
    )));
    // A tool beside the last axis, or tilted off it, rolls by more than
    // the last joint.
    assert!(!reach::roll_free(&ur5_variant(None, Pose::trans_x(0.05))));
    assert!(!reach::roll_free(&ur5_variant(None, Pose::rot_x(0.3))));
    // A prismatic last joint does not roll the tool, whatever its travel.
    let slide = DhLink::prismatic(0.0, last.a, last.alpha).with_limits(0.0, 7.0);
    let slider = ur5_variant(Some(slide), Pose::identity());
    assert!(!reach::roll_free(&slider) && !reach::one_roll_suffices(&slider));
}

/// Why one roll per direction suffices on the Panda: turning the tool about
/// its z axis by a random angle changes the ground truth's answer at
/// almost no pose (0.1 % over 20 000 poses when measured; at most 0.5 %
/// here), while snapping its approach direction to the map's 200 changes
/// it at about 1 %.
#[test]
fn rolling_the_pandas_tool_almost_never_changes_its_reachability() {
    let panda = robot("panda");
    let layout = MapLayout::new(&panda, &model_spec(&panda, 0.1, 200)).unwrap();
    let (origin, dims, r) = (layout.origin(), layout.dims(), layout.resolution());
    let mut solver = truth_solver(&panda);
    let start = panda.neutral_configuration();
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let (poses, mut reachable, mut changed) = (3000, 0, 0);
    for _ in 0..poses {
        let translation =
            Vector3::from_fn(|i, _| origin[i] + rng.gen_range(0.0..dims[i] as f64 * r));
        let rotation = random_rotation(&mut rng);
        let roll = rng.gen_range(0.0..std::f64::consts::TAU);
        let rolled = rotation * Rotation3::from_axis_angle(&Vector3::z_axis(), roll).into_inner();
        let is = truth(
            &mut solver,
            &start,
            &Pose {
                rotation,
                translation,
            },
        );
        let after = truth(
            &mut solver,
            &start,
            &Pose {
                rotation: rolled,
                translation,
            },
        );
        reachable += is as usize;
        changed += (is != after) as usize;
    }
    // Enough reachable poses for the fraction to mean something.
    assert!(reachable > poses / 10, "{reachable} of {poses} reachable");
    assert!(
        changed * 200 <= poses,
        "a roll changed {changed} of {poses} answers"
    );
}

#[test]
fn chunked_build_equals_whole_build() {
    let model = robot("ur5");
    let spec = ik_spec(0.2, 12);
    let layout = MapLayout::new(&model, &spec).unwrap();
    let whole = whole_map(&model, &layout);
    let mut parts: Vec<_> = reach::chunks(&layout, &spec, 100)
        .iter()
        .map(|c| build_chunk(&model, &layout, c).unwrap())
        .collect();
    assert!(parts.len() > 10);
    parts.reverse();
    let chunked = ReachMap::from_chunks(layout, parts).unwrap();
    assert_eq!(whole, chunked);
    // The merge keeps the cells' boundary; the local build refines after it.
    let refined = reach::refine(&model, whole.clone(), 1, &mut |_, _| {}).unwrap();
    let threaded = reach::build(&model, &spec, 2, &mut |_, _| {}).unwrap();
    assert_eq!(refined, threaded);
    assert_ne!(whole.boundary(), refined.boundary());
    assert_eq!(refined.reachable(), whole.reachable());
    assert!(whole.reachable_cells() > 0 && whole.reachable_cells() < whole.layout().cell_count());
    assert!(whole.capability().iter().all(|c| (0.0..=1.0).contains(c)));
}

#[test]
fn sampled_chunks_equal_the_whole_sampling() {
    let model = robot("panda");
    let spec = MapSpec::with_orientations(
        0.2,
        12,
        Builder::ForwardSampling {
            samples: 20_000,
            seed: 5,
        },
    );
    let layout = MapLayout::new(&model, &spec).unwrap();
    let one = build_chunk(
        &model,
        &layout,
        &reach::Chunk {
            cells: 0..0,
            samples: 0..20_000,
        },
    )
    .unwrap();
    let whole = ReachMap::from_chunks(layout.clone(), [one]).unwrap();
    let mut parts: Vec<_> = reach::chunks(&layout, &spec, 3_000)
        .iter()
        .map(|c| build_chunk(&model, &layout, c).unwrap())
        .collect();
    parts.swap(0, 3);
    assert_eq!(whole, ReachMap::from_chunks(layout, parts).unwrap());
    assert_eq!(whole.calls(), 20_000);
    assert!(whole.reachable_bins() > 100);
}

#[test]
fn ur5_map_agrees_with_ik_at_random_poses() {
    let model = robot("ur5");
    let map = reach::build(&model, &model_spec(&model, 0.1, 50), 2, &mut |_, _| {}).unwrap();
    let (agreement, false_positives, raw, raw_false) = accuracy(&model, &map, 3000, 11);
    eprintln!("ur5 0.1 m 50: agreement {agreement}, false positives {false_positives}; raw {raw}, {raw_false}");
    // The interpolated query beats the raw bins, which the coarse grid
    // leaves well short of it.
    assert!(agreement > 0.97, "{agreement}");
    assert!(false_positives < 0.015, "{false_positives}");
    assert!(agreement > raw, "{agreement} vs {raw}");
}

#[test]
fn panda_map_agrees_with_ik_at_random_poses() {
    let model = robot("panda");
    let began = std::time::Instant::now();
    let map = reach::build(&model, &model_spec(&model, 0.3, 8), 2, &mut |_, _| {}).unwrap();
    eprintln!("panda build {:?}, {} calls", began.elapsed(), map.calls());
    let (agreement, false_positives, raw, _) = accuracy(&model, &map, 400, 12);
    eprintln!("panda 0.3 m 8: agreement {agreement}, false positives {false_positives}; raw {raw}");
    assert!(agreement > 0.9, "{agreement}");
}

#[test]
fn nearest_reachable_cell_is_the_nearest() {
    let model = robot("ur5");
    let map = reach::build(&model, &ik_spec(0.2, 6), 2, &mut |_, _| {}).unwrap();
    let layout = map.layout();
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let reachable: Vec<usize> = (0..layout.cell_count())
        .filter(|&c| map.capability()[c] > 0.0)
        .collect();
    for _ in 0..200 {
        let p: [f64; 3] = std::array::from_fn(|i| {
            layout.origin()[i] + rng.gen_range(0.0..layout.dims()[i] as f64 * layout.resolution())
        });
        let found = map.nearest_reachable_cell(p).unwrap();
        let own = layout.cell_center(layout.cell_of(p).unwrap());
        let d = |c: usize| {
            let q = layout.cell_center(c);
            (0..3).map(|i| (q[i] - own[i]).powi(2)).sum::<f64>()
        };
        let best = reachable
            .iter()
            .map(|&c| d(c))
            .fold(f64::INFINITY, f64::min);
        assert!(map.capability()[found] > 0.0);
        assert!((d(found) - best).abs() < 1e-9, "{} vs {best}", d(found));
    }
}

#[test]
fn bad_specs_are_errors_naming_the_problem() {
    let model = robot("ur5");
    for resolution in [0.0, -0.1, f64::NAN, f64::INFINITY] {
        let e = MapLayout::new(&model, &ik_spec(resolution, 20)).unwrap_err();
        assert!(e.to_string().contains("resolution"), "{e}");
    }
    let e = MapLayout::new(&model, &ik_spec(0.1, 0)).unwrap_err();
    assert!(e.to_string().contains("zero orientations"), "{e}");
    let e = MapLayout::new(&model, &ik_spec(1e-4, 200)).unwrap_err();
    assert!(
        e.to_string().contains("cells times 200 orientations"),
        "{e}"
    );
}

#[test]
fn the_direction_table_finds_the_nearest_direction_as_a_full_scan_does() {
    let model = robot("ur5");
    for orientations in [200, 800] {
        let layout = MapLayout::new(&model, &model_spec(&model, 0.5, orientations)).unwrap();
        let mut rng = ChaCha8Rng::seed_from_u64(orientations as u64);
        for _ in 0..20_000 {
            let r = random_rotation(&mut rng);
            let z = r.column(2);
            let scan = layout
                .directions()
                .iter()
                .map(|d| z[0] * d[0] + z[1] * d[1] + z[2] * d[2])
                .enumerate()
                .fold(
                    (0, f64::NEG_INFINITY),
                    |b, (i, c)| if c > b.1 { (i, c) } else { b },
                );
            assert_eq!(layout.orientation_of(&r), scan.0);
            let around = layout.orientations_around(&r);
            assert_eq!(around[0].0, scan.0);
            assert!((around.iter().map(|a| a.1).sum::<f64>() - 1.0).abs() < 1e-12);
        }
    }
}

/// Where the disagreement comes from: `ARMKIT_REACH_DIAG="robot resolution
/// orientations poses"`. Per random pose, the truth at the 8 cell centres
/// with the pose's exact rotation (position error alone) and at the exact
/// position with the map's 3 orientations (orientation error alone).
#[test]
fn diagnose_disagreement_on_request() {
    let Some((request, model, spec, poses)) = requested("ARMKIT_REACH_DIAG") else {
        return;
    };
    let map = reach::build(&model, &spec, 2, &mut |_, _| {}).unwrap();
    let mut solver = truth_solver(&model);
    let start = model.neutral_configuration();
    let layout = map.layout();
    let (origin, dims, r) = (layout.origin(), layout.dims(), layout.resolution());
    let mut rng = ChaCha8Rng::seed_from_u64(2026);
    let mut wrong = [0usize; 8];
    let (mut pos_wrong, mut ori_wrong, mut total_wrong, mut fp) = (0, 0, 0, 0);
    for _ in 0..poses {
        let p = Vector3::from_fn(|i, _| origin[i] + rng.gen_range(0.0..dims[i] as f64 * r));
        let rotation = random_rotation(&mut rng);
        let pose = Pose {
            rotation,
            translation: p,
        };
        let is = truth(&mut solver, &start, &pose);
        let said = map.query(&pose);
        // Position only: trilinear over the 8 centres, exact rotation.
        let mut sum = 0.0;
        for corner in 0..8 {
            let mut w = 1.0;
            let mut c = Vector3::zeros();
            for axis in 0..3 {
                let t = (p[axis] - origin[axis]) / r - 0.5;
                let f = t.floor();
                let up = (corner >> axis) & 1 == 1;
                w *= if up { t - f } else { 1.0 - (t - f) };
                c[axis] = origin[axis] + (f + up as i32 as f64 + 0.5) * r;
            }
            let q = Pose {
                rotation,
                translation: c,
            };
            if truth(&mut solver, &start, &q) {
                sum += w;
            }
        }
        let by_position = sum >= 0.5;
        // Orientation only: the map's 3 orientations at the exact position.
        let mut osum = 0.0;
        for (k, w) in layout.orientations_around(&rotation) {
            let q = Pose {
                rotation: layout.orientation(k).into_inner(),
                translation: p,
            };
            if truth(&mut solver, &start, &q) {
                osum += w;
            }
        }
        let by_orientation = osum >= 0.5;
        pos_wrong += (by_position != is) as usize;
        ori_wrong += (by_orientation != is) as usize;
        if said != is {
            total_wrong += 1;
            fp += said as usize;
            wrong[(by_position != is) as usize * 2 + (by_orientation != is) as usize] += 1;
        }
    }
    eprintln!(
        "{request}: wrong {total_wrong} (fp {fp}); position-only wrong {pos_wrong}, orientation-only wrong {ori_wrong}; of the map's wrong: neither {} ori {} pos {} both {}",
        wrong[0], wrong[1], wrong[2], wrong[3]
    );
}

/// What snapping a pose to its bin costs, without building a map:
/// `ARMKIT_REACH_SNAP="robot resolution poses directions rolls"`. Per
/// random pose in the map's box, the truth at the pose against the truth
/// at its cell's centre (position snapping), at its bin's orientation
/// (orientation snapping, `directions x rolls`), at both, and at the pose
/// turned by a random roll about the tool axis; and the map's oracle (its
/// restarts) against the truth at the bin.
#[test]
fn snapping_cost_on_request() {
    let Ok(request) = std::env::var("ARMKIT_REACH_SNAP") else {
        return;
    };
    let words: Vec<&str> = request.split_whitespace().collect();
    let model = robot(words[0]);
    let number = |i: usize| words[i].parse::<f64>().unwrap();
    let spec = MapSpec {
        approach_directions: number(3) as usize,
        rolls: number(4) as usize,
        ..ik_spec(number(1), 1)
    };
    let layout = MapLayout::new(&model, &spec).unwrap();
    let (origin, dims, r) = (layout.origin(), layout.dims(), layout.resolution());
    let (mut truth_solver, mut map_solver) = (truth_solver(&model), {
        let options = IkOptions {
            max_restarts: reach::NUMERIC_RESTARTS,
            time_budget: None,
            ..IkOptions::default()
        };
        AutoSolver::new(&model, options).unwrap()
    });
    let start = model.neutral_configuration();
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let (mut poses, mut changed) = (0usize, [0usize; 5]);
    for _ in 0..number(2) as usize {
        let p = Vector3::from_fn(|i, _| origin[i] + rng.gen_range(0.0..dims[i] as f64 * r));
        let rotation = random_rotation(&mut rng);
        let roll = rng.gen_range(0.0..std::f64::consts::TAU);
        let Some(cell) = layout.cell_of([p.x, p.y, p.z]) else {
            continue;
        };
        poses += 1;
        let centre = Vector3::from(layout.cell_center(cell));
        let snapped = layout
            .orientation(layout.orientation_of(&rotation))
            .into_inner();
        let rolled = rotation * Rotation3::from_axis_angle(&Vector3::z_axis(), roll).into_inner();
        let at = |solver: &mut AutoSolver, rotation: Matrix3<f64>, translation: Vector3<f64>| {
            truth(
                solver,
                &start,
                &Pose {
                    rotation,
                    translation,
                },
            )
        };
        let is = at(&mut truth_solver, rotation, p);
        let bin = at(&mut truth_solver, snapped, centre);
        let answers = [
            at(&mut truth_solver, rotation, centre) != is,
            at(&mut truth_solver, snapped, p) != is,
            bin != is,
            at(&mut truth_solver, rolled, p) != is,
            at(&mut map_solver, snapped, centre) != bin,
        ];
        for (count, differs) in changed.iter_mut().zip(answers) {
            *count += differs as usize;
        }
    }
    let share = |k: usize| 100.0 * changed[k] as f64 / poses.max(1) as f64;
    eprintln!(
        "{request}: {poses} poses; the answer changes by position snapping at {:.2} %, orientation snapping {:.2} %, both {:.2} %, a random roll {:.2} %; the map's oracle against the truth at the bin {:.2} %",
        share(0),
        share(1),
        share(2),
        share(3),
        share(4)
    );
}
