//! DH and built-in robots drawn from their joint frames: a capsule from each
//! joint frame to the next (the link's length), a cylinder on each revolute
//! joint's axis, a rail box over each prismatic joint's travel and a carriage
//! box on its frame, a sphere at the end effector. Link frames are armkit's
//! joint frames ([`armkit::kinematics::Data::joint_frames`]), so the page's
//! transforms are armkit's FK.

use armkit::math::{Pose, Vector3};
use armkit::model::{JointKind, Model};

use crate::scene::{decimate, Link, Scene, Shape, Visual};

/// Names of the links [`chain_scene`] draws for `model`: `base`, one per
/// chain joint (the joint's name), `end effector`.
pub fn chain_link_names(model: &Model) -> Vec<String> {
    let mut names = vec!["base".to_string()];
    names.extend(model.chain_joints().iter().map(|j| j.name.clone()));
    names.push("end effector".into());
    names
}

/// World poses of [`chain_link_names`]'s links at configuration `q`, from
/// armkit's forward kinematics.
pub fn chain_link_poses(
    model: &Model,
    data: &mut armkit::Data,
    q: &[f64],
) -> Result<Vec<Pose>, armkit::Error> {
    let end = *armkit::forward_kinematics(model, data, q)?;
    let mut poses = vec![*model.base()];
    poses.extend_from_slice(data.joint_frames());
    poses.push(end);
    Ok(poses)
}

/// The link radius for a robot whose links reach `reach` metres: thin
/// enough to see the chain, thick enough to see at the scale of the floor.
fn link_radius(reach: f64) -> f64 {
    (0.03 * reach).clamp(0.008, 0.08)
}

fn point(v: &Vector3<f64>) -> [f64; 3] {
    [v.x, v.y, v.z]
}

/// The shapes of each link in its own frame.
fn chain_links(model: &Model, reach: f64) -> Vec<Link> {
    let radius = link_radius(reach);
    let joints = model.chain_joints();
    let placements = model.joint_placements();
    let names = chain_link_names(model);
    let mut links: Vec<Link> = names
        .into_iter()
        .map(|name| Link {
            name,
            visuals: Vec::new(),
        })
        .collect();
    // Where the next frame's origin sits in each link's frame before the
    // next joint moves: the next placement (joint 0's is given in the world
    // frame, so the base link sees it through the base pose).
    let base_inverse = model.base().inverse();
    let next_origin = |link: usize| -> Pose {
        match link {
            0 => placements
                .first()
                .map_or(base_inverse * *model.end_effector_placement(), |p| {
                    base_inverse * *p
                }),
            l if l < joints.len() => placements[l],
            _ => *model.end_effector_placement(),
        }
    };
    let gray = Some([0.55, 0.57, 0.6, 1.0]);
    for (l, link) in links.iter_mut().enumerate().take(joints.len() + 1) {
        let next = next_origin(l);
        let to = point(&next.translation);
        if next.translation.norm() > 1e-9 {
            link.visuals.push(Visual {
                shape: Shape::Capsule {
                    from: [0.0; 3],
                    to,
                    radius,
                },
                color: None,
            });
        }
        // The next joint's housing (revolute) or rail (prismatic), in this
        // link: it does not move with the joint.
        let Some(joint) = joints.get(l) else { continue };
        let visual = match joint.kind {
            JointKind::Prismatic => {
                // The rail runs from the joint's origin over the whole travel,
                // so that it meets the link it hangs from.
                let (lower, upper) = (
                    joint.limits.lower.max(-reach).min(0.0),
                    joint.limits.upper.min(reach).max(0.0),
                );
                let (lower, upper) = if upper > lower {
                    (lower, upper)
                } else {
                    (0.0, reach)
                };
                Visual {
                    shape: Shape::Box {
                        size: [1.4 * radius, 1.4 * radius, upper - lower + 2.0 * radius],
                        origin: next * Pose::trans_z(0.5 * (lower + upper)),
                    },
                    color: gray,
                }
            }
            _ => Visual {
                shape: Shape::Cylinder {
                    radius: 1.35 * radius,
                    length: 3.2 * radius,
                    origin: next,
                },
                color: gray,
            },
        };
        link.visuals.push(visual);
    }
    for (j, joint) in joints.iter().enumerate() {
        if joint.kind == JointKind::Prismatic {
            links[j + 1].visuals.push(Visual {
                shape: Shape::Box {
                    size: [2.4 * radius; 3],
                    origin: Pose::identity(),
                },
                color: None,
            });
        }
    }
    if let Some(end) = links.last_mut() {
        end.visuals.push(Visual {
            shape: Shape::Sphere {
                radius: 1.2 * radius,
                origin: Pose::identity(),
            },
            color: Some([0.12, 0.3, 0.47, 1.0]),
        });
    }
    links
}

/// The scene of `model` moving through `configurations` at `times` (at
/// most [`crate::scene::MAX_FRAMES`] frames kept), the end effector's path
/// drawn when there is more than one frame.
pub fn chain_scene(
    model: &Model,
    times: &[f64],
    configurations: &[Vec<f64>],
) -> Result<Scene, armkit::Error> {
    let mut data = armkit::Data::new(model);
    let n = times.len().min(configurations.len());
    let mut poses = Vec::new();
    let mut path = Vec::new();
    for q in &configurations[..n] {
        let frame = chain_link_poses(model, &mut data, q)?;
        path.push(point(&frame[frame.len() - 1].translation));
        poses.push(frame);
    }
    let picks = decimate(n);
    let mut scene = Scene {
        title: model.name().to_string(),
        joints: model.joints().iter().map(|j| j.name.clone()).collect(),
        times: picks.iter().map(|&k| times[k]).collect(),
        configurations: picks.iter().map(|&k| configurations[k].clone()).collect(),
        poses: picks.iter().map(|&k| poses[k].clone()).collect(),
        path_flags: vec![false; if n > 1 { path.len() } else { 0 }],
        path: if n > 1 { path } else { Vec::new() },
        ..Scene::default()
    };
    let reach = scene.reach();
    scene.links = chain_links(model, reach);
    Ok(scene)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn links_follow_armkit_fk_and_capsules_reach_the_next_frame() {
        let model = armkit::robots::by_name("puma560").unwrap();
        let q = vec![0.3, -0.5, 0.8, 0.1, 0.7, -0.2];
        let scene = chain_scene(
            &model,
            &[0.0, 1.0],
            &[model.neutral_configuration(), q.clone()],
        )
        .unwrap();
        assert_eq!(scene.links.len(), model.chain_joints().len() + 2);
        let mut data = armkit::Data::new(&model);
        let end = *armkit::forward_kinematics(&model, &mut data, &q).unwrap();
        let last = scene.poses[1].last().unwrap();
        assert!((last.translation - end.translation).norm() < 1e-15);
        // Each capsule ends at the next link's origin at this configuration
        // (the next joint is revolute: its motion keeps its origin).
        for l in 0..model.chain_joints().len() {
            for visual in &scene.links[l].visuals {
                if let Shape::Capsule { to, .. } = visual.shape {
                    let world = scene.poses[1][l].transform_point(&Vector3::from(to));
                    let next = scene.poses[1][l + 1].translation;
                    assert!((world - next).norm() < 1e-12, "link {l}");
                }
            }
        }
        assert_eq!(scene.path.len(), 2);
    }

    #[test]
    fn prismatic_joints_get_a_rail_and_a_carriage() {
        let model = armkit::robots::by_name("stanford").unwrap();
        let scene = chain_scene(&model, &[0.0], &[model.neutral_configuration()]).unwrap();
        let boxes = scene
            .links
            .iter()
            .flat_map(|l| &l.visuals)
            .filter(|v| matches!(v.shape, Shape::Box { .. }))
            .count();
        assert_eq!(
            boxes, 2,
            "one rail and one carriage for the stanford arm's d3"
        );
        assert!(scene.path.is_empty());
    }
}
