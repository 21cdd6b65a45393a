//! The methods a scenario can run, one table each, and their options.

use armkit::Model;
use serde::Deserialize;
use toml::Spanned;

use super::Locator;
use crate::commands::beam::{self, LoadArgs};
use crate::common::CliResult;
use crate::report::Report;

/// `[beam]`: seed 000's flexible beam, Table 1 and the rigid model's error.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BeamSpec {
    /// Mass per carriage, kg (default 400).
    mass: Option<f64>,
    /// Gravity, m/s^2 (default 10, which reproduces Table 1).
    gravity: Option<f64>,
    /// Carriage positions in the error sweep (default 51).
    samples: Option<usize>,
}

/// The method tables of a scenario file; exactly one may be present.
pub struct MethodTables {
    /// `[beam]`.
    pub beam: Option<Spanned<BeamSpec>>,
}

/// A scenario's method with its options.
#[derive(Debug)]
pub enum Method {
    /// Seed 000's beam.
    Beam(BeamSpec),
}

const METHOD_NAMES: &str = "[beam]";

impl Method {
    /// The one method given, or an error located at the second one.
    pub fn from_tables(tables: MethodTables, locator: &Locator) -> CliResult<Method> {
        let mut found: Vec<(std::ops::Range<usize>, Method)> = Vec::new();
        if let Some(spec) = tables.beam {
            found.push((spec.span(), Method::Beam(spec.into_inner())));
        }
        match found.len() {
            1 => Ok(found.remove(0).1),
            0 => Err(locator.error(
                0..0,
                format!("no method table: expected exactly one of {METHOD_NAMES}"),
            )),
            _ => Err(locator.error(
                found[1].0.clone(),
                format!("a second method table: expected exactly one of {METHOD_NAMES}"),
            )),
        }
    }

    /// Runs the method on `robot` (when it takes one).
    pub fn run(&self, _robot: Option<&Model>) -> CliResult<Report> {
        match self {
            Method::Beam(spec) => {
                let defaults = LoadArgs {
                    mass: armkit::beam::SEED000_CARRIAGE_MASS,
                    gravity: armkit::beam::SEED000_GRAVITY,
                };
                let load = LoadArgs {
                    mass: spec.mass.unwrap_or(defaults.mass),
                    gravity: spec.gravity.unwrap_or(defaults.gravity),
                };
                beam::report(load, spec.samples.unwrap_or(51))
            }
        }
    }
}
