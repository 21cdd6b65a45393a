//! `armkit dynamics`: inverse dynamics, mass matrix, gravity and Coriolis
//! torques at one state, and forward dynamics when torques are given.

use armkit::dynamics::{
    aba, coriolis_torques, gravity_torques, kinetic_energy, mass_matrix, potential_energy, rnea,
    DynamicsData,
};
use armkit::math::{DMatrix, Vector3};
use clap::Args;

use crate::common::{
    format_rows, parse_fixed_numbers, print_json, CliResult, ConfigurationArgs, Outcome,
};

/// Rigid-body dynamics at one state: tau = M(q) a + C(q, v) v + g(q), the
/// mass matrix, g and C v, and ddq = ABA(q, v, tau) with --tau.
#[derive(Args, Debug)]
pub struct DynamicsArgs {
    #[command(flatten)]
    pub config: ConfigurationArgs,
    /// Joint velocities, comma-separated (rad/s or m/s; default all 0).
    #[arg(long, value_name = "V1,V2,...", allow_hyphen_values = true)]
    pub v: Option<String>,
    /// Joint accelerations, comma-separated (rad/s^2 or m/s^2; default all 0).
    #[arg(long, value_name = "A1,A2,...", allow_hyphen_values = true)]
    pub a: Option<String>,
    /// Joint torques for forward dynamics, comma-separated (N m or N): prints ddq.
    #[arg(long, value_name = "T1,T2,...", allow_hyphen_values = true)]
    pub tau: Option<String>,
    /// Gravity in the world frame, m/s^2 (default 0,0,-9.81).
    #[arg(long, value_name = "GX,GY,GZ", allow_hyphen_values = true)]
    pub gravity: Option<String>,
}

/// Everything the command computes, in SI units.
struct DynamicsReport {
    tau: Vec<f64>,
    mass_matrix: DMatrix<f64>,
    gravity: Vec<f64>,
    coriolis: Vec<f64>,
    ddq: Option<Vec<f64>>,
    kinetic_energy: f64,
    potential_energy: f64,
}

fn optional_vector(text: &Option<String>, what: &str, n: usize) -> CliResult<Vec<f64>> {
    match text {
        Some(text) => parse_fixed_numbers(text, what, n),
        None => Ok(vec![0.0; n]),
    }
}

fn matrix_rows(m: &DMatrix<f64>) -> Vec<Vec<f64>> {
    m.row_iter().map(|r| r.iter().copied().collect()).collect()
}

/// Runs `armkit dynamics`.
pub fn run(args: &DynamicsArgs) -> CliResult<Outcome> {
    let (model, q) = args.config.load()?;
    let n = model.dof();
    let v = optional_vector(&args.v, "--v", n)?;
    let a = optional_vector(&args.a, "--a", n)?;
    let tau_in = args
        .tau
        .as_ref()
        .map(|t| parse_fixed_numbers(t, "--tau", n))
        .transpose()?;
    let gravity = match &args.gravity {
        Some(text) => Vector3::from_vec(parse_fixed_numbers(text, "--gravity", 3)?),
        None => armkit::dynamics::DEFAULT_GRAVITY,
    };
    let mut data = DynamicsData::new(&model)?.with_gravity(gravity)?;
    let report = DynamicsReport {
        tau: rnea(&model, &mut data, &q, &v, &a)?.to_vec(),
        mass_matrix: mass_matrix(&model, &mut data, &q)?.clone(),
        gravity: gravity_torques(&model, &mut data, &q)?.to_vec(),
        coriolis: coriolis_torques(&model, &mut data, &q, &v)?.to_vec(),
        ddq: match &tau_in {
            Some(tau) => Some(aba(&model, &mut data, &q, &v, tau)?.to_vec()),
            None => None,
        },
        kinetic_energy: kinetic_energy(&model, &mut data, &q, &v)?,
        potential_energy: potential_energy(&model, &mut data, &q)?,
    };
    if args.config.json {
        print_json(&serde_json::json!({
            "robot": model.name(),
            "q": q,
            "v": v,
            "a": a,
            "gravity_vector": gravity.as_slice(),
            "tau": report.tau,
            "mass_matrix": matrix_rows(&report.mass_matrix),
            "gravity": report.gravity,
            "coriolis": report.coriolis,
            "tau_in": tau_in,
            "ddq": report.ddq,
            "kinetic_energy": report.kinetic_energy,
            "potential_energy": report.potential_energy,
        }))?;
    } else {
        print!("{}", describe(model.name(), &gravity, &report));
    }
    Ok(Outcome::Success)
}

fn describe(robot: &str, gravity: &Vector3<f64>, report: &DynamicsReport) -> String {
    let row = |values: &[f64]| format_rows(&[values.to_vec()]);
    let mut text = format!(
        "{robot}: rigid-body dynamics, gravity ({}, {}, {}) m/s^2 (world frame)\n\
         tau = M(q) a + C(q, v) v + g(q) (N m, N for prismatic joints):\n{}\n\
         mass matrix M(q) ({n} x {n}):\n{}\n\
         gravity torques g(q):\n{}\n\
         Coriolis and centrifugal torques C(q, v) v:\n{}\n",
        gravity.x,
        gravity.y,
        gravity.z,
        row(&report.tau),
        format_rows(&matrix_rows(&report.mass_matrix)),
        row(&report.gravity),
        row(&report.coriolis),
        n = report.tau.len(),
    );
    if let Some(ddq) = &report.ddq {
        text += &format!(
            "forward dynamics ddq = ABA(q, v, tau) (rad/s^2, m/s^2):\n{}\n",
            row(ddq)
        );
    }
    text += &format!(
        "kinetic energy {:.6} J, potential energy {:.6} J\n",
        report.kinetic_energy, report.potential_energy
    );
    text
}
