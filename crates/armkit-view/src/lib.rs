//! armkit's 3-D view: a robot moving along a motion, drawn in one offline
//! HTML page by a vendored three.js, with every link placed at the world
//! transform armkit's forward kinematics computed (the page does no
//! kinematics, and `window.armkitView` reads the transforms back for tests).
//!
//! * [`chain_scene`]: DH and built-in robots (capsules between joint frames,
//!   boxes for prismatic stages);
//! * [`urdf_scene`]: URDF robots with their `<visual>` shapes and meshes
//!   (STL, OBJ, Collada, read here by [`read_mesh`]);
//! * [`standalone_page`] (scripts inlined) and [`viewer_block`] with
//!   [`Scripts::Shared`] (one asset file beside several pages).
//!
//! World frame z up, metres, seconds.

mod chain;
mod dae;
mod html;
mod mesh;
mod scene;
mod urdf;

pub use chain::{chain_link_names, chain_link_poses, chain_scene};
pub use html::{
    asset_script, standalone_page, viewer_block, Scripts, ASSET_FILE, STYLE, THREE_BUNDLE,
    THREE_LICENSE, VIEWER_SCRIPT,
};
pub use mesh::{read_mesh, MeshBuffer, MeshFormat};
pub use scene::{
    decimate, format_factor, BeamLine, Link, Marker, Placement, Scene, Shape, Visual, MAX_FRAMES,
};
pub use urdf::{urdf_scene, UrdfSource};
