//! Mesh files read once, in Rust, into compact triangle buffers that the
//! page draws with three.js's core alone: STL (binary and ASCII, `stl_io`),
//! Wavefront OBJ (`tobj`) and Collada `.dae` (`crate::dae`, over quick-xml).
//! Coordinates in the mesh file's own frame and units (a Collada
//! `<unit meter>` is applied; the URDF's `scale` is applied by the page).

use std::path::Path;

/// A triangle mesh: vertex positions (x, y, z per vertex, f32, the file's
/// frame, metres after the file's own unit) and triangle indices (three per
/// triangle, into the vertices).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MeshBuffer {
    /// x, y, z of each vertex.
    pub positions: Vec<f32>,
    /// Three vertex indices per triangle.
    pub indices: Vec<u32>,
    /// The mesh's own colour (RGBA in 0..1) when the file gives one
    /// (an OBJ's `.mtl` diffuse colour, a Collada effect's diffuse colour).
    pub color: Option<[f64; 4]>,
}

impl MeshBuffer {
    /// Number of triangles.
    pub fn triangles(&self) -> usize {
        self.indices.len() / 3
    }

    /// The axis-aligned bounds `(min, max)` of the vertices, `None` when empty.
    pub fn bounds(&self) -> Option<([f64; 3], [f64; 3])> {
        let mut chunks = self.positions.chunks_exact(3);
        let first = chunks.next()?;
        let mut low = [first[0] as f64, first[1] as f64, first[2] as f64];
        let mut high = low;
        for p in chunks {
            for c in 0..3 {
                low[c] = low[c].min(p[c] as f64);
                high[c] = high[c].max(p[c] as f64);
            }
        }
        Some((low, high))
    }

    /// Checks that every index names a vertex and that there is a triangle.
    fn validated(self, file: &Path) -> Result<MeshBuffer, String> {
        let vertices = self.positions.len() / 3;
        if self.indices.is_empty() {
            return Err(format!("{}: no triangles", file.display()));
        }
        if let Some(bad) = self.indices.iter().find(|&&i| i as usize >= vertices) {
            return Err(format!(
                "{}: a triangle names vertex {bad} of {vertices}",
                file.display()
            ));
        }
        if self.positions.iter().any(|v| !v.is_finite()) {
            return Err(format!("{}: a vertex is not finite", file.display()));
        }
        Ok(self)
    }
}

/// Mesh file formats, by extension (case-insensitive).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MeshFormat {
    /// STL, binary or ASCII.
    Stl,
    /// Wavefront OBJ (with its `.mtl` when present).
    Obj,
    /// Collada.
    Collada,
}

impl MeshFormat {
    /// The format of `path` from its extension, `None` when unsupported.
    pub fn of(path: &Path) -> Option<MeshFormat> {
        let extension = path.extension()?.to_str()?.to_ascii_lowercase();
        match extension.as_str() {
            "stl" => Some(MeshFormat::Stl),
            "obj" => Some(MeshFormat::Obj),
            "dae" => Some(MeshFormat::Collada),
            _ => None,
        }
    }
}

/// Reads the mesh file at `path`. The error names the file and says why.
pub fn read_mesh(path: &Path) -> Result<MeshBuffer, String> {
    let format = MeshFormat::of(path).ok_or_else(|| {
        format!(
            "{}: not a mesh format armkit reads (.stl, .obj, .dae)",
            path.display()
        )
    })?;
    let mesh = match format {
        MeshFormat::Stl => read_stl(path)?,
        MeshFormat::Obj => read_obj(path)?,
        MeshFormat::Collada => {
            let text = std::fs::read_to_string(path)
                .map_err(|e| format!("{}: cannot read: {e}", path.display()))?;
            crate::dae::parse(&text).map_err(|e| format!("{}: {e}", path.display()))?
        }
    };
    mesh.validated(path)
}

fn read_stl(path: &Path) -> Result<MeshBuffer, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("{}: cannot read: {e}", path.display()))?;
    let mut cursor = std::io::Cursor::new(bytes);
    let mesh = stl_io::read_stl(&mut cursor)
        .map_err(|e| format!("{}: not a readable STL file: {e}", path.display()))?;
    let positions = mesh.vertices.iter().flat_map(|v| v.0).collect();
    let indices = mesh
        .faces
        .iter()
        .flat_map(|f| f.vertices)
        .map(|i| u32::try_from(i).unwrap_or(u32::MAX))
        .collect();
    Ok(MeshBuffer {
        positions,
        indices,
        color: None,
    })
}

fn read_obj(path: &Path) -> Result<MeshBuffer, String> {
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ..Default::default()
    };
    let (models, materials) = tobj::load_obj(path, &options)
        .map_err(|e| format!("{}: not a readable OBJ file: {e}", path.display()))?;
    // A missing or broken .mtl only loses the colour.
    let materials = materials.unwrap_or_default();
    let mut mesh = MeshBuffer::default();
    for model in &models {
        let base = (mesh.positions.len() / 3) as u32;
        mesh.positions.extend_from_slice(&model.mesh.positions);
        mesh.indices
            .extend(model.mesh.indices.iter().map(|&i| i.saturating_add(base)));
        if mesh.color.is_none() {
            mesh.color = model
                .mesh
                .material_id
                .and_then(|m| materials.get(m))
                .and_then(|m| m.diffuse)
                .map(|[r, g, b]| [r as f64, g as f64, b as f64, 1.0]);
        }
    }
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("armkit-view-mesh-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        dir.join(name)
    }

    const ASCII_STL: &str = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 2 0\nendloop\nendfacet\nfacet normal 0 0 1\nouter loop\nvertex 1 0 0\nvertex 0 2 0\nvertex 0 0 3\nendloop\nendfacet\nendsolid t\n";

    #[test]
    fn ascii_and_binary_stl_give_the_same_triangles() {
        let ascii = scratch("t.stl");
        std::fs::write(&ascii, ASCII_STL).unwrap();
        let a = read_mesh(&ascii).unwrap();
        assert_eq!((a.positions.len() / 3, a.triangles()), (4, 2));
        assert_eq!(a.bounds(), Some(([0.0; 3], [1.0, 2.0, 3.0])));
        // The same two triangles, written as binary STL.
        let mut bytes = vec![0u8; 80];
        bytes.extend(2u32.to_le_bytes());
        for triangle in [
            [[0., 0., 0.], [1., 0., 0.], [0., 2., 0.]],
            [[1., 0., 0.], [0., 2., 0.], [0., 0., 3.]],
        ] {
            bytes.extend([0f32, 0., 1.].iter().flat_map(|v| v.to_le_bytes()));
            for v in triangle {
                bytes.extend(v.iter().flat_map(|c: &f32| c.to_le_bytes()));
            }
            bytes.extend([0u8, 0]);
        }
        let binary = scratch("b.STL");
        std::fs::write(&binary, bytes).unwrap();
        let b = read_mesh(&binary).unwrap();
        assert_eq!(
            (b.positions.clone(), b.indices.clone()),
            (a.positions, a.indices)
        );
    }

    #[test]
    fn obj_with_quads_is_triangulated_and_unknown_formats_are_named() {
        let obj = scratch("q.obj");
        std::fs::write(&obj, "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n").unwrap();
        let mesh = read_mesh(&obj).unwrap();
        assert_eq!(mesh.triangles(), 2);
        let ply = scratch("x.ply");
        std::fs::write(&ply, "ply").unwrap();
        let err = read_mesh(&ply).unwrap_err();
        assert!(
            err.contains("x.ply") && err.contains(".stl, .obj, .dae"),
            "{err}"
        );
        let broken = scratch("broken.stl");
        std::fs::write(&broken, "solid x\nfacet nonsense").unwrap();
        assert!(read_mesh(&broken).unwrap_err().contains("broken.stl"));
    }
}
