//! `armkit manipulability`: how well the arm can move at one configuration:
//! the Jacobian's singular values and rank, the singularity kind (wrist,
//! elbow, shoulder for 6R spherical-wrist arms) and the translational and
//! rotational manipulability ellipsoids.

use armkit::kinematics::{jacobian, Data, JacobianFrame};
use armkit::singularity::{
    classify, manipulability_ellipsoid, Classification, ClassifyOptions, Ellipsoid, JacobianPart,
};
use clap::Args;

use crate::common::{print_json, CliResult, ConfigurationArgs, Outcome};

/// Arguments of `armkit manipulability`.
#[derive(Args, Debug)]
pub struct ManipulabilityArgs {
    #[command(flatten)]
    pub config: ConfigurationArgs,
    /// A singular value below this times the largest counts as lost rank; a
    /// wrist, elbow or shoulder factor (in [-1, 1]) below it names its kind.
    #[arg(long, default_value_t = 1e-6)]
    pub tolerance: f64,
}

/// Runs `armkit manipulability`.
pub fn run(args: &ManipulabilityArgs) -> CliResult<Outcome> {
    let (model, q) = args.config.load()?;
    let options = ClassifyOptions {
        tolerance: args.tolerance,
    };
    let mut data = Data::new(&model);
    let found = classify(&model, &mut data, &q, &options)?;
    let j = jacobian(&model, &mut data, &q, JacobianFrame::World)?;
    let translational = manipulability_ellipsoid(j, JacobianPart::Translational)?;
    let rotational = manipulability_ellipsoid(j, JacobianPart::Rotational)?;
    if args.config.json {
        print_json(&serde_json::json!({
            "robot": model.name(),
            "q": q,
            "singular_values": found.singular_values,
            "rank": found.rank,
            "singular": found.is_singular(),
            "kinds": found.kinds.iter().map(|k| k.as_str()).collect::<Vec<_>>(),
            "factors": found.factors.map(|f| serde_json::json!({
                "wrist_centre": f.centre.as_slice(),
                "wrist": f.wrist,
                "elbow": f.elbow,
                "shoulder": f.shoulder,
            })),
            "translational_ellipsoid": ellipsoid_json(&translational),
            "rotational_ellipsoid": ellipsoid_json(&rotational),
        }))?;
    } else {
        print!(
            "{}",
            describe(model.name(), &found, &translational, &rotational)
        );
    }
    Ok(Outcome::Success)
}

fn ellipsoid_json(e: &Ellipsoid) -> serde_json::Value {
    serde_json::json!({
        "radii": e.radii,
        "axes": e.axes.iter().map(|a| a.as_slice().to_vec()).collect::<Vec<_>>(),
        "volume": e.volume_measure(),
        "isotropy": e.isotropy(),
    })
}

/// The text report: singular values, rank and kind, factors, ellipsoids.
fn describe(
    robot: &str,
    found: &Classification,
    translational: &Ellipsoid,
    rotational: &Ellipsoid,
) -> String {
    let values: Vec<String> = found
        .singular_values
        .iter()
        .map(|s| format!("{s:.6}"))
        .collect();
    let kinds = if found.is_singular() {
        let names: Vec<&str> = found.kinds.iter().map(|k| k.as_str()).collect();
        format!("singular: {}", names.join(", "))
    } else {
        "not singular".to_string()
    };
    let mut text = format!(
        "{robot}: {kinds}\nJacobian singular values (world frame, largest first): {}\nrank: {}\n",
        values.join(" "),
        found.rank
    );
    match &found.factors {
        Some(f) => text += &format!(
            "wrist centre (m): {:.6} {:.6} {:.6}\nfactors in [-1, 1] (0 on the singularity): wrist {:.6}, elbow {:.6}, shoulder {:.6}\n",
            f.centre.x, f.centre.y, f.centre.z, f.wrist, f.elbow, f.shoulder
        ),
        None => text += "no wrist/elbow/shoulder factors: not a 6R arm with a spherical wrist and parallel axes 2, 3\n",
    }
    for (name, unit, e) in [
        ("translational", "m/rad", translational),
        ("rotational", "rad/rad", rotational),
    ] {
        text += &format!(
            "{name} ellipsoid: radii ({unit}) {:.6} {:.6} {:.6}, volume {:.6e}, isotropy {:.6}\n",
            e.radii[0],
            e.radii[1],
            e.radii[2],
            e.volume_measure(),
            e.isotropy()
        );
        for (radius, axis) in e.radii.iter().zip(&e.axes) {
            text += &format!(
                "  axis {:>9.6} {:>9.6} {:>9.6}  radius {radius:.6}\n",
                axis.x, axis.y, axis.z
            );
        }
    }
    text
}
