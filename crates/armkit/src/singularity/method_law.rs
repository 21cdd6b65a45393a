//! The rate law of one [`Method`] on a [`PathTracker`]'s path, and how a
//! [`MethodRun`] records a run: what [`PathTracker::run`] hands to the
//! tracking loop ([`crate::tracking::track`]).

use super::avoidance::{Method, MethodRun, PathTracker, SingularRegion};
use super::detection::{detect, jacobian_determinant};
use super::plant::Plant;
use crate::error::Result;
use crate::tracking::{RateLaw, RateOutcome, Recorder, SampleState, Step};
use crate::trajectory::JointState;

/// The rate law of one [`Method`] on a [`PathTracker`]'s path: the plain,
/// damped or singularity-robust inverse, or seed 004's avoidance (plain
/// outside a singular region, the fitted joint motion across it).
pub(super) struct MethodLaw<'t, 'm> {
    pub(super) tracker: &'t PathTracker<'m>,
    pub(super) method: Method,
    /// The active region: its fit and the sample index where it ends.
    pub(super) active: Option<(crate::trajectory::Trajectory, usize)>,
    /// The rates applied in the last period.
    pub(super) previous_rates: Vec<f64>,
    /// The plain rates' joint steps, for detection.
    pub(super) candidate: Vec<f64>,
    pub(super) fit_state: JointState,
    pub(super) regions: Vec<SingularRegion>,
}

impl RateLaw<Plant<'_>> for MethodLaw<'_, '_> {
    fn rates(
        &mut self,
        plant: &mut Plant<'_>,
        step: &Step<'_>,
        rates: &mut [f64],
    ) -> Result<RateOutcome> {
        let (i, t, h) = (step.index, step.time, step.dt);
        if self.active.as_ref().is_some_and(|(_, end)| i >= *end) {
            self.active = None;
        }
        if self.active.is_none() {
            let solved = self.tracker.rates(&self.method, plant, &step.twist, rates);
            match self.method {
                Method::Avoidance { k } => {
                    for (c, r) in self.candidate.iter_mut().zip(rates.iter()) {
                        *c = if solved { r * h } else { f64::INFINITY };
                    }
                    let detection = detect(
                        plant.jacobian(),
                        &self.candidate,
                        &self.tracker.options.detection,
                    )?;
                    if let Some(trigger) = detection.trigger {
                        let (fit, end, region) =
                            self.tracker
                                .plan_region(plant, i, k, trigger, &self.previous_rates)?;
                        self.regions.push(region);
                        self.active = Some((fit, end));
                    } else if !solved {
                        return Ok(RateOutcome::Singular);
                    }
                }
                _ if !solved => return Ok(RateOutcome::Singular),
                _ => {}
            }
        }
        let planned = if let Some((fit, _)) = &self.active {
            fit.sample_into(t + h, &mut self.fit_state)?;
            for ((rate, target), q) in rates
                .iter_mut()
                .zip(&self.fit_state.position)
                .zip(plant.q())
            {
                *rate = (target - q) / h;
            }
            true
        } else {
            false
        };
        self.previous_rates.copy_from_slice(rates);
        Ok(RateOutcome::Rates {
            velocity_scale: 1.0,
            limit_locks: 0,
            planned,
            stopped_at: None,
        })
    }
}

/// A [`MethodRun`] records its series column by column (sized once: a
/// period allocates nothing).
impl Recorder for MethodRun {
    fn state(&mut self, sample: &SampleState<'_>) -> Result<()> {
        self.time.push(sample.time);
        for (series, q) in self.joint_positions.iter_mut().zip(sample.q) {
            series.push(*q);
        }
        self.position_error.push(sample.position_error);
        self.orientation_error.push(sample.orientation_error);
        self.determinant.push(jacobian_determinant(sample.jacobian));
        let base = sample.base.translation;
        self.base_position.push([base.x, base.y, base.z]);
        Ok(())
    }

    fn rates(&mut self, rates: &[f64], outcome: Option<&RateOutcome>) {
        for (series, r) in self.joint_rates.iter_mut().zip(rates) {
            series.push(*r);
        }
        let planned = matches!(outcome, Some(RateOutcome::Rates { planned: true, .. }));
        self.in_region.push(planned);
    }
}
