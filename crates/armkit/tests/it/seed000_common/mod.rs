//! Seed 000's examples (sec 5) built from the public planner API, and a
//! closed-loop runner with a chosen [`PlantModel`], for the seed 000 tests.
//!
//! The set-up mirrors the demo's (start, targets, priorities, `N = 10`,
//! `M = 1`, `Q = 10`/200 on position, the default velocity term, no goal
//! posture), written out here so that these tests do not depend on where
//! the demo's study code lives.

#![allow(dead_code)]

use armkit::math::{Matrix3, Pose, Vector3};
use armkit::model::JointKind;
use armkit::mpc::{MpcOptions, MpcPlanner, Plant, PlantModel, ReachAid, TaskWeights};

/// The demo's start for every example: inside every limit, the hand at the
/// paper's `X0 = [2.00, 2.38, 5.00]` m.
pub const START: [f64; 9] = [
    2.0,
    0.89,
    0.76,
    std::f64::consts::FRAC_PI_2,
    0.5,
    0.5,
    0.0,
    0.5,
    0.0,
];

/// The examples.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Example {
    /// Example 1: to `[4, 1, 6]`, `R = 100/10/1` (rail, beam joints, rotary).
    LargeMove,
    /// Example 2 as the demo runs it: to `[2, 1.8, 4.5]`, `R = 1e5/1e4/1`.
    SmallMove,
    /// Example 2 with the paper's `R = 100/10/1`.
    SmallMovePaperWeights,
    /// Example 3: to `[2, 1.8, 4.5]`, every `R = 10`.
    EqualWeights,
}

impl Example {
    pub fn target(self) -> Pose {
        let p = match self {
            Example::LargeMove => Vector3::new(4.0, 1.0, 6.0),
            _ => Vector3::new(2.0, 1.8, 4.5),
        };
        Pose::new(Matrix3::identity(), p)
    }

    pub fn increment_weights(self) -> Vec<f64> {
        let (rail, beam, rotary) = match self {
            Example::LargeMove | Example::SmallMovePaperWeights => (100.0, 10.0, 1.0),
            Example::SmallMove => (1e5, 1e4, 1.0),
            Example::EqualWeights => (10.0, 10.0, 10.0),
        };
        let mut r = vec![rotary; 9];
        r[0] = rail;
        r[1] = beam;
        r[2] = beam;
        r
    }

    pub fn options(self) -> MpcOptions {
        MpcOptions {
            horizon: 10,
            control_horizon: 1,
            task_weights: TaskWeights::position_only(10.0, 200.0),
            increment_weights: Some(self.increment_weights()),
            reach: ReachAid::Off,
            ..MpcOptions::default()
        }
    }
}

/// A recorded run: per sample the joint positions, the commanded
/// velocities (applied from that sample on) and the hand's distance to the
/// target.
pub struct Run {
    pub sample_time: f64,
    pub q: Vec<Vec<f64>>,
    pub velocity: Vec<Vec<f64>>,
    pub error: Vec<f64>,
    pub prismatic: Vec<usize>,
    /// First step at the target (1e-4 m) and at rest (every |v| <= 1e-3),
    /// the demo's convergence test.
    pub converged_at: Option<usize>,
}

/// Runs `example` for `steps` samples on `plant` (no early stop).
pub fn run(example: Example, plant: PlantModel, steps: usize) -> Run {
    let model = armkit::robots::gantry9_flex().unwrap();
    let kinds: Vec<JointKind> = model.joints().iter().map(|j| j.kind).collect();
    let mut planner = MpcPlanner::new(&model, example.options()).unwrap();
    planner.set_target(&example.target()).unwrap();
    let t = planner.options().sample_time;
    let mut plant = Plant::new(plant, &kinds, &START).unwrap();
    let mut q = START.to_vec();
    let mut out = Run {
        sample_time: t,
        q: Vec::with_capacity(steps),
        velocity: Vec::with_capacity(steps),
        error: Vec::with_capacity(steps),
        prismatic: (0..9)
            .filter(|&j| kinds[j] == JointKind::Prismatic)
            .collect(),
        converged_at: None,
    };
    for k in 0..steps {
        let report = planner.step(&q).unwrap();
        let v = report.velocity.clone();
        if out.converged_at.is_none()
            && report.position_error <= 1e-4
            && v.iter().all(|x| x.abs() <= 1e-3)
        {
            out.converged_at = Some(k);
        }
        out.q.push(q.clone());
        out.error.push(report.position_error);
        out.velocity.push(v.clone());
        plant.advance(&mut q, &v, t).unwrap();
    }
    out
}

impl Run {
    /// First sample whose error is at most `tolerance` m.
    pub fn first_within(&self, tolerance: f64) -> Option<usize> {
        self.error.iter().position(|&e| e <= tolerance)
    }

    /// Sign changes of joint `j`'s commanded velocity from sample `from`
    /// on, counting only commands of magnitude above `floor` m/s.
    pub fn sign_changes(&self, j: usize, from: usize, floor: f64) -> usize {
        let signs: Vec<f64> = self.velocity[from..]
            .iter()
            .map(|v| v[j])
            .filter(|v| v.abs() > floor)
            .map(f64::signum)
            .collect();
        signs.windows(2).filter(|w| w[0] != w[1]).count()
    }

    /// Largest error from sample `from` on, m.
    pub fn max_error_from(&self, from: usize) -> f64 {
        self.error[from..].iter().copied().fold(0.0, f64::max)
    }

    /// Largest |v| of joint `j` from sample `from` on.
    pub fn max_speed_from(&self, j: usize, from: usize) -> f64 {
        self.velocity[from..]
            .iter()
            .map(|v| v[j].abs())
            .fold(0.0, f64::max)
    }

    /// Largest |v| of joint `j` over the run.
    pub fn peak_speed(&self, j: usize) -> f64 {
        self.max_speed_from(j, 0)
    }
}
