//! `armkit space study` and the `[space]` scenario table: seed 004's
//! free-floating space robot ([`armkit::study::SpaceRobotStudy`]) as a report.

use std::path::PathBuf;

use armkit::math::Pose;
use armkit::space::FreeFloatingModel;
use armkit::study::{SpaceRobotStudy, StudyReport};
use clap::Args;

use super::BaseBodyArgs;
use crate::common::{parse_fixed_numbers, CliError, CliResult, Outcome, RobotArgs};
use crate::report::{Animation, Report};

/// Seed 004's space robot: space6r on its satellite (or the arm and base
/// body given), free-floating and with the attitude held; centre of mass,
/// momenta, J* and the base motion.
#[derive(Args, Debug)]
pub struct SpaceStudyArgs {
    /// The arm (default: --robot space6r). Every link needs mass properties.
    #[command(flatten)]
    pub robot: RobotArgs,
    #[command(flatten)]
    pub body: BaseBodyArgs,
    /// Start joint positions, rad (default: space6r's
    /// 0.3,0.8,-0.6,0.4,0.9,-0.3; other arms' mid-range configuration).
    #[arg(long, value_name = "Q1,...,Q6", allow_hyphen_values = true)]
    pub start: Option<String>,
    /// Simulated time, s.
    #[arg(long, default_value_t = 20.0, allow_hyphen_values = true)]
    pub duration: f64,
    /// Simulation step, s.
    #[arg(long, default_value_t = 0.01, allow_hyphen_values = true)]
    pub dt: f64,
    /// Seed of the smooth random joint motion.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Amplitude of each joint's excursion, rad.
    #[arg(long, default_value_t = 0.5, allow_hyphen_values = true)]
    pub amplitude: f64,
    /// Highest angular frequency of the joint motion, rad/s.
    #[arg(long, default_value_t = 0.5, allow_hyphen_values = true)]
    pub max_frequency: f64,
    /// Output directory for the report (CSV, SVG, summary.json, report.html).
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
}

impl SpaceStudyArgs {
    /// The library study these flags describe, and the system it runs on.
    pub fn study(&self) -> CliResult<(SpaceRobotStudy, FreeFloatingModel)> {
        let system = self.body.system(&self.robot)?;
        let mut study = SpaceRobotStudy {
            duration: self.duration,
            dt: self.dt,
            seed: self.seed,
            amplitude: self.amplitude,
            max_frequency: self.max_frequency,
            ..SpaceRobotStudy::default()
        };
        match &self.start {
            Some(text) => {
                study.start = parse_fixed_numbers(text, "--start", system.dof())?;
            }
            None if system.arm().name() != "space6r" => {
                study.start = system.arm().neutral_configuration();
            }
            None => {}
        }
        Ok((study, system))
    }

    /// True when the arm and the base body are seed 004's.
    fn is_seed004(&self, system: &FreeFloatingModel) -> bool {
        system.arm().name() == "space6r"
            && self.body.base_mass.is_none()
            && self.body.base_inertia.is_none()
            && self.body.base_mount.is_none()
    }
}

/// Runs `armkit space study`: prints the checks, writes the report with `--out`.
pub fn run(args: &SpaceStudyArgs) -> CliResult<Outcome> {
    let report = report(args)?;
    print!("{}", report.to_text());
    if let Some(dir) = &args.out {
        let summary = report.write(dir)?;
        println!("wrote {}", summary.html.display());
    }
    // Every check, the invariants among them, must hold.
    Ok(if report.checks.iter().all(|c| c.passed()) {
        Outcome::Success
    } else {
        Outcome::NotConverged
    })
}

/// The study as a report (a scenario's `[space]` table, with the
/// scenario's `[robot]` as the arm).
pub fn report(args: &SpaceStudyArgs) -> CliResult<Report> {
    let (study, system) = args.study()?;
    let mut result = study.run_on(&system)?;
    let animation = animation(&system, &result)?;
    let motion = format!(
        "a smooth random joint motion (seed {}, amplitude {} rad, up to {} rad/s) for {} s, once with the \
         base free-floating (linear and angular momentum zero, Umetani-Yoshida) and once with its attitude \
         held (seed 004, eqs 15-17). The base moves so that the centre of mass stays put; the generalized \
         Jacobian J* (eq 17) predicts the end effector's motion. The animation shows the free-floating run, \
         the base drawn from its centre of mass.",
        study.seed, study.amplitude, study.max_frequency, study.duration
    );
    let mut report = if args.is_seed004(&system) {
        Report::from_study(
            "seed004-space",
            "Seed 004, sec 1: the free-floating space robot",
            format!("space6r on its 400 kg satellite moves {motion}"),
            result,
        )
    } else {
        // The paper's claims are its own arm's; a user's arm gets the checks.
        result.findings.clear();
        let arm = system.arm().name();
        Report::from_study(
            "space",
            format!("{arm} on a free-floating base"),
            format!(
                "{arm} on a {} kg base body moves {motion}",
                system.base().mass
            ),
            result,
        )
    };
    report.animation = Some(animation);
    Ok(report)
}

/// The free-floating run: the satellite's centre of mass, then the arm from
/// its mount, every frame placed by the simulated base pose.
fn animation(system: &FreeFloatingModel, result: &StudyReport) -> CliResult<Animation> {
    let missing = |name: &str| CliError(format!("space study: no `{name}` series"));
    let joints = result
        .series("joints_free_floating")
        .ok_or_else(|| missing("joints_free_floating"))?;
    let translation = result
        .series("base_translation_free_floating")
        .ok_or_else(|| missing("base_translation_free_floating"))?;
    let rotation = result
        .series("base_rotation_free_floating")
        .ok_or_else(|| missing("base_rotation_free_floating"))?;
    let configurations: Vec<Vec<f64>> = (0..joints.x.len())
        .map(|k| joints.columns.iter().map(|(_, q)| q[k]).collect())
        .collect();
    let mut animation = Animation::from_configurations(system.arm(), &joints.x, &configurations)?;
    let body = system.base();
    let bases: Vec<Pose> = (0..animation.frames.len())
        .map(|k| {
            let value = |s: &armkit::study::Series, i: usize| s.columns[i].1[k];
            Pose::from_xyz_rpy(
                [
                    value(translation, 0),
                    value(translation, 1),
                    value(translation, 2),
                ],
                [value(rotation, 0), value(rotation, 1), value(rotation, 2)],
            )
        })
        .collect();
    // The arm's world frame is the base's mount frame, moving with the base.
    let worlds: Vec<Pose> = bases.iter().map(|base| *base * body.mount).collect();
    animation.place_frames(&worlds);
    animation.draw_base_body(body);
    for (frame, base) in animation.frames.iter_mut().zip(&bases) {
        let centre = base.rotation * body.com + base.translation;
        frame.insert(0, [centre.x, centre.y, centre.z]);
    }
    // The satellite's centre of mass, marked in the 3-D view at the start.
    if let Some(base) = bases.first() {
        let centre = base.rotation * body.com + base.translation;
        animation.markers.push(armkit_view::Marker {
            at: [centre.x, centre.y, centre.z],
            color: [0.2, 0.4, 0.8],
            label: "base centre of mass at t = 0".into(),
        });
    }
    Ok(animation)
}
