//! `armkit reach`: a reachability and capability map of one robot, built on
//! every core, summarized, and written as NumPy `.npz` with an SVG of the
//! capability index's slices.
//!
//! Positions in the world frame, metres (see `armkit::reach`).

mod npz;
mod placement;
mod slices;

use std::time::Instant;

use armkit::reach::{self, Boundary, Builder, FloorGrid, MapSpec, MapTarget, ReachMap};
use clap::{Args, ValueEnum};
use indicatif::{ProgressBar, ProgressStyle};

use crate::common::{print_json, CliError, CliResult, Outcome, RobotArgs};
use npz::Array;

/// Orientations per cell when `--orientations` is not given.
const DEFAULT_ORIENTATIONS: usize = 200;

/// Which builder decides the bins.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum BuilderArg {
    /// Inverse kinematics at every (cell centre, orientation): exact at the centres.
    Ik,
    /// Forward kinematics of uniform random configurations, binned (RM4D's way).
    FkSamples,
}

/// Arguments of `armkit reach`.
#[derive(Args, Debug)]
pub struct ReachArgs {
    #[command(flatten)]
    pub robot: RobotArgs,
    /// Edge of a cubic position cell, m.
    #[arg(long, default_value_t = 0.05)]
    pub resolution: f64,
    /// Tool orientations per cell (approach directions x rolls; directions
    /// only when the last joint turns the tool fully about its z axis, or
    /// at least 300 degrees on an arm with more than six joints);
    /// default 200. Not for arms with fewer than six joints, whose maps
    /// are position-only.
    #[arg(long)]
    pub orientations: Option<usize>,
    /// How the bins are decided.
    #[arg(long, value_enum, default_value_t = BuilderArg::Ik)]
    pub builder: BuilderArg,
    /// Configurations drawn by the fk-samples builder.
    #[arg(long, default_value_t = 1_000_000)]
    pub samples: u64,
    /// Seed of the fk-samples builder's generator.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// With fk-samples: also build the IK map and report the samples'
    /// coverage of its reachable bins.
    #[arg(long)]
    pub coverage: bool,
    /// Worker threads (default: every core).
    #[arg(long)]
    pub threads: Option<usize>,
    /// Write the map as NumPy .npz.
    #[arg(long, value_name = "PATH")]
    pub out: Option<std::path::PathBuf>,
    /// Write the capability index's slices through the reach centre as SVG.
    #[arg(long, value_name = "PATH")]
    pub svg: Option<std::path::PathBuf>,
    /// Inverse reachability: a JSON list of task poses (world frame; 4 x 4
    /// transforms or `[x, y, z, qw, qx, qy, qz]`, m); prints the base
    /// placements on the floor grid from which every pose is reachable.
    #[arg(long, value_name = "PATH")]
    pub base_placements: Option<std::path::PathBuf>,
    /// Floor grid's x range of base positions, m.
    #[arg(long, num_args = 2, value_names = ["LO", "HI"], allow_negative_numbers = true, default_values_t = [-1.0, 1.0])]
    pub floor_x: Vec<f64>,
    /// Floor grid's y range of base positions, m.
    #[arg(long, num_args = 2, value_names = ["LO", "HI"], allow_negative_numbers = true, default_values_t = [-1.0, 1.0])]
    pub floor_y: Vec<f64>,
    /// Floor grid's step along x and y, m.
    #[arg(long, default_value_t = 0.1)]
    pub floor_step: f64,
    /// Height of the floor plane (the base frame's origin), m.
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub floor_z: f64,
    /// Base headings sampled in [0, 2 pi).
    #[arg(long, default_value_t = 1)]
    pub yaws: usize,
    /// Print the summary as JSON.
    #[arg(long)]
    pub json: bool,
}

/// A built map with its wall-clock time, s.
fn timed_build(
    model: &armkit::Model,
    spec: &MapSpec,
    threads: usize,
    show: bool,
) -> CliResult<(ReachMap, f64)> {
    let bar = if show {
        ProgressBar::new(0)
    } else {
        ProgressBar::hidden()
    };
    bar.set_style(
        ProgressStyle::with_template(
            "{prefix} [{bar:40}] {pos}/{len} chunks {elapsed_precise} eta {eta}",
        )
        .map_err(|e| CliError(format!("progress bar: {e}")))?
        .progress_chars("=> "),
    );
    bar.set_prefix(format!("{} reach", model.name()));
    let began = Instant::now();
    let map = reach::build(model, spec, threads, &mut |done, total| {
        bar.set_length(total as u64);
        bar.set_position(done as u64);
    })?;
    bar.finish_and_clear();
    Ok((map, began.elapsed().as_secs_f64()))
}

/// Runs `armkit reach`.
pub fn run(args: &ReachArgs) -> CliResult<Outcome> {
    let model = args.robot.load()?;
    let builder = match args.builder {
        BuilderArg::Ik => Builder::InverseKinematics,
        BuilderArg::FkSamples => Builder::ForwardSampling {
            samples: args.samples,
            seed: args.seed,
        },
    };
    if args.threads == Some(0) {
        return Err(CliError("--threads must be at least 1".into()));
    }
    let threads = args
        .threads
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    let spec = MapSpec::for_model(
        &model,
        args.resolution,
        args.orientations.unwrap_or(DEFAULT_ORIENTATIONS),
        builder,
    );
    if let (MapTarget::Position, Some(n)) = (spec.target, args.orientations) {
        return Err(CliError(format!(
            "--orientations {n}: `{}` has {} joints, fewer than the six a tool pose needs, so it cannot hold an arbitrary tool orientation and its map is position-only (a cell is reachable when some configuration puts the tool point in it); drop --orientations",
            model.name(),
            model.dof()
        )));
    }
    let (map, seconds) = timed_build(&model, &spec, threads, !args.json)?;
    let coverage = if args.coverage && args.builder == BuilderArg::FkSamples {
        let ik_spec = MapSpec {
            builder: Builder::InverseKinematics,
            ..spec.clone()
        };
        let (ik_map, _) = timed_build(&model, &ik_spec, threads, !args.json)?;
        Some(map.coverage_of(&ik_map)?)
    } else {
        None
    };
    if let Some(path) = &args.out {
        std::fs::write(path, npz::npz(&arrays(&map))?)
            .map_err(|e| CliError(format!("cannot write {}: {e}", path.display())))?;
    }
    if let Some(path) = &args.svg {
        std::fs::write(path, slices::capability_svg(&map, model.name())?)
            .map_err(|e| CliError(format!("cannot write {}: {e}", path.display())))?;
    }
    let placements = match &args.base_placements {
        Some(path) => {
            let floor = FloorGrid {
                x: [args.floor_x[0], args.floor_x[1]],
                y: [args.floor_y[0], args.floor_y[1]],
                step: args.floor_step,
                z: args.floor_z,
                yaws: args.yaws,
            };
            Some(placement::placements(&map, path, &floor)?)
        }
        None => None,
    };
    let layout = map.layout();
    let [nx, ny, nz] = layout.dims();
    let per_second = map.calls() as f64 / seconds.max(1e-9);
    let calls_name = match args.builder {
        BuilderArg::Ik => "ik_calls",
        BuilderArg::FkSamples => "fk_samples",
    };
    if args.json {
        print_json(&serde_json::json!({
            "robot": model.name(),
            "builder": spec.builder,
            "resolution": spec.resolution,
            "dims": [nx, ny, nz],
            "cells": layout.cell_count(),
            "approach_directions": spec.approach_directions,
            "rolls": spec.rolls,
            "orientations": layout.orientation_count(),
            "target": spec.target,
            "boundary": spec.boundary,
            "reachable_cells": map.reachable_cells(),
            "reachable_bins": map.reachable_bins(),
            "reachable_volume": map.reachable_volume(),
            "mean_capability": mean_capability(&map),
            "build_seconds": seconds,
            calls_name: map.calls(),
            "calls_per_second": per_second,
            "threads": threads,
            "coverage": coverage,
            "base_placements": placements.as_deref().map(placement::json),
        }))?;
    } else {
        let orientations = match spec.target {
            MapTarget::Position => "position only".to_string(),
            MapTarget::Pose => format!(
                "{} orientations ({} directions x {} rolls)",
                layout.orientation_count(),
                spec.approach_directions,
                spec.rolls
            ),
        };
        let boundary = match spec.boundary {
            Boundary::Cells => "the cells' boundary".to_string(),
            Boundary::Bisection { steps } => format!("boundary refined by {steps} bisection steps"),
        };
        println!(
            "{}: {nx} x {ny} x {nz} cells of {} m, {orientations}, builder {}, {boundary}",
            model.name(),
            spec.resolution,
            match args.builder {
                BuilderArg::Ik => "ik",
                BuilderArg::FkSamples => "fk-samples",
            }
        );
        println!(
            "reachable: {} cells, {:.4} m^3, {} bins; mean capability of reachable cells {:.4}",
            map.reachable_cells(),
            map.reachable_volume(),
            map.reachable_bins(),
            mean_capability(&map)
        );
        println!(
            "build: {seconds:.2} s on {threads} threads, {} {} ({per_second:.0} per second)",
            map.calls(),
            calls_name.replace('_', " ")
        );
        if let Some(c) = coverage {
            println!("coverage of the IK map's reachable bins: {:.4}", c);
        }
        if let Some(found) = &placements {
            placement::print(found);
        }
    }
    Ok(Outcome::Success)
}

/// Mean capability index over the reachable cells (0 if none).
fn mean_capability(map: &ReachMap) -> f64 {
    let reachable: Vec<f64> = map
        .capability()
        .iter()
        .copied()
        .filter(|&c| c > 0.0)
        .collect();
    if reachable.is_empty() {
        0.0
    } else {
        reachable.iter().sum::<f64>() / reachable.len() as f64
    }
}

/// The map's arrays for the `.npz`: per bin `(nx, ny, nz, orientations)`
/// (`boundary`: the signed distance to the boundary in 1/64 of a cell),
/// per cell `(nx, ny, nz)`, the layout (origin of the grid's lower
/// corner, m; resolution, m; orientations as rotation matrices) and the
/// spec as JSON (`spec`, a string).
fn arrays(map: &ReachMap) -> Vec<Array> {
    let layout = map.layout();
    let [nx, ny, nz] = layout.dims();
    let o = layout.orientation_count();
    let rotations: Vec<f64> = (0..o)
        .flat_map(|k| {
            let m = layout.orientation(k).into_inner();
            // Row-major 3 x 3 for NumPy.
            (0..9).map(move |i| m[(i / 3, i % 3)])
        })
        .collect();
    let directions: Vec<f64> = layout.directions().iter().flatten().copied().collect();
    let spec = serde_json::to_string(layout.spec()).unwrap_or_default();
    vec![
        Array::u8("reachable", vec![nx, ny, nz, o], map.reachable()),
        Array::u8("solutions", vec![nx, ny, nz, o], map.solutions()),
        Array::f64("capability", vec![nx, ny, nz], map.capability()),
        Array::f64("manipulability", vec![nx, ny, nz], map.manipulability()),
        Array::f64("origin", vec![3], &layout.origin()),
        Array::f64("resolution", vec![], &[layout.resolution()]),
        Array::f64("orientations", vec![o, 3, 3], &rotations),
        Array::f64(
            "directions",
            vec![layout.directions().len(), 3],
            &directions,
        ),
        Array::i64("rolls", vec![], &[layout.spec().rolls as i64]),
        Array::i8("boundary", vec![nx, ny, nz, o], map.boundary()),
        Array::text("spec", &spec),
    ]
}
