//! The scene the page draws: links with their shapes, and each link's world
//! transform at each frame, computed here by armkit's forward kinematics, so
//! that the page does no kinematics. Written as JSON (the format is at the
//! top of `assets/viewer.js`).

use armkit::math::Pose;
use nalgebra::UnitQuaternion;

use crate::mesh::MeshBuffer;

/// Most frames a scene keeps (evenly spaced, the last one always): enough
/// for a smooth motion, small enough for light reports.
pub const MAX_FRAMES: usize = 300;

/// A placement in a link's frame: translation (m) and rotation.
pub type Placement = Pose;

/// What a link is drawn with, in the link's frame (metres).
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    /// A capsule (cylinder with round ends) from `from` to `to`.
    Capsule {
        /// One end's centre.
        from: [f64; 3],
        /// The other end's centre.
        to: [f64; 3],
        /// Radius, m.
        radius: f64,
    },
    /// A box centred at `origin`, edges `size` along the origin's axes.
    Box {
        /// Edge lengths, m.
        size: [f64; 3],
        /// Centre and axes.
        origin: Placement,
    },
    /// A cylinder along the origin's z axis, centred at it.
    Cylinder {
        /// Radius, m.
        radius: f64,
        /// Length along z, m.
        length: f64,
        /// Centre and axes.
        origin: Placement,
    },
    /// A sphere centred at the origin.
    Sphere {
        /// Radius, m.
        radius: f64,
        /// Centre.
        origin: Placement,
    },
    /// A mesh of the scene's `meshes`, scaled per axis, then placed.
    Mesh {
        /// Index into [`Scene::meshes`].
        mesh: usize,
        /// Scale per axis (URDF `<mesh scale>`).
        scale: [f64; 3],
        /// Placement of the mesh's frame.
        origin: Placement,
    },
}

/// One shape and its colour (RGBA in 0..1; `None`: the robot colour).
#[derive(Clone, Debug, PartialEq)]
pub struct Visual {
    /// The geometry.
    pub shape: Shape,
    /// Its colour.
    pub color: Option<[f64; 4]>,
}

/// A rigid body of the robot as drawn.
#[derive(Clone, Debug, PartialEq)]
pub struct Link {
    /// Name (the URDF link's, or `base`, the joint's name, `end effector`).
    pub name: String,
    /// Shapes in the link's frame.
    pub visuals: Vec<Visual>,
}

/// A point marked in the scene (a target, a singular pose), world frame.
#[derive(Clone, Debug, PartialEq)]
pub struct Marker {
    /// Position, m.
    pub at: [f64; 3],
    /// RGB in 0..1.
    pub color: [f64; 3],
    /// What it marks.
    pub label: String,
}

/// A flexible beam drawn bent: its centre line at each frame as computed
/// (`samples`) and undeflected (`straight`), world frame; the page draws
/// `straight + magnification (samples - straight)`.
#[derive(Clone, Debug, PartialEq)]
pub struct BeamLine {
    /// Deflection magnification the page applies (stated on the page).
    pub magnification: f64,
    /// Centre-line points per frame, deflected.
    pub samples: Vec<Vec<[f64; 3]>>,
    /// The same points without deflection.
    pub straight: Vec<Vec<[f64; 3]>>,
}

/// Everything the page draws.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Scene {
    /// Caption.
    pub title: String,
    /// Joint names (the configuration's order).
    pub joints: Vec<String>,
    /// Frame times, s.
    pub times: Vec<f64>,
    /// Configuration at each frame (rad or m).
    pub configurations: Vec<Vec<f64>>,
    /// The links.
    pub links: Vec<Link>,
    /// World pose of each link at each frame: `poses[frame][link]`.
    pub poses: Vec<Vec<Pose>>,
    /// Meshes the links' [`Shape::Mesh`] name.
    pub meshes: Vec<MeshBuffer>,
    /// End-effector path, world frame, m.
    pub path: Vec<[f64; 3]>,
    /// Per path point: inside a marked region (drawn red, e.g. singular).
    pub path_flags: Vec<bool>,
    /// Markers.
    pub markers: Vec<Marker>,
    /// A beam drawn bent, if any.
    pub beam: Option<BeamLine>,
    /// What could not be drawn as given (an unreadable mesh), for the user.
    pub warnings: Vec<String>,
}

/// The frames kept of `n`: all when `n <= MAX_FRAMES`, else evenly spaced
/// with the first and the last.
pub fn decimate(n: usize) -> Vec<usize> {
    if n <= MAX_FRAMES {
        return (0..n).collect();
    }
    let mut picks: Vec<usize> = (0..MAX_FRAMES)
        .map(|k| k * (n - 1) / (MAX_FRAMES - 1))
        .collect();
    picks.dedup();
    picks
}

/// A magnification factor for people: `50`, `2.5`.
pub fn format_factor(v: f64) -> String {
    let s = format!("{v:.3}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// A number rounded to 12 significant digits, in its shortest form: the
/// page's transforms stay within 1e-11 of armkit's (relative), half the
/// size of full precision.
fn num(v: f64) -> serde_json::Value {
    if !v.is_finite() {
        return serde_json::Value::Null;
    }
    let rounded: f64 = format!("{v:.11e}").parse().unwrap_or(v);
    serde_json::json!(rounded)
}

/// A length for drawing only (paths, beams): rounded to a micrometre.
fn micrometres(values: &[f64; 3]) -> serde_json::Value {
    serde_json::Value::Array(
        values
            .iter()
            .map(|&v| {
                if v.is_finite() {
                    serde_json::json!((v * 1e6).round() / 1e6)
                } else {
                    serde_json::Value::Null
                }
            })
            .collect(),
    )
}

fn nums(values: &[f64]) -> serde_json::Value {
    serde_json::Value::Array(values.iter().map(|&v| num(v)).collect())
}

/// `[x, y, z, qx, qy, qz, qw]` of a pose (three.js's quaternion order).
fn pose_json(pose: &Pose) -> serde_json::Value {
    let q = UnitQuaternion::from_matrix(&pose.rotation);
    let t = pose.translation;
    nums(&[t.x, t.y, t.z, q.i, q.j, q.k, q.w])
}

fn color_json(color: &Option<[f64; 4]>) -> serde_json::Value {
    color.map_or(serde_json::Value::Null, |c| nums(&c))
}

fn visual_json(visual: &Visual) -> serde_json::Value {
    let color = color_json(&visual.color);
    match &visual.shape {
        Shape::Capsule { from, to, radius } => serde_json::json!({
            "kind": "capsule", "from": nums(from), "to": nums(to), "radius": num(*radius), "color": color,
        }),
        Shape::Box { size, origin } => serde_json::json!({
            "kind": "box", "size": nums(size), "origin": pose_json(origin), "color": color,
        }),
        Shape::Cylinder {
            radius,
            length,
            origin,
        } => serde_json::json!({
            "kind": "cylinder", "radius": num(*radius), "length": num(*length),
            "origin": pose_json(origin), "color": color,
        }),
        Shape::Sphere { radius, origin } => serde_json::json!({
            "kind": "sphere", "radius": num(*radius), "origin": pose_json(origin), "color": color,
        }),
        Shape::Mesh {
            mesh,
            scale,
            origin,
        } => serde_json::json!({
            "kind": "mesh", "mesh": mesh, "scale": nums(scale), "origin": pose_json(origin), "color": color,
        }),
    }
}

fn mesh_json(mesh: &MeshBuffer) -> serde_json::Value {
    let positions: Vec<u8> = mesh
        .positions
        .iter()
        .flat_map(|v| v.to_le_bytes())
        .collect();
    let indices: Vec<u8> = mesh.indices.iter().flat_map(|v| v.to_le_bytes()).collect();
    serde_json::json!({ "positions": base64(&positions), "indices": base64(&indices) })
}

/// Standard base64 with padding (what the page's `atob` reads).
fn base64(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            *chunk.get(1).unwrap_or(&0),
            *chunk.get(2).unwrap_or(&0),
        ];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(ALPHABET[((n >> (18 - 6 * k)) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

impl Scene {
    /// The largest distance from the world origin of any link origin or
    /// path point, m (at least 0.2): sizes the floor, the camera, markers.
    pub fn reach(&self) -> f64 {
        let links = self.poses.iter().flatten().map(|p| p.translation.norm());
        let path = self
            .path
            .iter()
            .map(|p| (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt());
        links.chain(path).fold(0.2, f64::max)
    }

    /// The scene as the JSON the page reads.
    pub fn to_json(&self) -> serde_json::Value {
        let links: Vec<serde_json::Value> = self
            .links
            .iter()
            .map(|l| serde_json::json!({"name": l.name, "shapes": l.visuals.iter().map(visual_json).collect::<Vec<_>>()}))
            .collect();
        let beam = self.beam.as_ref().map(|b| {
            let lines = |frames: &Vec<Vec<[f64; 3]>>| -> Vec<serde_json::Value> {
                frames
                    .iter()
                    .map(|f| serde_json::Value::Array(f.iter().map(micrometres).collect()))
                    .collect()
            };
            serde_json::json!({"magnification": num(b.magnification), "samples": lines(&b.samples), "straight": lines(&b.straight)})
        });
        serde_json::json!({
            "title": self.title,
            "joints": self.joints,
            "times": nums(&self.times),
            "q": self.configurations.iter().map(|q| nums(q)).collect::<Vec<_>>(),
            "links": links,
            "poses": self.poses.iter().map(|f| f.iter().map(pose_json).collect::<Vec<_>>()).collect::<Vec<_>>(),
            "meshes": self.meshes.iter().map(mesh_json).collect::<Vec<_>>(),
            "path": self.path.iter().map(micrometres).collect::<Vec<_>>(),
            "path_flags": self.path_flags.iter().map(|&f| u8::from(f)).collect::<Vec<_>>(),
            "markers": self.markers.iter().map(|m| serde_json::json!({"at": nums(&m.at), "color": nums(&m.color), "label": m.label})).collect::<Vec<_>>(),
            "beam": beam,
            "reach": num(self.reach()),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_matches_the_standard_alphabet_and_padding() {
        assert_eq!(base64(b""), "");
        assert_eq!(base64(b"f"), "Zg==");
        assert_eq!(base64(b"fo"), "Zm8=");
        assert_eq!(base64(b"foo"), "Zm9v");
        assert_eq!(base64(b"foobar"), "Zm9vYmFy");
        assert_eq!(base64(&[0xff, 0xfe]), "//4=");
    }

    #[test]
    fn decimation_keeps_the_ends_and_at_most_max_frames() {
        assert_eq!(decimate(3), vec![0, 1, 2]);
        let picks = decimate(1001);
        assert_eq!(picks.len(), MAX_FRAMES);
        assert_eq!((picks[0], *picks.last().unwrap()), (0, 1000));
    }

    #[test]
    fn numbers_keep_twelve_digits() {
        let v = num(std::f64::consts::PI).as_f64().unwrap();
        assert!((v - std::f64::consts::PI).abs() < 1e-11 && v != std::f64::consts::PI);
        assert_eq!(num(0.5).to_string(), "0.5");
        assert_eq!(num(f64::NAN), serde_json::Value::Null);
    }
}
