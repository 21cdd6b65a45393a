//! URDF robots drawn with their own `<visual>` elements: boxes, cylinders,
//! spheres and meshes (STL, OBJ, Collada) with their origins and colours.
//!
//! Each URDF link below the chain's base is a link of the scene. Its world
//! transform comes from armkit's FK of the sub-chain from the base to that
//! link (`armkit::urdf::parse_str` with [`ChainSelection::between`]): links
//! on the chain take the configuration's leading joints, links off it (a
//! gripper's fingers, sensor mounts) take the configuration's value of each
//! joint they share with the chain and zero for the others.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use armkit::math::Pose;
use armkit::model::Model;
use armkit::urdf::ChainSelection;

use crate::mesh::{read_mesh, MeshBuffer};
use crate::scene::{decimate, Link, Scene, Shape, Visual};

/// A URDF file and where its `package://` meshes are found.
#[derive(Clone, Debug)]
pub struct UrdfSource {
    /// The URDF file.
    pub path: PathBuf,
    /// The chain drawn (the model's base and tip).
    pub selection: ChainSelection,
    /// Folders that hold packages: `package://NAME/rest` is looked up as
    /// `FOLDER/NAME/rest` in each, then beside and above the URDF.
    pub package_paths: Vec<PathBuf>,
}

/// One drawn link: its sub-chain model and where its joints are in the
/// configuration.
struct LinkChain {
    model: Option<Model>,
    /// For each of the sub-chain's joints, its index in the configuration.
    map: Vec<Option<usize>>,
    /// The pose in the base frame of a link with no moving joint above it.
    fixed: Pose,
}

/// The pose of `link` in `base`'s frame when only fixed joints lie between.
fn fixed_pose(robot: &urdf_rs::Robot, base: &str, link: &str) -> Option<Pose> {
    let mut pose = Pose::identity();
    let mut at = link.to_string();
    while at != base {
        let joint = robot.joints.iter().find(|j| j.child.link == at)?;
        if !matches!(joint.joint_type, urdf_rs::JointType::Fixed) {
            return None;
        }
        pose = pose_of(&joint.origin) * pose;
        at = joint.parent.link.clone();
    }
    Some(pose)
}

impl UrdfSource {
    /// Resolves a `<mesh filename>`: `package://`, `file://`, absolute or
    /// relative to the URDF's folder. `None` when no candidate exists.
    pub fn resolve(&self, filename: &str) -> Option<PathBuf> {
        let folder = self.path.parent().unwrap_or(Path::new("."));
        if let Some(rest) = filename.strip_prefix("package://") {
            let (package, inner) = rest.split_once('/').unwrap_or((rest, ""));
            let mut candidates: Vec<PathBuf> = self
                .package_paths
                .iter()
                .map(|p| p.join(package).join(inner))
                .collect();
            // A URDF inside its package (PACKAGE/urdf/robot.urdf): the
            // folders above it.
            for ancestor in folder.ancestors() {
                candidates.push(ancestor.join(package).join(inner));
                if ancestor.file_name().and_then(|n| n.to_str()) == Some(package) {
                    candidates.push(ancestor.join(inner));
                }
            }
            return candidates.into_iter().find(|c| c.is_file());
        }
        let plain = filename.strip_prefix("file://").unwrap_or(filename);
        let path = Path::new(plain);
        let path = if path.is_absolute() {
            path.to_path_buf()
        } else {
            folder.join(path)
        };
        path.is_file().then_some(path)
    }
}

fn pose_of(origin: &urdf_rs::Pose) -> Pose {
    Pose::from_xyz_rpy(*origin.xyz, *origin.rpy)
}

/// The link's extent for a mesh that cannot be read: its collision
/// primitive when it has one, else a box reaching its child joints.
fn bounding_shape(link: &urdf_rs::Link, robot: &urdf_rs::Robot, visual_origin: Pose) -> Shape {
    for collision in &link.collision {
        let origin = pose_of(&collision.origin);
        match &collision.geometry {
            urdf_rs::Geometry::Box { size } => {
                return Shape::Box {
                    size: **size,
                    origin,
                }
            }
            urdf_rs::Geometry::Cylinder { radius, length }
            | urdf_rs::Geometry::Capsule { radius, length } => {
                return Shape::Cylinder {
                    radius: *radius,
                    length: *length,
                    origin,
                }
            }
            urdf_rs::Geometry::Sphere { radius } => {
                return Shape::Sphere {
                    radius: *radius,
                    origin,
                }
            }
            urdf_rs::Geometry::Mesh { .. } => {}
        }
    }
    let children: Vec<[f64; 3]> = robot
        .joints
        .iter()
        .filter(|j| j.parent.link == link.name)
        .map(|j| *j.origin.xyz)
        .collect();
    let mut low = [0.0f64; 3];
    let mut high = [0.0f64; 3];
    for c in &children {
        for a in 0..3 {
            low[a] = low[a].min(c[a]);
            high[a] = high[a].max(c[a]);
        }
    }
    let size = [0, 1, 2].map(|a| (high[a] - low[a]).max(0.05));
    let centre = [0, 1, 2].map(|a| 0.5 * (high[a] + low[a]));
    if children.is_empty() {
        return Shape::Box {
            size,
            origin: visual_origin,
        };
    }
    Shape::Box {
        size,
        origin: Pose::from_translation(centre.into()),
    }
}

/// The links below the base, in the file's order (base first).
fn links_below<'r>(robot: &'r urdf_rs::Robot, base: &str) -> Vec<&'r urdf_rs::Link> {
    let mut names = vec![base.to_string()];
    let mut k = 0;
    while k < names.len() {
        let parent = names[k].clone();
        names.extend(
            robot
                .joints
                .iter()
                .filter(|j| j.parent.link == parent)
                .map(|j| j.child.link.clone()),
        );
        k += 1;
    }
    robot
        .links
        .iter()
        .filter(|l| names.contains(&l.name))
        .collect()
}

/// The scene of the URDF robot `model` (loaded from `source`) moving through
/// `configurations` at `times`. Unreadable meshes become their link's
/// bounding primitive, with a warning naming the file in
/// [`Scene::warnings`]; links that armkit cannot reach from the base (behind
/// a floating joint) are left out with a warning.
pub fn urdf_scene(
    source: &UrdfSource,
    model: &Model,
    times: &[f64],
    configurations: &[Vec<f64>],
) -> Result<Scene, String> {
    let text = std::fs::read_to_string(&source.path)
        .map_err(|e| format!("{}: cannot read: {e}", source.path.display()))?;
    let robot = urdf_rs::read_from_string(&text)
        .map_err(|e| format!("{}: cannot read its visuals: {e}", source.path.display()))?;
    let source_name = source.path.display().to_string();
    let base = match &source.selection.base {
        Some(base) => base.clone(),
        None => {
            let children: Vec<&str> = robot.joints.iter().map(|j| j.child.link.as_str()).collect();
            robot
                .links
                .iter()
                .find(|l| !children.contains(&l.name.as_str()))
                .map(|l| l.name.clone())
                .ok_or_else(|| format!("{source_name}: no root link"))?
        }
    };
    let joint_index: HashMap<&str, usize> = model
        .joints()
        .iter()
        .enumerate()
        .map(|(i, j)| (j.name.as_str(), i))
        .collect();
    let mut warnings = Vec::new();
    let mut links = Vec::new();
    let mut chains = Vec::new();
    let mut meshes: Vec<MeshBuffer> = Vec::new();
    let mut mesh_index: HashMap<PathBuf, Option<usize>> = HashMap::new();
    let materials: HashMap<&str, [f64; 4]> = robot
        .materials
        .iter()
        .filter_map(|m| Some((m.name.as_str(), *m.color.as_ref()?.rgba)))
        .collect();
    for link in links_below(&robot, &base) {
        let chain = if link.name == base {
            LinkChain {
                model: None,
                map: Vec::new(),
                fixed: Pose::identity(),
            }
        } else {
            match armkit::urdf::parse_str(
                &text,
                &source_name,
                &ChainSelection::between(base.clone(), link.name.clone()),
            ) {
                Ok(sub) => {
                    let map = sub
                        .joints()
                        .iter()
                        .map(|j| joint_index.get(j.name.as_str()).copied())
                        .collect();
                    LinkChain {
                        model: Some(sub),
                        map,
                        fixed: Pose::identity(),
                    }
                }
                // A link fixed to the base has no moving joint, so no model:
                // its constant pose.
                Err(e) => match fixed_pose(&robot, &base, &link.name) {
                    Some(pose) => LinkChain {
                        model: None,
                        map: Vec::new(),
                        fixed: pose,
                    },
                    None => {
                        warnings.push(format!("link `{}` is not drawn: {e}", link.name));
                        continue;
                    }
                },
            }
        };
        let mut visuals = Vec::new();
        for visual in &link.visual {
            let origin = pose_of(&visual.origin);
            let color = visual.material.as_ref().and_then(|m| {
                m.color
                    .as_ref()
                    .map(|c| *c.rgba)
                    .or_else(|| materials.get(m.name.as_str()).copied())
            });
            let shape = match &visual.geometry {
                urdf_rs::Geometry::Box { size } => Shape::Box {
                    size: **size,
                    origin,
                },
                urdf_rs::Geometry::Cylinder { radius, length }
                | urdf_rs::Geometry::Capsule { radius, length } => Shape::Cylinder {
                    radius: *radius,
                    length: *length,
                    origin,
                },
                urdf_rs::Geometry::Sphere { radius } => Shape::Sphere {
                    radius: *radius,
                    origin,
                },
                urdf_rs::Geometry::Mesh { filename, scale } => {
                    let scale = scale.as_ref().map_or([1.0; 3], |s| **s);
                    let loaded = match source.resolve(filename) {
                        None => Err(format!(
                            "{filename}: not found (looked beside the URDF and in --package-path)"
                        )),
                        Some(path) => match mesh_index.get(&path) {
                            Some(Some(index)) => Ok(*index),
                            Some(None) => {
                                Err(format!("{}: unreadable (see above)", path.display()))
                            }
                            None => match read_mesh(&path) {
                                Ok(mesh) => {
                                    meshes.push(mesh);
                                    mesh_index.insert(path, Some(meshes.len() - 1));
                                    Ok(meshes.len() - 1)
                                }
                                Err(e) => {
                                    mesh_index.insert(path, None);
                                    Err(e)
                                }
                            },
                        },
                    };
                    match loaded {
                        Ok(mesh) => {
                            let own = meshes[mesh].color;
                            visuals.push(Visual {
                                shape: Shape::Mesh {
                                    mesh,
                                    scale,
                                    origin,
                                },
                                color: color.or(own),
                            });
                            continue;
                        }
                        Err(e) => {
                            warnings.push(format!(
                                "mesh of link `{}` drawn as its bounding primitive: {e}",
                                link.name
                            ));
                            bounding_shape(link, &robot, origin)
                        }
                    }
                }
            };
            visuals.push(Visual { shape, color });
        }
        links.push(Link {
            name: link.name.clone(),
            visuals,
        });
        chains.push(chain);
    }
    let n = times.len().min(configurations.len());
    let picks = decimate(n);
    let mut data: Vec<Option<armkit::Data>> = chains
        .iter()
        .map(|c| c.model.as_ref().map(armkit::Data::new))
        .collect();
    let mut poses = Vec::new();
    let mut sub_q = Vec::new();
    for &k in &picks {
        let q = &configurations[k];
        let mut frame = Vec::with_capacity(chains.len());
        for (chain, data) in chains.iter().zip(data.iter_mut()) {
            let (Some(sub), Some(data)) = (&chain.model, data) else {
                frame.push(model.base() * &chain.fixed);
                continue;
            };
            sub_q.clear();
            sub_q.extend(
                chain
                    .map
                    .iter()
                    .map(|i| i.and_then(|i| q.get(i).copied()).unwrap_or(0.0)),
            );
            let pose = armkit::forward_kinematics(sub, data, &sub_q).map_err(|e| e.to_string())?;
            frame.push(*pose);
        }
        poses.push(frame);
    }
    let mut ee = armkit::Data::new(model);
    let mut path = Vec::new();
    if n > 1 {
        for q in &configurations[..n] {
            let p = armkit::forward_kinematics(model, &mut ee, q)
                .map_err(|e| e.to_string())?
                .translation;
            path.push([p.x, p.y, p.z]);
        }
    }
    Ok(Scene {
        title: model.name().to_string(),
        joints: model.joints().iter().map(|j| j.name.clone()).collect(),
        times: picks.iter().map(|&k| times[k]).collect(),
        configurations: picks.iter().map(|&k| configurations[k].clone()).collect(),
        links,
        poses,
        meshes,
        path_flags: vec![false; path.len()],
        path,
        warnings,
        ..Scene::default()
    })
}
