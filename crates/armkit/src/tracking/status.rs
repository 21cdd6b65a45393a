//! How a tracking run ended.

use std::fmt;

/// How a tracking run ended: the one status of every velocity-level tracker
/// ([`super::track`], [`crate::redundancy::ResolvedRateTracker`],
/// [`crate::space::track_pose_path`], [`crate::singularity::PathTracker`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TrackingStatus {
    /// The whole path was run; see the report's errors for how well.
    Completed,
    /// A joint position limit stopped the motion: with the joints at their
    /// limits locked, the others could not realise the twist. The last step
    /// stops short of the limit.
    StoppedAtJointLimit {
        /// 0-based joint index.
        joint: usize,
        /// Time of the last step, s.
        time: f64,
    },
    /// The rate law met a numerically singular Jacobian (use damping, or a
    /// singularity-robust law); the run stopped at `time`.
    Singular {
        /// Time of the step that could not be solved, s.
        time: f64,
    },
}

impl TrackingStatus {
    /// `completed`, `stopped at joint limit` or `singular`.
    pub fn as_str(&self) -> &'static str {
        match self {
            TrackingStatus::Completed => "completed",
            TrackingStatus::StoppedAtJointLimit { .. } => "stopped at joint limit",
            TrackingStatus::Singular { .. } => "singular",
        }
    }

    /// True for [`TrackingStatus::Completed`].
    pub fn is_completed(&self) -> bool {
        matches!(self, TrackingStatus::Completed)
    }
}

/// `completed`; `stopped: joint 3 at its limit at 1.20 s` (1-based joint);
/// `singular at 0.50 s`.
impl fmt::Display for TrackingStatus {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            TrackingStatus::Completed => f.write_str("completed"),
            TrackingStatus::StoppedAtJointLimit { joint, time } => {
                write!(
                    f,
                    "stopped: joint {} at its limit at {time:.2} s",
                    joint + 1
                )
            }
            TrackingStatus::Singular { time } => write!(f, "singular at {time:.2} s"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn statuses_print_what_happened() {
        assert_eq!(TrackingStatus::Completed.to_string(), "completed");
        let stopped = TrackingStatus::StoppedAtJointLimit {
            joint: 2,
            time: 1.2,
        };
        assert_eq!(
            stopped.to_string(),
            "stopped: joint 3 at its limit at 1.20 s"
        );
        assert_eq!(stopped.as_str(), "stopped at joint limit");
        assert_eq!(
            TrackingStatus::Singular { time: 0.5 }.to_string(),
            "singular at 0.50 s"
        );
    }
}
