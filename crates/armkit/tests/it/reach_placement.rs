//! Inverse reachability: the base placements from which a map reaches a
//! task's poses.

use armkit::kinematics::{forward_kinematics, Data};
use armkit::math::{Pose, Vector3};
use armkit::reach::{self, base_placements, Builder, FloorGrid, MapSpec, ReachMap};
use armkit::Model;

fn ur5_map() -> (Model, ReachMap) {
    let model = armkit::robots::by_name("ur5").unwrap();
    let spec = MapSpec::for_model(&model, 0.1, 50, Builder::InverseKinematics);
    let map = reach::build(&model, &spec, 2, &mut |_, _| {}).unwrap();
    (model, map)
}

/// Tool poses of a few configurations, in the robot's base frame.
fn task_in_base_frame(model: &Model) -> Vec<Pose> {
    let mut data = Data::new(model);
    [
        [0.3, -1.2, 1.4, -1.7, -1.5, 0.2],
        [0.6, -1.0, 1.2, -1.6, -1.5, 0.0],
        [0.0, -1.4, 1.6, -1.8, -1.4, 0.5],
    ]
    .iter()
    .map(|q| *forward_kinematics(model, &mut data, q).unwrap())
    .collect()
}

fn floor() -> FloorGrid {
    FloorGrid {
        x: [-0.5, 1.5],
        y: [-1.5, 0.5],
        step: 0.1,
        z: 0.0,
        yaws: 4,
    }
}

#[test]
fn a_task_placed_from_a_known_base_finds_that_base() {
    let (model, map) = ur5_map();
    let mut base = Pose::rot_z(std::f64::consts::FRAC_PI_2);
    base.translation = Vector3::new(0.7, -0.4, 0.0);
    let task: Vec<Pose> = task_in_base_frame(&model)
        .iter()
        .map(|t| &base * t)
        .collect();
    // The task is where the map says the arm reaches from the known base.
    for t in &task {
        assert!(map.query(&(&base.inverse() * t)));
    }
    let found = base_placements(&map, &task, &floor()).unwrap();
    let known = found
        .iter()
        .find(|p| {
            (p.x - 0.7).abs() < 1e-9
                && (p.y + 0.4).abs() < 1e-9
                && (p.yaw - std::f64::consts::FRAC_PI_2).abs() < 1e-9
        })
        .expect("the known base is among the placements");
    assert!(known.score > 0.0 && known.score <= 1.0);
    // Best first, and every placement reaches every pose.
    assert!(found.windows(2).all(|w| w[0].score >= w[1].score));
    assert!(found.len() < 4 * 21 * 21, "{} placements", found.len());
    for p in &found {
        let mut b = Pose::rot_z(p.yaw);
        b.translation = Vector3::new(p.x, p.y, p.z);
        let inverse = b.inverse();
        assert!(task.iter().all(|t| map.query(&(&inverse * t))));
        let mean: f64 = task
            .iter()
            .map(|t| {
                let s = (&inverse * t).translation;
                map.capability_at([s.x, s.y, s.z])
            })
            .sum::<f64>()
            / task.len() as f64;
        assert!((mean - p.score).abs() < 1e-12);
    }
}

#[test]
fn an_impossible_task_is_an_error_saying_so() {
    let (model, map) = ur5_map();
    let mut task = task_in_base_frame(&model);
    // Two poses 4 m apart: no UR5 base reaches both.
    task[1].translation += Vector3::new(4.0, 0.0, 0.0);
    let e = base_placements(&map, &task, &floor())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("no base placement reaches all 3 task poses") && e.contains("the best reached"),
        "{e}"
    );
    let e = base_placements(&map, &[], &floor())
        .unwrap_err()
        .to_string();
    assert!(e.contains("at least one pose"), "{e}");
    for (bad, name) in [
        (
            FloorGrid {
                step: 0.0,
                ..floor()
            },
            "step",
        ),
        (
            FloorGrid {
                x: [1.0, -1.0],
                ..floor()
            },
            "lower <= upper",
        ),
        (FloorGrid { yaws: 0, ..floor() }, "yaws"),
        (
            FloorGrid {
                step: 1e-5,
                ..floor()
            },
            "exceed the limit",
        ),
    ] {
        let e = base_placements(&map, &task, &bad).unwrap_err().to_string();
        assert!(e.contains(name), "{e}");
    }
    let mut broken = task.clone();
    broken[0].translation.x = f64::NAN;
    let e = base_placements(&map, &broken, &floor())
        .unwrap_err()
        .to_string();
    assert!(e.contains("pose 0"), "{e}");
}
