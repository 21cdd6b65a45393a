//! Comparing the methods on one path (seed 004, Table 1 and Figs 5-8):
//! plain resolved rate, the avoidance for several `k`, and the three damped
//! baselines (DLS, SRI and the paper's reference [9], singularity separation
//! with a damped reciprocal), with a plain-text table.

use super::avoidance::PathTracker;
use super::detection::DetectionOptions;
use super::method::{Method, MethodRun};
use crate::error::{Error, Result};
use crate::ik::{ChiaveriniFilter, DampedReciprocal, NakamuraDamping};

impl PathTracker<'_> {
    /// Runs plain tracking, the avoidance method with `k` = `ks[0]`, the
    /// three baselines (the separation only on a 6-joint arm), and the avoidance method for every `k` of `ks` (the
    /// error against `k`, seed 004 Figs 7-8), all from the same start.
    ///
    /// Errors: an empty `ks`, a `k` of 0, bad baseline parameters, and the
    /// errors of [`PathTracker::run`].
    pub fn compare(&self, baselines: &Baselines, ks: &[usize]) -> Result<Comparison> {
        let Some(&first) = ks.first() else {
            return Err(Error::invalid_argument(
                "ks",
                "give at least one knot stride k",
            ));
        };
        for &k in ks {
            Method::Avoidance { k }.validate()?;
        }
        baselines.nakamura.validate()?;
        baselines.chiaverini.validate()?;
        baselines.reciprocal.validate()?;
        let mut k_sweep = Vec::with_capacity(ks.len());
        for &k in ks {
            k_sweep.push(self.run(&Method::Avoidance { k })?);
        }
        let avoidance = match k_sweep
            .iter()
            .find(|r| r.method == Method::Avoidance { k: first })
        {
            Some(run) => run.clone(),
            None => self.run(&Method::Avoidance { k: first })?,
        };
        Ok(Comparison {
            plain: self.run(&Method::Plain)?,
            avoidance,
            damped_least_squares: self.run(&Method::DampedLeastSquares(baselines.nakamura))?,
            singularity_robust: self.run(&Method::SingularityRobust(baselines.chiaverini))?,
            separation: match self.manipulator().dof() {
                6 => Some(self.run(&Method::SeparatedDampedReciprocal(baselines.reciprocal))?),
                _ => None,
            },
            k_sweep,
        })
    }
}

/// Parameters of the three baselines of [`PathTracker::compare`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Baselines {
    /// Damped least squares with Nakamura's adaptive damping.
    pub nakamura: NakamuraDamping,
    /// Chiaverini's singularity-robust inverse.
    pub chiaverini: ChiaveriniFilter,
    /// The damped reciprocal of the singularity separation (seed 004's
    /// reference [9]).
    pub reciprocal: DampedReciprocal,
}

impl Baselines {
    /// Baselines damping the same region as the detection: Nakamura's
    /// threshold `w_0` = the determinant threshold (`|det J|` is the
    /// manipulability of a square Jacobian), `lambda_0` = 0.05; Chiaverini's
    /// defaults (`epsilon` = 0.05, `lambda_max` = 0.05, `beta` = 1e-4); the
    /// damped reciprocal's defaults (`epsilon` = 0.05, `lambda_max` = 0.05:
    /// the same damping law as SRI's, on the wrist block alone).
    /// ([`NakamuraDamping::default`]'s threshold, 1e-3 m^3, would start
    /// damping only at a 4 times smaller `|det J|`, inside the region.)
    pub fn for_detection(detection: &DetectionOptions) -> Baselines {
        Baselines {
            nakamura: NakamuraDamping {
                threshold: detection.determinant_threshold,
                max_damping: 0.05,
            },
            chiaverini: ChiaveriniFilter::default(),
            reciprocal: DampedReciprocal::default(),
        }
    }
}

/// The runs of [`PathTracker::compare`].
#[derive(Clone, Debug, PartialEq)]
pub struct Comparison {
    /// Plain resolved rate.
    pub plain: MethodRun,
    /// Seed 004's avoidance with the first `k`.
    pub avoidance: MethodRun,
    /// Damped least squares (Nakamura).
    pub damped_least_squares: MethodRun,
    /// Singularity-robust inverse (Chiaverini).
    pub singularity_robust: MethodRun,
    /// Singularity separation with a damped reciprocal (seed 004's
    /// reference [9]); `None` on an arm without 6 joints.
    pub separation: Option<MethodRun>,
    /// Seed 004's avoidance for each `k` given.
    pub k_sweep: Vec<MethodRun>,
}

impl Comparison {
    /// The methods of the table, in order: plain, avoidance, dls, sri,
    /// then separation when it ran.
    pub fn methods(&self) -> Vec<&MethodRun> {
        [
            &self.plain,
            &self.avoidance,
            &self.damped_least_squares,
            &self.singularity_robust,
        ]
        .into_iter()
        .chain(&self.separation)
        .collect()
    }
}

/// A plain-text table: one row per run (plain, each `k`, DLS, SRI,
/// separation) with the
/// peak joint rate (rad/s), the maximum and final position (m) and
/// orientation (rad) errors, the time in the singular region (s) and the IK
/// solves; then one line per singular region of the avoidance runs.
impl std::fmt::Display for Comparison {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        writeln!(
            f,
            "{:>14} {:>10} {:>10} {:>10} {:>10} {:>10} {:>8} {:>6}",
            "method",
            "peak rad/s",
            "max pos m",
            "max ori",
            "final pos",
            "final ori",
            "region s",
            "IK"
        )?;
        let rows = std::iter::once(&self.plain)
            .chain(&self.k_sweep)
            .chain([&self.damped_least_squares, &self.singularity_robust])
            .chain(&self.separation);
        for run in rows {
            let s = &run.summary;
            writeln!(
                f,
                "{:>14} {:>10.4} {:>10.3e} {:>10.3e} {:>10.3e} {:>10.3e} {:>8.2} {:>6}",
                run.method.label(),
                s.peak_joint_rate,
                s.max_position_error,
                s.max_orientation_error,
                s.final_position_error,
                s.final_orientation_error,
                s.time_in_singular_region,
                s.ik_solves
            )?;
        }
        for run in &self.k_sweep {
            for r in &run.regions {
                writeln!(
                    f,
                    "{}: region {:.2} s .. {:.2} s ({}), {} knots, {} IK iterations, {} least-squares knots",
                    run.method.label(),
                    r.start_time,
                    r.end_time,
                    r.trigger.as_str(),
                    r.knot_times.len(),
                    r.ik_iterations,
                    r.bounded_knots
                )?;
            }
        }
        Ok(())
    }
}
