//! The samples and summary of a tracking run.

use super::run::{RateOutcome, Recorder, SampleState};
use super::status::TrackingStatus;
use crate::error::Result;
use crate::math::Pose;

/// One sample of a tracking run, at the start of a control period.
#[derive(Clone, Debug, PartialEq)]
pub struct TrackingSample {
    /// Time, s.
    pub time: f64,
    /// Joint positions at `time`, rad or m.
    pub q: Vec<f64>,
    /// Joint rates applied from `time` to the next sample (zero in the last
    /// sample), rad/s or m/s.
    pub joint_rates: Vec<f64>,
    /// Base pose, inertial frame (identity on a fixed base).
    pub base: Pose,
    /// End-effector pose, world (inertial) frame.
    pub end_effector: Pose,
    /// `|p_d - p|` at `time`, m.
    pub position_error: f64,
    /// Angle of `R_d R'` at `time`, rad.
    pub orientation_error: f64,
    /// Uniform velocity scale applied for the velocity limits, in `(0, 1]`.
    pub velocity_scale: f64,
    /// Number of joints locked in this step because they would have crossed
    /// a position limit.
    pub limit_locks: usize,
}

/// The result of a tracking run: every sample and the summary figures.
#[derive(Clone, Debug, PartialEq)]
pub struct TrackingReport {
    /// How the run ended.
    pub status: TrackingStatus,
    /// Every sample, the initial one first and the final state last.
    pub samples: Vec<TrackingSample>,
    /// Largest position error over the run, m.
    pub max_position_error: f64,
    /// Largest orientation error over the run, rad.
    pub max_orientation_error: f64,
    /// Position error at the end, m.
    pub final_position_error: f64,
    /// Orientation error at the end, rad.
    pub final_orientation_error: f64,
    /// Steps whose velocities were scaled down for the velocity limits.
    pub velocity_scaled_steps: usize,
    /// Steps in which a joint was locked at a position limit.
    pub limit_locked_steps: usize,
}

impl TrackingReport {
    /// The report of `samples` ending with `status`.
    pub fn new(status: TrackingStatus, samples: Vec<TrackingSample>) -> Self {
        let max = |f: fn(&TrackingSample) -> f64| samples.iter().map(f).fold(0.0, f64::max);
        let last = samples.last();
        TrackingReport {
            status,
            max_position_error: max(|s| s.position_error),
            max_orientation_error: max(|s| s.orientation_error),
            final_position_error: last.map_or(0.0, |s| s.position_error),
            final_orientation_error: last.map_or(0.0, |s| s.orientation_error),
            velocity_scaled_steps: samples.iter().filter(|s| s.velocity_scale < 1.0).count(),
            limit_locked_steps: samples.iter().filter(|s| s.limit_locks > 0).count(),
            samples,
        }
    }

    /// Largest `|q_dot_j|` over joints and samples, rad/s or m/s.
    pub fn peak_joint_rate(&self) -> f64 {
        self.samples
            .iter()
            .flat_map(|s| s.joint_rates.iter())
            .fold(0.0, |m: f64, r| m.max(r.abs()))
    }
}

/// A [`Recorder`] keeping every sample as a [`TrackingSample`].
#[derive(Clone, Debug, Default)]
pub struct SampleRecorder {
    /// The samples recorded so far.
    pub samples: Vec<TrackingSample>,
}

impl SampleRecorder {
    /// Room for `capacity` samples.
    pub fn with_capacity(capacity: usize) -> Self {
        SampleRecorder {
            samples: Vec::with_capacity(capacity),
        }
    }
}

impl Recorder for SampleRecorder {
    fn state(&mut self, sample: &SampleState<'_>) -> Result<()> {
        self.samples.push(TrackingSample {
            time: sample.time,
            q: sample.q.to_vec(),
            joint_rates: Vec::new(),
            base: sample.base,
            end_effector: *sample.end_effector,
            position_error: sample.position_error,
            orientation_error: sample.orientation_error,
            velocity_scale: 1.0,
            limit_locks: 0,
        });
        Ok(())
    }

    fn rates(&mut self, rates: &[f64], outcome: Option<&RateOutcome>) {
        if let Some(sample) = self.samples.last_mut() {
            sample.joint_rates = rates.to_vec();
            if let Some(RateOutcome::Rates {
                velocity_scale,
                limit_locks,
                ..
            }) = outcome
            {
                sample.velocity_scale = *velocity_scale;
                sample.limit_locks = *limit_locks;
            }
        }
    }
}
