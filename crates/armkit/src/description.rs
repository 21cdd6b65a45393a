//! Robot description files: a DH table in TOML or JSON.
//!
//! The fields are those of the `dh` block of the reference files in
//! `tests/data/reference_*_dh.json` (made by the Robotics Toolbox), so those
//! blocks load as they are, and a JSON file holding a whole reference file is
//! read through its `dh` block:
//!
//! ```toml
//! name = "planar2r"                  # optional
//! convention = "standard"            # or "modified" / "modified (Craig)"
//! base = [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]   # optional, row-major
//! tool = [[1,0,0,0],[0,1,0,0],[0,0,1,0.1],[0,0,0,1]] # optional
//!
//! [[links]]
//! type = "R"          # "R" revolute or "P" prismatic
//! theta = 0.0         # rad (constant part; default 0)
//! d = 0.0             # m
//! a = 0.5             # m
//! alpha = 0.0         # rad
//! offset = 0.0        # joint offset, rad or m (default 0)
//! qlim = [-1.57, 1.57]  # optional; absent or null: no limits (a revolute joint then wraps)
//! vlim = 2.0          # optional, rad/s or m/s
//! alim = 10.0         # optional, rad/s^2 or m/s^2
//! tlim = 150.0        # optional: torque (N m) or force (N) limit of the joint's motor
//! mass = 3.0          # optional, kg
//! com = [-0.25, 0, 0] # optional, m, in the link's DH frame
//! inertia = [0.1, 0.1, 0.01, 0, 0, 0]  # optional: [Ixx, Iyy, Izz, Ixy, Iyz, Ixz] or a 3x3, kg m^2
//! ```
//!
//! The informational strings of the reference files (`link_transform`,
//! `joint_variable`, `chain`) are accepted and ignored; any other unknown
//! field is an error, so that a misspelt field never passes silently.
//!
//! ```
//! let text = r#"
//! convention = "standard"
//! [[links]]
//! type = "R"
//! d = 0.0
//! a = 0.5
//! alpha = 0.0
//! qlim = [-1.0, 1.0]
//! "#;
//! let model = armkit::description::parse_str(text, armkit::description::Format::Toml, "<example>").unwrap();
//! assert_eq!(model.dof(), 1);
//! ```

use std::path::Path;

use serde::Deserialize;

use crate::error::{Error, Result};
use crate::math::{Matrix3, Pose, Vector3};
use crate::model::{DhConvention, DhLink, JointKind, JointLimits, LinkInertia, Model};

/// Text format of a description file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// TOML.
    Toml,
    /// JSON (a description, or a whole reference file with a `dh` block).
    Json,
}

impl Format {
    /// The format implied by a path's extension (`.toml`, `.json`), else by
    /// the text: JSON when its first non-blank character is `{`.
    pub fn detect(path: &Path, text: &str) -> Format {
        match path.extension().and_then(|e| e.to_str()) {
            Some(e) if e.eq_ignore_ascii_case("json") => Format::Json,
            Some(e) if e.eq_ignore_ascii_case("toml") => Format::Toml,
            _ if text.trim_start().starts_with('{') => Format::Json,
            _ => Format::Toml,
        }
    }
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct DescriptionFile {
    name: Option<String>,
    convention: String,
    links: Vec<LinkEntry>,
    base: Option<[[f64; 4]; 4]>,
    tool: Option<[[f64; 4]; 4]>,
    // Informational strings written by the reference generator.
    #[allow(dead_code)]
    link_transform: Option<String>,
    #[allow(dead_code)]
    joint_variable: Option<String>,
    #[allow(dead_code)]
    chain: Option<String>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct LinkEntry {
    #[serde(rename = "type")]
    kind: String,
    #[serde(default)]
    theta: f64,
    d: f64,
    a: f64,
    alpha: f64,
    #[serde(default)]
    offset: f64,
    qlim: Option<[f64; 2]>,
    vlim: Option<f64>,
    alim: Option<f64>,
    tlim: Option<f64>,
    mass: Option<f64>,
    com: Option<[f64; 3]>,
    inertia: Option<InertiaEntry>,
}

#[derive(Debug, Deserialize)]
#[serde(untagged)]
enum InertiaEntry {
    Matrix([[f64; 3]; 3]),
    Components([f64; 6]),
}

impl InertiaEntry {
    fn matrix(&self) -> Matrix3<f64> {
        match self {
            InertiaEntry::Matrix(rows) => Matrix3::from_fn(|r, c| rows[r][c]),
            InertiaEntry::Components([ixx, iyy, izz, ixy, iyz, ixz]) => {
                Matrix3::new(*ixx, *ixy, *ixz, *ixy, *iyy, *iyz, *ixz, *iyz, *izz)
            }
        }
    }
}

/// Loads a description file (format from the extension or the content).
pub fn load(path: impl AsRef<Path>) -> Result<Model> {
    let path = path.as_ref();
    let (text, source_name) = crate::error::read_source(path)?;
    parse_str(&text, Format::detect(path, &text), &source_name)
}

/// Parses description text; `source_name` names it in errors (a path, or
/// e.g. `<string>`). Errors give the line and column where the parser knows
/// them, and name the link (0-based) and field for bad values.
pub fn parse_str(text: &str, format: Format, source_name: &str) -> Result<Model> {
    let parse_error = |reason: String| Error::Parse {
        source_name: source_name.to_string(),
        reason,
    };
    let (file, default_name) = match format {
        Format::Json => parse_json(text).map_err(parse_error)?,
        Format::Toml => parse_toml(text).map_err(parse_error)?,
    };
    build(file, default_name, source_name)
}

fn parse_json(text: &str) -> std::result::Result<(DescriptionFile, Option<String>), String> {
    let value: serde_json::Value =
        serde_json::from_str(text).map_err(|e| format!("invalid JSON: {e}"))?;
    match value.get("dh") {
        Some(dh) => {
            let robot = value
                .get("robot")
                .and_then(|r| r.as_str())
                .map(str::to_string);
            let file =
                DescriptionFile::deserialize(dh).map_err(|e| format!("in the `dh` block: {e}"))?;
            Ok((file, robot))
        }
        None => {
            let file = serde_json::from_str(text).map_err(|e| format!("{e}"))?;
            Ok((file, None))
        }
    }
}

fn parse_toml(text: &str) -> std::result::Result<(DescriptionFile, Option<String>), String> {
    let file: DescriptionFile = toml::from_str(text).map_err(|e| toml_error_line(text, &e))?;
    Ok((file, None))
}

/// A TOML error on one line: `line L, column C (`the line`): message`.
/// Used for every TOML input of armkit (description and scenario files).
pub fn toml_error_line(text: &str, error: &toml::de::Error) -> String {
    let message = error.message().trim().replace('\n', " ");
    match error.span() {
        Some(span) => {
            let (line, column) = line_and_column(text, span.start);
            let source_line = text.lines().nth(line - 1).unwrap_or("").trim();
            format!("line {line}, column {column} (`{source_line}`): {message}")
        }
        None => message,
    }
}

/// 1-based line and column of a byte offset in `text`.
pub fn line_and_column(text: &str, offset: usize) -> (usize, usize) {
    let before = text.get(..offset).unwrap_or(text);
    let line = before.matches('\n').count() + 1;
    let column = before
        .rfind('\n')
        .map_or(before.len(), |nl| before.len() - nl - 1)
        + 1;
    (line, column)
}

fn parse_convention(text: &str) -> Option<DhConvention> {
    match text.trim().to_ascii_lowercase().as_str() {
        "standard" => Some(DhConvention::Standard),
        "modified" | "modified (craig)" | "craig" => Some(DhConvention::Modified),
        _ => None,
    }
}

fn parse_kind(text: &str, has_limits: bool) -> Option<JointKind> {
    match text.trim().to_ascii_uppercase().as_str() {
        "R" | "REVOLUTE" if has_limits => Some(JointKind::Revolute),
        "R" | "REVOLUTE" => Some(JointKind::Continuous),
        "P" | "PRISMATIC" => Some(JointKind::Prismatic),
        _ => None,
    }
}

fn matrix_pose(rows: &Option<[[f64; 4]; 4]>) -> std::result::Result<Pose, String> {
    match rows {
        None => Ok(Pose::identity()),
        Some(rows) => Pose::from_rows(rows),
    }
}

fn build(file: DescriptionFile, default_name: Option<String>, source_name: &str) -> Result<Model> {
    let file_error = |reason: String| Error::Parse {
        source_name: source_name.to_string(),
        reason,
    };
    let convention = parse_convention(&file.convention).ok_or_else(|| {
        file_error(format!(
            "field `convention`: expected \"standard\" or \"modified\" (also \"modified (Craig)\"), got {:?}",
            file.convention
        ))
    })?;
    if file.links.is_empty() {
        return Err(file_error(
            "field `links`: the chain has no links (an empty chain)".into(),
        ));
    }
    let base = matrix_pose(&file.base).map_err(|r| file_error(format!("field `base`: {r}")))?;
    let tool = matrix_pose(&file.tool).map_err(|r| file_error(format!("field `tool`: {r}")))?;
    let links = file
        .links
        .iter()
        .enumerate()
        .map(|(j, entry)| {
            link_from_entry(entry).map_err(|(field, reason)| {
                file_error(format!("link {j}, field `{field}`: {reason}"))
            })
        })
        .collect::<Result<Vec<_>>>()?;
    let name = file
        .name
        .or(default_name)
        .unwrap_or_else(|| "robot".to_string());
    Model::from_dh_with_transforms(&name, convention, &links, base, tool)
        .map_err(|e| file_error(e.to_string()))
}

fn link_from_entry(entry: &LinkEntry) -> std::result::Result<DhLink, (&'static str, String)> {
    let kind = parse_kind(&entry.kind, entry.qlim.is_some()).ok_or_else(|| {
        (
            "type",
            format!("expected \"R\" or \"P\", got {:?}", entry.kind),
        )
    })?;
    let (lower, upper) = match entry.qlim {
        Some([lower, upper]) => (lower, upper),
        None => (f64::NEG_INFINITY, f64::INFINITY),
    };
    let limits = JointLimits {
        lower,
        upper,
        velocity: entry.vlim,
        acceleration: entry.alim,
        effort: entry.tlim,
    };
    let inertia = match (entry.mass, &entry.com, &entry.inertia) {
        (None, None, None) => None,
        (None, _, _) => return Err(("mass", "`com` or `inertia` is given without `mass`".into())),
        (Some(mass), com, inertia) => Some(LinkInertia {
            mass,
            com: com.map(Vector3::from).unwrap_or_else(Vector3::zeros),
            inertia: inertia
                .as_ref()
                .map(InertiaEntry::matrix)
                .unwrap_or_else(Matrix3::zeros),
        }),
    };
    Ok(DhLink {
        kind,
        theta: entry.theta,
        d: entry.d,
        a: entry.a,
        alpha: entry.alpha,
        offset: entry.offset,
        limits,
        inertia,
    })
}
