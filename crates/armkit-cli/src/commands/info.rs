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

/// Runs `armkit info`.
pub fn run(args: &InfoArgs) -> CliResult<Outcome> {
    let model = args.robot.load()?;
    if args.json {
        print_json(&json(&model))?;
    } else {
        print!("{}", table(&model));
    }
    Ok(Outcome::Success)
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
        "robot {}: {} chain joints, {} independent (dof)\n\nchain joints, base to tip:\n",
        model.name(),
        model.chain_joints().len(),
        model.dof()
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
        "chain_joints": model.chain_joints().iter().map(joint_json).collect::<Vec<_>>(),
        "joints": model.joints().iter().map(joint_json).collect::<Vec<_>>(),
        "couplings": couplings,
    })
}
