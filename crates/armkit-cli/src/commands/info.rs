//! `armkit info`: what a robot model is made of: the chain's joints with
//! their kinds and limits, which joints mimic which (and through what law),
//! and the configuration (the independent joints `q` holds).

use armkit::model::{CouplingLaw, Joint};
use armkit::Model;
use clap::Args;

use crate::common::{print_json, CliResult, Outcome, RobotArgs};

/// Lists a robot's chain: joints, mimic joints and limits.
#[derive(Args, Debug)]
pub struct InfoArgs {
    #[command(flatten)]
    pub robot: RobotArgs,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
}

/// Runs `armkit info`: the chain, or, for a URDF with several leaf links (or
/// roots) and neither `--base` nor `--tip`, the whole tree (the tips to
/// choose from).
pub fn run(args: &InfoArgs) -> CliResult<Outcome> {
    if let (Some(path), None, None) = (&args.robot.urdf, &args.robot.base, &args.robot.tip) {
        let tree = armkit::urdf::outline(path)?;
        if tree.leaves.len() > 1 || tree.roots.len() > 1 {
            if args.json {
                print_json(&tree_json(&tree))?;
            } else {
                print!("{}", tree_text(&tree));
            }
            return Ok(Outcome::Success);
        }
    }
    let model = args.robot.load()?;
    if args.json {
        print_json(&json(&model))?;
    } else {
        print!("{}", table(&model));
    }
    Ok(Outcome::Success)
}

/// The tree of a URDF as text: joints indented by depth, then the leaves.
pub fn tree_text(tree: &armkit::urdf::Outline) -> String {
    let mut out = format!(
        "robot {}: {} links, {} joints, {} leaf links: a tree, not one chain; \
         choose one with --tip LINK (and --base LINK)\n\n",
        tree.robot,
        tree.links,
        tree.joints.len(),
        tree.leaves.len()
    );
    for root in &tree.roots {
        out += &format!("{root} (root)\n");
    }
    for joint in &tree.joints {
        out += &format!(
            "{}{} -> {}  [{} {}]\n",
            "  ".repeat(joint.depth + 1),
            joint.parent,
            joint.child,
            joint.kind,
            joint.name
        );
    }
    out += &format!("\nleaf links (tips): {}\n", tree.leaves.join(", "));
    out
}

fn tree_json(tree: &armkit::urdf::Outline) -> serde_json::Value {
    serde_json::json!({
        "name": tree.robot,
        "links": tree.links,
        "roots": tree.roots,
        "leaves": tree.leaves,
        "joints": tree.joints.iter().map(|j| serde_json::json!({
            "name": j.name, "kind": j.kind, "parent": j.parent, "child": j.child, "depth": j.depth,
        })).collect::<Vec<_>>(),
    })
}

/// Which frame poses are given in: a built-in's convention, a DH table's
/// base frame, or a URDF's base link.
fn frames_line(model: &Model) -> String {
    if let Some(builtin) = armkit::robots::BUILTIN
        .iter()
        .find(|r| r.name == model.name())
    {
        if model.dh_table().is_some() || model.name().starts_with("gantry9") {
            return builtin.frames.to_string();
        }
    }
    match model.dh_table() {
        Some((convention, _)) => {
            format!("{convention:?} DH: the table's base frame (times its base transform)")
        }
        None => "the URDF's base link frame; link frames are the URDF's".into(),
    }
}

fn kind_name(joint: &Joint) -> &'static str {
    match joint.kind {
        armkit::model::JointKind::Revolute => "revolute",
        armkit::model::JointKind::Continuous => "continuous",
        armkit::model::JointKind::Prismatic => "prismatic",
    }
}

/// A number for the table: at most 6 decimals, trailing zeros dropped.
fn number(value: f64) -> String {
    if !value.is_finite() {
        return format!("{value}");
    }
    let text = format!("{value:.6}");
    let text = text.trim_end_matches('0').trim_end_matches('.');
    if text == "-0" {
        "0".into()
    } else {
        text.into()
    }
}

fn optional(value: Option<f64>) -> String {
    value.map_or("-".into(), number)
}

/// What drives chain joint `j`: `q[i]`, or a mimic or additive law.
fn driver(model: &Model, j: usize) -> String {
    let mut parts = Vec::new();
    for coupling in model.couplings().iter().filter(|c| c.target == j) {
        let leader = &model.joints()[coupling.source].name;
        parts.push(match &coupling.law {
            CouplingLaw::Mimic { multiplier, offset } => {
                let sign = if *offset < 0.0 { '-' } else { '+' };
                format!(
                    "mimics {leader}: {} * q[{}] {sign} {}",
                    number(*multiplier),
                    coupling.source,
                    number(offset.abs())
                )
            }
            CouplingLaw::Additive(_) => format!("+ f(q[{}] = {leader})", coupling.source),
        });
    }
    let name = &model.chain_joints()[j].name;
    let independent = model.joints().iter().position(|k| &k.name == name);
    if let (Some(i), false) = (independent, parts.iter().any(|p| p.starts_with("mimics"))) {
        parts.insert(0, format!("q[{i}]"));
    }
    parts.join(" ")
}

/// The text listing.
pub fn table(model: &Model) -> String {
    let mut out = format!(
        "robot {}: {} chain joints, {} independent (dof)\nframes: {}\n\nchain joints, base to tip:\n",
        model.name(),
        model.chain_joints().len(),
        model.dof(),
        frames_line(model)
    );
    let width = model
        .chain_joints()
        .iter()
        .chain(model.joints())
        .map(|j| j.name.len())
        .max()
        .unwrap_or(4)
        .max(5);
    out += &format!(
        "  {:>2} {:<width$} {:<10} {:>12} {:>12} {:>9}  driven by\n",
        "#", "joint", "kind", "lower", "upper", "velocity"
    );
    for (j, joint) in model.chain_joints().iter().enumerate() {
        out += &format!(
            "  {:>2} {:<width$} {:<10} {:>12} {:>12} {:>9}  {}\n",
            j,
            joint.name,
            kind_name(joint),
            number(joint.limits.lower),
            number(joint.limits.upper),
            optional(joint.limits.velocity),
            driver(model, j)
        );
    }
    out += "\nconfiguration q (limits include those the mimic joints impose):\n";
    for (i, joint) in model.joints().iter().enumerate() {
        let on_chain = model.chain_joints().iter().any(|c| c.name == joint.name);
        out += &format!(
            "  q[{i}] {:<width$} {:<10} {:>12} {:>12} {:>9}{}\n",
            joint.name,
            kind_name(joint),
            number(joint.limits.lower),
            number(joint.limits.upper),
            optional(joint.limits.velocity),
            if on_chain { "" } else { "  (off the chain)" }
        );
    }
    for coupling in model.couplings() {
        if let CouplingLaw::Additive(_) = coupling.law {
            out += &format!(
                "\ncoupling: {} {}\n",
                model.chain_joints()[coupling.target].name,
                coupling.law.describe()
            );
        }
    }
    out
}

fn joint_json(joint: &Joint) -> serde_json::Value {
    let finite = |v: f64| v.is_finite().then_some(v);
    serde_json::json!({
        "name": joint.name,
        "kind": kind_name(joint),
        "lower": finite(joint.limits.lower),
        "upper": finite(joint.limits.upper),
        "velocity": joint.limits.velocity,
        "acceleration": joint.limits.acceleration,
    })
}

/// The JSON listing: `chain_joints`, `joints` (the configuration) and
/// `couplings` (source is an index into `joints`, target into
/// `chain_joints`); infinite limits are `null`.
pub fn json(model: &Model) -> serde_json::Value {
    let couplings: Vec<_> = model
        .couplings()
        .iter()
        .map(|c| match &c.law {
            CouplingLaw::Mimic { multiplier, offset } => serde_json::json!({
                "kind": "mimic", "source": c.source, "target": c.target,
                "multiplier": multiplier, "offset": offset,
            }),
            CouplingLaw::Additive(_) => serde_json::json!({
                "kind": "additive", "source": c.source, "target": c.target,
                "description": c.law.describe(),
            }),
        })
        .collect();
    serde_json::json!({
        "name": model.name(),
        "dof": model.dof(),
        "frames": frames_line(model),
        "chain_joints": model.chain_joints().iter().map(joint_json).collect::<Vec<_>>(),
        "joints": model.joints().iter().map(joint_json).collect::<Vec<_>>(),
        "couplings": couplings,
    })
}
