//! Position-only maps (arm4) against the arm's analytic workspace, and the
//! box of an arm on rails (gantry9) against forward kinematics.

use armkit::kinematics::{forward_kinematics, Data};
use armkit::math::{Pose, Vector3};
use armkit::reach::{self, Builder, MapLayout, MapSpec, MapTarget, ReachBox};
use armkit::Model;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn robot(name: &str) -> Model {
    armkit::robots::by_name(name).unwrap()
}

fn random_q(model: &Model, rng: &mut ChaCha8Rng) -> Vec<f64> {
    model
        .joints()
        .iter()
        .map(|j| rng.gen_range(j.limits.lower..=j.limits.upper))
        .collect()
}

#[test]
fn arms_with_fewer_than_six_joints_get_position_only_specs() {
    let spec = MapSpec::for_model(&robot("arm4"), 0.05, 200, Builder::InverseKinematics);
    assert_eq!(spec.target, MapTarget::Position);
    assert_eq!(spec.orientation_count(), 1);
    let spec = MapSpec::for_model(&robot("ur5"), 0.05, 200, Builder::InverseKinematics);
    assert_eq!(spec.target, MapTarget::Pose);
    let bad = MapSpec {
        approach_directions: 20,
        ..MapSpec::position_only(0.05, Builder::InverseKinematics)
    };
    let e = bad.validate().unwrap_err().to_string();
    assert!(
        e.contains("one nominal orientation") && e.contains("20 x 1"),
        "{e}"
    );
}

/// arm4's tool point is 0.08 m from its wrist point W (the origin of joint
/// 4's frame) along a direction that joints 3 and 4 turn over the whole
/// sphere, and W moves in the plane z = 0.30 m over the region of joints 1
/// and 2. So a point c is reachable exactly when the circle of radius
/// `sqrt(0.08^2 - (c_z - 0.30)^2)` about it in that plane meets W's region,
/// which is connected: when that radius lies between the least and the
/// greatest distance from c to the region (sampled at 0.5 deg of joints 1
/// and 2). Cells within 5 mm of deciding otherwise are left out. Forward
/// kinematics checks the geometry first.
#[test]
fn arm4_position_map_matches_the_analytic_workspace() {
    let model = robot("arm4");
    let mut data = Data::new(&model);
    let mut rng = ChaCha8Rng::seed_from_u64(41);
    for _ in 0..2000 {
        let q = random_q(&model, &mut rng);
        let tool = forward_kinematics(&model, &mut data, &q)
            .unwrap()
            .translation;
        let w = data.joint_frames()[3].translation;
        assert!(((tool - w).norm() - 0.08).abs() < 1e-12);
        assert!((w.z - 0.30).abs() < 1e-12);
    }
    // The wrist's region, sampled.
    let (l1, l2) = (&model.joints()[0].limits, &model.joints()[1].limits);
    let steps = |l: &armkit::model::JointLimits| ((l.upper - l.lower).to_degrees() * 2.0) as usize;
    let (n1, n2) = (steps(l1), steps(l2));
    let mut wrists = Vec::with_capacity((n1 + 1) * (n2 + 1));
    for i in 0..=n1 {
        for j in 0..=n2 {
            let q = [
                l1.lower + (l1.upper - l1.lower) * i as f64 / n1 as f64,
                l2.lower + (l2.upper - l2.lower) * j as f64 / n2 as f64,
                0.0,
                0.0,
            ];
            forward_kinematics(&model, &mut data, &q).unwrap();
            let w = data.joint_frames()[3].translation;
            wrists.push([w.x, w.y]);
        }
    }
    let spec = MapSpec::for_model(&model, 0.05, 200, Builder::InverseKinematics);
    let map = reach::build(&model, &spec, 2, &mut |_, _| {}).unwrap();
    let layout = map.layout();
    let (tool, m) = (0.08f64, 0.005);
    let (mut sure_in, mut sure_out, mut missed, mut false_positive) = (0, 0, 0, 0);
    for cell in 0..layout.cell_count() {
        let c = layout.cell_center(cell);
        let dz = (c[2] - 0.30).abs();
        let said = map.reachable()[cell] != 0;
        if dz - m > tool {
            sure_out += 1;
            false_positive += said as usize;
            continue;
        }
        let (mut near, mut far) = (f64::INFINITY, 0.0f64);
        for w in &wrists {
            let d = ((c[0] - w[0]).powi(2) + (c[1] - w[1]).powi(2)).sqrt();
            near = near.min(d);
            far = far.max(d);
        }
        let rho_hi = (tool * tool - (dz - m).max(0.0).powi(2)).max(0.0).sqrt();
        let rho_lo = (tool * tool - (dz + m).powi(2)).max(0.0).sqrt();
        if dz + m <= tool && near + m <= rho_lo && rho_hi <= far - m {
            sure_in += 1;
            missed += (!said) as usize;
        } else if rho_hi < near - m || rho_lo > far + m {
            sure_out += 1;
            false_positive += said as usize;
        }
    }
    eprintln!("arm4 0.05 m: {sure_in} cells surely reachable ({missed} missed), {sure_out} surely not ({false_positive} said reachable), {} reachable in the map", map.reachable_cells());
    assert!(sure_in > 200, "{sure_in}");
    assert_eq!(false_positive, 0);
    assert!(
        missed as f64 <= 0.01 * sure_in as f64,
        "{missed} of {sure_in}"
    );
    // The query ignores the rotation of a position-only map.
    let mut agree = 0;
    for _ in 0..2000 {
        let q = random_q(&model, &mut rng);
        let tool = *forward_kinematics(&model, &mut data, &q).unwrap();
        let turned = Pose {
            rotation: Pose::rot_x(1.0).rotation * tool.rotation,
            translation: tool.translation,
        };
        assert_eq!(map.query(&tool), map.query(&turned));
        agree += map.query(&tool) as usize;
    }
    // Reached points are mostly inside the map's boundary (those near it
    // may fall either side).
    assert!(agree > 1800, "{agree}");
}

#[test]
fn gantry9s_box_holds_every_tool_position_and_is_the_rails_plus_the_arm() {
    let model = robot("gantry9");
    let bound = ReachBox::of_model(&model).unwrap();
    let (lower, upper) = (bound.lower(), bound.upper());
    let mut data = Data::new(&model);
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    let (mut low, mut high) = (
        Vector3::repeat(f64::INFINITY),
        Vector3::repeat(f64::NEG_INFINITY),
    );
    for s in 0..200_000 {
        let mut q = random_q(&model, &mut rng);
        // Every tenth sample with the rails at their ends.
        if s % 10 == 0 {
            for (v, j) in q.iter_mut().zip(model.joints()).take(3) {
                *v = if rng.gen_bool(0.5) {
                    j.limits.lower
                } else {
                    j.limits.upper
                };
            }
        }
        let p = forward_kinematics(&model, &mut data, &q)
            .unwrap()
            .translation;
        for a in 0..3 {
            assert!(
                p[a] >= lower[a] && p[a] <= upper[a],
                "{p:?} outside {lower:?}..{upper:?}"
            );
            low[a] = low[a].min(p[a]);
            high[a] = high[a].max(p[a]);
            assert!(!bound.excludes(&p), "{p:?}");
        }
    }
    // The rails' travel (9 m, 5 m, 5 m) plus at most twice the arm's reach
    // per axis; the sampled extent reaches within the arm's reach of each face.
    let side = upper - lower;
    eprintln!(
        "gantry9 box {:.3} x {:.3} x {:.3} m (arm reach {:.3} m), sampled extent {:.3} x {:.3} x {:.3} m, reach ball radius {:.3} m",
        side.x, side.y, side.z, bound.radius(),
        high.x - low.x, high.y - low.y, high.z - low.z,
        armkit::ik::ReachBound::of_model(&model).radius()
    );
    let mut sides: Vec<f64> = side.iter().copied().collect();
    sides.sort_by(f64::total_cmp);
    let arm = bound.radius();
    assert!(arm > 1.0 && arm < 2.5, "{arm}");
    for (s, rail) in sides.iter().zip([5.0, 5.0, 9.0]) {
        assert!((s - rail - 2.0 * arm).abs() < 1e-9, "{sides:?} {arm}");
    }
    for a in 0..3 {
        assert!(
            low[a] - lower[a] < arm && upper[a] - high[a] < arm,
            "{a}: {low:?} {high:?}"
        );
    }
    // Beyond the radius from the core box is excluded, within it not: along
    // each axis from the middle of a face, and past a corner.
    let middle = (lower + upper) * 0.5;
    for a in 0..3 {
        for (face, out) in [(upper[a], 1.0), (lower[a], -1.0)] {
            let mut p = middle;
            p[a] = face + out * 0.01;
            assert!(bound.excludes(&p), "{p:?}");
            p[a] = face - out * 0.01;
            assert!(!bound.excludes(&p), "{p:?}");
        }
    }
    // The margin: REACH_MARGIN relative plus as much in metres (about
    // 2.6e-9 m for this arm) is kept, not less.
    for a in 0..3 {
        let mut p = middle;
        p[a] = upper[a] + 1.5e-9;
        assert!(!bound.excludes(&p), "{p:?}");
        p[a] = upper[a] + 4e-9;
        assert!(bound.excludes(&p), "{p:?}");
    }
    assert!(bound.excludes(&upper));
    assert!(bound.excludes(&lower));
    let corner = upper - Vector3::repeat(arm * (1.0 - 1.0 / 3f64.sqrt()) + 0.01);
    assert!(!bound.excludes(&corner), "{corner:?}");
    // A rail without limits has no box; a limited one has the rail's
    // travel plus the arm's reach.
    use armkit::model::DhLink;
    let links2 = [
        DhLink::revolute(0.3, 0.4, 0.0).with_limits(-3.0, 3.0),
        DhLink::revolute(0.0, 0.3, 0.0).with_limits(-3.0, 3.0),
    ];
    let rail = |limits: Option<(f64, f64)>| {
        let mut links = vec![match limits {
            Some((lo, hi)) => DhLink::prismatic(0.0, 0.0, 0.0).with_limits(lo, hi),
            None => DhLink::prismatic(0.0, 0.0, 0.0),
        }];
        links.extend(links2);
        Model::from_dh("rail", armkit::model::DhConvention::Standard, &links).unwrap()
    };
    let e = ReachBox::of_model(&rail(None)).unwrap_err().to_string();
    assert!(e.contains("`rail` has no finite reach bound"), "{e}");
    let e = ReachBox::of_model(&rail(Some((0.0, f64::INFINITY))))
        .unwrap_err()
        .to_string();
    assert!(e.contains("`rail` has no finite reach bound"), "{e}");
    let railed = ReachBox::of_model(&rail(Some((-0.5, 2.0)))).unwrap();
    assert!((railed.radius() - 0.7).abs() < 1e-12, "{}", railed.radius());
    let extent = railed.upper() - railed.lower();
    assert!(
        (extent.z - 2.5 - 1.4).abs() < 1e-12 && (extent.x - 1.4).abs() < 1e-12,
        "{extent:?}"
    );
    assert!(
        (railed.upper().z - 2.0 - 0.3 - 0.7).abs() < 1e-12,
        "{:?}",
        railed.upper()
    );
    // Far smaller than the cube around the reach ball it replaces.
    let ball = armkit::ik::ReachBound::of_model(&model).radius();
    assert!(side.x * side.y * side.z < 0.1 * (2.0 * ball).powi(3));
    let layout = MapLayout::new(
        &model,
        &MapSpec::for_model(&model, 0.25, 20, Builder::InverseKinematics),
    )
    .unwrap();
    for a in 0..3 {
        assert_eq!(layout.dims()[a], (side[a] / 0.25).ceil() as usize);
        assert!(
            layout.origin()[a] <= lower[a]
                && layout.origin()[a] + layout.dims()[a] as f64 * 0.25 >= upper[a]
        );
    }
}
