//! A small Collada (`.dae`) reader: the triangles of every geometry the
//! visual scene instantiates, with its node transforms, the `<unit meter>`
//! and `<up_axis>` applied, and the first diffuse colour its materials give.
//!
//! Why not a crate: the Collada crates on crates.io (`collada`, `dae-parser`)
//! have had no release for years; this reads what robot descriptions use
//! (`<triangles>`, `<polylist>`, `<polygons>` with `<p>` and `<vcount>`,
//! `<matrix>`, `<translate>`, `<rotate>`, `<scale>`) over quick-xml, which the
//! URDF parser already brings. Skinning, animation and textures are ignored.

use std::collections::HashMap;

use nalgebra::{Matrix4, Point3, Vector3};

use crate::mesh::MeshBuffer;

/// One element of the document: name (without prefix), attributes, text and
/// children.
#[derive(Debug, Default)]
struct Element {
    name: String,
    attributes: Vec<(String, String)>,
    text: String,
    children: Vec<Element>,
}

impl Element {
    fn attribute(&self, key: &str) -> Option<&str> {
        self.attributes
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, v)| v.as_str())
    }

    fn child(&self, name: &str) -> Option<&Element> {
        self.children.iter().find(|c| c.name == name)
    }

    fn children_named<'a>(&'a self, name: &'a str) -> impl Iterator<Item = &'a Element> + 'a {
        self.children.iter().filter(move |c| c.name == name)
    }

    /// Every element below this one (depth first) named `name`.
    fn descendants<'a>(&'a self, name: &str, found: &mut Vec<&'a Element>) {
        for child in &self.children {
            if child.name == name {
                found.push(child);
            }
            child.descendants(name, found);
        }
    }

    fn numbers(&self) -> Result<Vec<f64>, String> {
        self.text
            .split_ascii_whitespace()
            .map(|s| {
                s.parse::<f64>()
                    .map_err(|_| format!("<{}>: `{s}` is not a number", self.name))
            })
            .collect()
    }
}

fn local(name: &[u8]) -> String {
    let name = String::from_utf8_lossy(name);
    match name.rsplit_once(':') {
        Some((_, local)) => local.to_string(),
        None => name.to_string(),
    }
}

fn start_element(start: &quick_xml::events::BytesStart<'_>) -> Element {
    let attributes = start
        .attributes()
        .flatten()
        .map(|a| {
            let value = a
                .unescape_value()
                .map(|v| v.to_string())
                .unwrap_or_else(|_| String::from_utf8_lossy(&a.value).to_string());
            (local(a.key.as_ref()), value)
        })
        .collect();
    Element {
        name: local(start.name().as_ref()),
        attributes,
        ..Element::default()
    }
}

/// Parses the XML into a tree.
fn document(text: &str) -> Result<Element, String> {
    use quick_xml::events::Event;
    let mut reader = quick_xml::Reader::from_str(text);
    let mut stack = vec![Element::default()];
    loop {
        let event = reader
            .read_event()
            .map_err(|e| format!("malformed XML near byte {}: {e}", reader.buffer_position()))?;
        match event {
            Event::Start(start) => stack.push(start_element(&start)),
            Event::Empty(start) => {
                let element = start_element(&start);
                if let Some(parent) = stack.last_mut() {
                    parent.children.push(element);
                }
            }
            Event::Text(text) => {
                if let (Some(top), Ok(decoded)) = (stack.last_mut(), text.decode()) {
                    top.text.push_str(&decoded);
                    top.text.push(' ');
                }
            }
            Event::End(_) => {
                let element = stack.pop().ok_or("unbalanced XML")?;
                stack
                    .last_mut()
                    .ok_or("unbalanced XML")?
                    .children
                    .push(element);
            }
            Event::Eof => break,
            _ => {}
        }
    }
    let root = stack.pop().ok_or("empty document")?;
    if !stack.is_empty() {
        return Err("an element is not closed".into());
    }
    root.children
        .into_iter()
        .find(|e| e.name == "COLLADA")
        .ok_or_else(|| "not a Collada document (no <COLLADA> root)".to_string())
}

/// A node's transform from its `<matrix>`, `<translate>`, `<rotate>`
/// (axis, degrees) and `<scale>` children, in document order.
fn node_transform(node: &Element) -> Result<Matrix4<f64>, String> {
    let mut transform = Matrix4::identity();
    for child in &node.children {
        let v = match child.name.as_str() {
            "matrix" | "translate" | "rotate" | "scale" => child.numbers()?,
            _ => continue,
        };
        let need = match child.name.as_str() {
            "matrix" => 16,
            "rotate" => 4,
            _ => 3,
        };
        if v.len() != need {
            return Err(format!(
                "<{}> needs {need} numbers, has {}",
                child.name,
                v.len()
            ));
        }
        let step = match child.name.as_str() {
            "matrix" => Matrix4::from_row_slice(&v),
            "translate" => Matrix4::new_translation(&Vector3::new(v[0], v[1], v[2])),
            "scale" => Matrix4::new_nonuniform_scaling(&Vector3::new(v[0], v[1], v[2])),
            _ => {
                let axis = Vector3::new(v[0], v[1], v[2]);
                if axis.norm() == 0.0 {
                    Matrix4::identity()
                } else {
                    Matrix4::from_axis_angle(
                        &nalgebra::Unit::new_normalize(axis),
                        v[3].to_radians(),
                    )
                }
            }
        };
        transform *= step;
    }
    Ok(transform)
}

/// Diffuse colours by material id (material, then its effect).
fn material_colors(root: &Element) -> HashMap<String, [f64; 4]> {
    let mut effects = HashMap::new();
    let mut found = Vec::new();
    root.descendants("effect", &mut found);
    for effect in found {
        let mut diffuse = Vec::new();
        effect.descendants("diffuse", &mut diffuse);
        let color = diffuse
            .iter()
            .filter_map(|d| d.child("color"))
            .filter_map(|c| c.numbers().ok())
            .find(|v| v.len() >= 3);
        if let (Some(id), Some(v)) = (effect.attribute("id"), color) {
            effects.insert(
                id.to_string(),
                [v[0], v[1], v[2], v.get(3).copied().unwrap_or(1.0)],
            );
        }
    }
    let mut materials = HashMap::new();
    let mut found = Vec::new();
    root.descendants("material", &mut found);
    for material in found {
        let effect = material
            .child("instance_effect")
            .and_then(|i| i.attribute("url"))
            .map(|u| u.trim_start_matches('#'));
        if let (Some(id), Some(color)) = (
            material.attribute("id"),
            effect.and_then(|e| effects.get(e)),
        ) {
            materials.insert(id.to_string(), *color);
        }
    }
    materials
}

/// Appends the triangles of `geometry` (its `<mesh>`) transformed by `transform`.
fn append_geometry(
    geometry: &Element,
    transform: &Matrix4<f64>,
    bindings: &HashMap<String, String>,
    colors: &HashMap<String, [f64; 4]>,
    out: &mut MeshBuffer,
) -> Result<(), String> {
    let Some(mesh) = geometry.child("mesh") else {
        return Ok(());
    };
    let sources: HashMap<&str, &Element> = mesh
        .children_named("source")
        .filter_map(|s| Some((s.attribute("id")?, s)))
        .collect();
    let source_positions = |id: &str| -> Result<Vec<[f64; 3]>, String> {
        let source = sources
            .get(id.trim_start_matches('#'))
            .ok_or_else(|| format!("source `{id}` not found"))?;
        let values = source
            .child("float_array")
            .ok_or_else(|| format!("source `{id}` has no <float_array>"))?
            .numbers()?;
        let stride = source
            .child("technique_common")
            .and_then(|t| t.child("accessor"))
            .and_then(|a| a.attribute("stride"))
            .and_then(|s| s.parse::<usize>().ok())
            .unwrap_or(3)
            .max(3);
        Ok(values
            .chunks_exact(stride)
            .map(|c| [c[0], c[1], c[2]])
            .collect())
    };
    // <vertices id> names the POSITION source.
    let mut vertex_sources = HashMap::new();
    for vertices in mesh.children_named("vertices") {
        let position = vertices
            .children_named("input")
            .find(|i| i.attribute("semantic") == Some("POSITION"))
            .and_then(|i| i.attribute("source"));
        if let (Some(id), Some(position)) = (vertices.attribute("id"), position) {
            vertex_sources.insert(id.to_string(), position.to_string());
        }
    }
    for primitive in &mesh.children {
        let polygon = match primitive.name.as_str() {
            "triangles" | "polylist" | "polygons" => primitive,
            _ => continue,
        };
        let inputs: Vec<&Element> = polygon.children_named("input").collect();
        let stride = inputs
            .iter()
            .filter_map(|i| i.attribute("offset")?.parse::<usize>().ok())
            .max()
            .map_or(1, |m| m + 1);
        let Some(vertex_input) = inputs
            .iter()
            .find(|i| matches!(i.attribute("semantic"), Some("VERTEX") | Some("POSITION")))
        else {
            continue;
        };
        let offset = vertex_input
            .attribute("offset")
            .and_then(|o| o.parse::<usize>().ok())
            .unwrap_or(0);
        let source = vertex_input.attribute("source").unwrap_or("");
        let source = vertex_sources
            .get(source.trim_start_matches('#'))
            .map_or(source, String::as_str);
        let positions = source_positions(source)?;
        let base = (out.positions.len() / 3) as u32;
        for p in &positions {
            let q = transform.transform_point(&Point3::new(p[0], p[1], p[2]));
            out.positions.extend([q.x as f32, q.y as f32, q.z as f32]);
        }
        // Polygon vertex counts: all 3 for <triangles>, <vcount> for
        // <polylist>, one <p> per polygon for <polygons>; fanned into triangles.
        let mut polygons: Vec<(Vec<f64>, Vec<usize>)> = Vec::new();
        let ps: Vec<Vec<f64>> = polygon
            .children_named("p")
            .map(Element::numbers)
            .collect::<Result<_, _>>()?;
        match polygon.name.as_str() {
            "triangles" => {
                for p in ps {
                    let count = p.len() / (3 * stride);
                    polygons.push((p, vec![3; count]));
                }
            }
            "polylist" => {
                let counts = polygon
                    .child("vcount")
                    .map(Element::numbers)
                    .transpose()?
                    .unwrap_or_default()
                    .into_iter()
                    .map(|c| c as usize)
                    .collect();
                if let Some(p) = ps.into_iter().next() {
                    polygons.push((p, counts));
                }
            }
            _ => {
                for p in ps {
                    let count = p.len() / stride;
                    polygons.push((p, vec![count]));
                }
            }
        }
        for (p, counts) in polygons {
            let mut at = 0;
            for count in counts {
                let corner = |k: usize| -> Result<u32, String> {
                    let raw = *p
                        .get((at + k) * stride + offset)
                        .ok_or("a <p> is shorter than its polygons")?;
                    let index = raw as usize;
                    if raw < 0.0 || index >= positions.len() {
                        return Err(format!("index {raw} out of {} vertices", positions.len()));
                    }
                    Ok(base + index as u32)
                };
                for k in 1..count.saturating_sub(1) {
                    out.indices.extend([corner(0)?, corner(k)?, corner(k + 1)?]);
                }
                at += count;
            }
        }
        if out.color.is_none() {
            let symbol = polygon.attribute("material").unwrap_or("");
            let material = bindings.get(symbol).map_or(symbol, String::as_str);
            out.color = colors.get(material.trim_start_matches('#')).copied();
        }
    }
    Ok(())
}

/// The node tree of the visual scene, each geometry instance appended with
/// its accumulated transform.
fn walk(
    node: &Element,
    parent: &Matrix4<f64>,
    geometries: &HashMap<&str, &Element>,
    colors: &HashMap<String, [f64; 4]>,
    out: &mut MeshBuffer,
) -> Result<(), String> {
    let transform = parent * node_transform(node)?;
    for instance in node.children_named("instance_geometry") {
        let url = instance
            .attribute("url")
            .unwrap_or("")
            .trim_start_matches('#');
        let Some(geometry) = geometries.get(url) else {
            return Err(format!("geometry `{url}` not found"));
        };
        let mut found = Vec::new();
        instance.descendants("instance_material", &mut found);
        let bindings = found
            .iter()
            .filter_map(|m| {
                Some((
                    m.attribute("symbol")?.to_string(),
                    m.attribute("target")?.to_string(),
                ))
            })
            .map(|(s, t)| (s, t.trim_start_matches('#').to_string()))
            .collect();
        append_geometry(geometry, &transform, &bindings, colors, out)?;
    }
    for child in node.children_named("node") {
        walk(child, &transform, geometries, colors, out)?;
    }
    Ok(())
}

/// Parses Collada text into one triangle mesh in metres, z up.
pub fn parse(text: &str) -> Result<MeshBuffer, String> {
    let root = document(text)?;
    let asset = root.child("asset");
    let meter = asset
        .and_then(|a| a.child("unit"))
        .and_then(|u| u.attribute("meter"))
        .and_then(|m| m.trim().parse::<f64>().ok())
        .filter(|m| m.is_finite() && *m > 0.0)
        .unwrap_or(1.0);
    let up = asset
        .and_then(|a| a.child("up_axis"))
        .map_or("Y_UP".to_string(), |u| u.text.trim().to_string());
    // Collada's up axis turned onto z (the URDF's up), as its specification says.
    let to_z_up = match up.as_str() {
        "Z_UP" => Matrix4::identity(),
        "X_UP" => Matrix4::from_row_slice(&[
            0., -1., 0., 0., 1., 0., 0., 0., 0., 0., 1., 0., 0., 0., 0., 1.,
        ]),
        _ => Matrix4::from_row_slice(&[
            1., 0., 0., 0., 0., 0., -1., 0., 0., 1., 0., 0., 0., 0., 0., 1.,
        ]),
    };
    let root_transform = Matrix4::new_scaling(meter) * to_z_up;
    let mut found = Vec::new();
    root.descendants("geometry", &mut found);
    let geometries: HashMap<&str, &Element> = found
        .into_iter()
        .filter_map(|g| Some((g.attribute("id")?, g)))
        .collect();
    let colors = material_colors(&root);
    let mut out = MeshBuffer::default();
    let mut scenes = Vec::new();
    root.descendants("visual_scene", &mut scenes);
    if let Some(scene) = scenes.first() {
        for node in scene.children_named("node") {
            walk(node, &root_transform, &geometries, &colors, &mut out)?;
        }
    } else {
        // No scene: every geometry as it is.
        for geometry in geometries.values() {
            append_geometry(
                geometry,
                &root_transform,
                &HashMap::new(),
                &colors,
                &mut out,
            )?;
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit square as a <polylist> quad in a node moved by 1 m along x,
    /// in centimetres, z up, coloured red through its material binding.
    const SQUARE: &str = r##"<?xml version="1.0"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
 <asset><unit name="centimeter" meter="0.01"/><up_axis>Z_UP</up_axis></asset>
 <library_effects><effect id="red-fx"><profile_COMMON><technique sid="t"><phong>
   <diffuse><color>1 0 0 1</color></diffuse></phong></technique></profile_COMMON></effect></library_effects>
 <library_materials><material id="red" name="red"><instance_effect url="#red-fx"/></material></library_materials>
 <library_geometries><geometry id="g"><mesh>
  <source id="g-pos"><float_array id="g-arr" count="12">0 0 0 100 0 0 100 100 0 0 100 0</float_array>
   <technique_common><accessor source="#g-arr" count="4" stride="3"/></technique_common></source>
  <vertices id="g-v"><input semantic="POSITION" source="#g-pos"/></vertices>
  <polylist count="1" material="sym"><input semantic="VERTEX" source="#g-v" offset="0"/>
   <vcount>4</vcount><p>0 1 2 3</p></polylist>
 </mesh></geometry></library_geometries>
 <library_visual_scenes><visual_scene id="s"><node id="n"><translate>100 0 0</translate>
  <instance_geometry url="#g"><bind_material><technique_common>
   <instance_material symbol="sym" target="#red"/></technique_common></bind_material></instance_geometry>
 </node></visual_scene></library_visual_scenes>
</COLLADA>"##;

    #[test]
    fn polylist_with_units_node_transform_and_material() {
        let mesh = parse(SQUARE).unwrap();
        assert_eq!(mesh.triangles(), 2);
        assert_eq!(mesh.bounds(), Some(([1.0, 0.0, 0.0], [2.0, 1.0, 0.0])));
        assert_eq!(mesh.color, Some([1.0, 0.0, 0.0, 1.0]));
    }

    #[test]
    fn y_up_is_turned_to_z_up_and_errors_say_what() {
        let y_up = SQUARE.replace("Z_UP", "Y_UP");
        let (low, high) = parse(&y_up).unwrap().bounds().unwrap();
        // (x, y, z) -> (x, -z, y): the square now stands in the xz plane.
        assert!(
            (low[2] - 0.0).abs() < 1e-6 && (high[2] - 1.0).abs() < 1e-6,
            "{low:?} {high:?}"
        );
        assert!(parse("<COLLADA><asset>")
            .unwrap_err()
            .contains("not closed"));
        assert!(parse("<x/>").unwrap_err().contains("<COLLADA>"));
        let bad_index = SQUARE.replace("0 1 2 3</p>", "0 1 2 9</p>");
        assert!(parse(&bad_index).unwrap_err().contains("index 9"));
    }
}
